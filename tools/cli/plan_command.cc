// `sacfuse plan CONFIG`: the geo-tiles of a job, the views and depth windows each needs, and an estimate of the
// memory each tile's rasters take; prints a table and writes <output.dir>/plan.json (shared by every worker).
// --list prints only the ids of the tiles with views, one per line; --json prints plan.json itself.
#include <cstdio>
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "config/job_config.h"
#include "core/error.h"
#include "io/input_file.h"
#include "jobs/output_lock.h"
#include "jobs/tile_queue.h"
#include "tiles/tile_plan.h"
#include "tools/cli/cli_support.h"
#include "tools/cli/commands.h"
#include "tools/cli/config_args.h"

namespace sacfuse::cli {
namespace {

void PrintPlanTable(const TilePlan& plan, std::ostream& out) {
  char line[256];
  std::snprintf(line, sizeof(line), "%zu tiles (%d x %d), tile %.1f m, halo %.1f m, z [%.1f, %.1f] m (%s)\n",
                plan.tiles.size(), plan.grid.num_x(), plan.grid.num_y(), plan.options.tile_size_m,
                plan.options.halo_m, plan.z_min_m, plan.z_max_m, plan.z_source.c_str());
  out << line;
  std::snprintf(line, sizeof(line), "%-10s %14s %14s %14s %14s %6s %12s %10s\n", "tile", "core x min", "core y min",
                "core x max", "core y max", "views", "window px", "mem MiB");
  out << line;
  for (const PlannedTile& t : plan.tiles) {
    std::snprintf(line, sizeof(line), "%-10s %14.2f %14.2f %14.2f %14.2f %6zu %12llu %10.1f\n", t.id.c_str(),
                  t.core.min.x(), t.core.min.y(), t.core.max.x(), t.core.max.y(), t.views.size(),
                  static_cast<unsigned long long>(t.window_pixels), t.memory_bytes / (1024.0 * 1024.0));
    out << line;
  }
}

}  // namespace

void AddPlanCommand(CLI::App& app, int* exit_code) {
  auto config_args = std::make_shared<ConfigArgs>();
  auto list = std::make_shared<bool>(false);
  auto json = std::make_shared<bool>(false);
  auto* cmd = app.add_subcommand("plan", "Plan the geo-tiles of a job: views and depth windows per tile, memory "
                                         "estimate; prints a table and writes DIR/plan.json");
  AddConfigOptions(cmd, config_args.get(), "YAML config (the tiling.* keys; see sacfuse run --print-defaults)");
  auto* list_flag = cmd->add_flag("--list", *list, "Print only the ids of the tiles with views, one per line (for "
                                                   "GNU parallel or SLURM arrays driving `sacfuse tile`)");
  cmd->add_flag("--json", *json, "Print DIR/plan.json instead of the table (the schema below)")->excludes(list_flag);
  cmd->footer(
      "plan.json (printed by --json, shared by every `sacfuse tile` worker): an object with version (the sacfuse "
      "that wrote it), tile_size_m, halo_m, window_margin_px, z_range_m [min, max], z_source, area [min_x, min_y, "
      "max_x, max_y], grid [columns, rows], bytes_per_window_pixel, config_hash, inputs_hash and tiles: a list of "
      "{id, core and halo (boxes as area), views: [{view (index), name, window {row_begin, row_end, col_begin, "
      "col_end} in depth pixels}], window_pixels, memory_bytes}. Coordinates in metres of the project CRS.");
  cmd->callback([config_args, list, json, exit_code] {
    SetupLogging(*list || *json ? "warn" : "info");
    *exit_code = RunGuarded([&] {
      const JobConfig config = config_args->Load();
      const OutputWorkerLock lock(config);  // writes DIR/plan.json beside a run by design (jobs/output_lock.h)
      std::string plan_path;
      const TilePlan plan = PlanJob(config, &plan_path);
      if (*list) {
        for (const PlannedTile& t : plan.tiles) {
          if (!t.views.empty()) std::cout << t.id << "\n";
        }
        return kExitOk;
      }
      if (*json) {
        std::cout << OpenInputStream(plan_path, "plan").rdbuf();
        return kExitOk;
      }
      PrintPlanTable(plan, std::cout);
      std::cout << "plan: " << plan_path << "\n";
      return kExitOk;
    });
  });
}

}  // namespace sacfuse::cli
