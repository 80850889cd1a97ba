// `sacfuse dsm CLOUD.las|laz|ply --cell M --out DSM.tif|DSM.vrt`: the DSM of any cloud by exactly the rule and the
// assembly a run uses (core/dsm_rule.h, io/dsm_file.h), so a user (and the benchmark) can grid another tool's
// cloud like sacfuse's own. DSM.tif: one Cloud Optimized GeoTIFF; DSM.vrt: COG blocks in the folder DSM/ beside it
// and a VRT over them (for extents too large for one file).
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "config/job_config.h"
#include "core/error.h"
#include "io/crs_wkt.h"
#include "io/dsm_file.h"
#include "io/point_cloud_file.h"
#include "io/resource_usage.h"
#include "jobs/dsm_product.h"
#include "tiles/memory_model.h"
#include "tools/cli/cli_support.h"
#include "tools/cli/commands.h"

namespace sacfuse::cli {
namespace {

namespace fs = std::filesystem;

struct DsmArgs {
  std::string cloud;
  double cell_m = 0.0;
  std::string out;
  std::string crs;
  std::vector<double> offset;  // X,Y,Z added to every point
  std::vector<double> extent;  // XMIN,YMIN,XMAX,YMAX
  double max_hole_m = OutputOptions{}.dsm_max_hole_m;
  double quantile = DsmRule{}.quantile;
  double memory_gb = ResourceOptions{}.memory_gb;
};

void CheckArgs(const DsmArgs& a) {
  if (!(a.cell_m > 0) || !std::isfinite(a.cell_m)) throw ConfigError("--cell " + std::to_string(a.cell_m) + ": must be > 0");
  if (!(a.max_hole_m >= 0)) throw ConfigError("--max-hole: must be >= 0");
  if (!(a.quantile >= 0 && a.quantile <= 1)) throw ConfigError("--quantile: must be in [0, 1]");
  if (!(a.memory_gb > 0)) throw ConfigError("--memory-gb: must be > 0");
  if (!a.offset.empty() && a.offset.size() != 3) throw ConfigError("--offset: give X,Y,Z (three numbers)");
  if (!a.extent.empty() && (a.extent.size() != 4 || !(a.extent[0] < a.extent[2]) || !(a.extent[1] < a.extent[3]))) {
    throw ConfigError("--extent: give XMIN,YMIN,XMAX,YMAX with XMIN < XMAX and YMIN < YMAX");
  }
  const std::string ext = fs::path(a.out).extension().string();
  if (ext != ".tif" && ext != ".tiff" && ext != ".vrt") {
    throw ConfigError("--out " + a.out + ": name a .tif (one COG) or a .vrt (COG blocks in a folder beside it)");
  }
}

int DsmCommand(const DsmArgs& a) {
  CheckArgs(a);
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = ProcessCpuSeconds();
  const Eigen::Vector3d shift =
      a.offset.empty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(a.offset[0], a.offset[1], a.offset[2]);
  PointCloudFile cloud(a.cloud, shift);
  std::string crs_wkt = a.crs.empty() ? cloud.crs_wkt() : ProjectCrsWkt(a.crs, CrsWktDialect::kGdal);
  if (crs_wkt.empty()) spdlog::warn("{}: no CRS (give --crs); the DSM carries none", a.cloud);
  const Box2d area = a.extent.empty() ? cloud.bounds_xy() : Box2d(a.extent[0], a.extent[1], a.extent[2], a.extent[3]);
  if (area.IsEmpty()) throw InputError(a.cloud, "has no points");
  const CellWindow extent = CellWindowCovering(area, a.cell_m);
  RasterOutput output;
  output.blocks = fs::path(a.out).extension() == ".vrt";
  output.single_path = a.out;
  output.vrt_path = a.out;
  output.blocks_dir = (fs::path(a.out).parent_path() / fs::path(a.out).stem()).string();
  if (!output.blocks && extent.size() > kSingleFileMaxCells) {
    throw ConfigError(fmt::format("--out {}: {} x {} cells are more than one file holds here ({}); write a .vrt",
                                  a.out, extent.cols, extent.rows, kSingleFileMaxCells));
  }
  OutputOptions options;
  options.dsm_max_hole_m = a.max_hole_m;
  DsmRule rule = DsmRuleOf(options);
  rule.quantile = a.quantile;
  CloudGrid grid;
  const DsmWriteStats s = WriteDsmOfCloud(cloud, extent, rule, DsmRasterFormat(crs_wkt), output,
                                          MemoryBudgetBytes(a.memory_gb) / 4 / 8, &grid);
  if (grid.points_gridded == 0) throw InputError(a.cloud, "no point falls in the extent");
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << fmt::format(
      "{}: {} x {} cells of {} m from {} points ({} outside the extent, {} passes over the file); {:.2f} % with a "
      "value: {} from points, {} in filled holes\n",
      s.assembly.files.front(), extent.cols, extent.rows, a.cell_m, grid.points_gridded, grid.points_outside,
      grid.passes, 100.0 * static_cast<double>(s.assembly.cells_with_value) / static_cast<double>(extent.size()),
      s.raw_cells_with_value, s.finish.cells_filled);
  std::cout << fmt::format("wall {:.2f} s, CPU {:.2f} s, peak RSS {:.0f} MiB\n", wall,
                           ProcessCpuSeconds() - cpu_start, PeakRssMiB());
  return kExitOk;
}

}  // namespace

void AddDsmCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<DsmArgs>();
  auto* cmd = app.add_subcommand(
      "dsm",
      "Grid any point cloud (LAS, LAZ, binary PLY) into a DSM by the rule of sacfuse's own DSM: float32 Cloud "
      "Optimized GeoTIFF (.tif) or COG blocks with a VRT (.vrt); cells on multiples of --cell in the cloud's CRS");
  cmd->add_option("CLOUD", args->cloud, "LAS, LAZ or binary PLY point cloud")->required();
  cmd->add_option("--cell", args->cell_m, "Cell edge, metres")->required();
  cmd->add_option("--out", args->out, "DSM.tif (one COG) or DSM.vrt (COG blocks in DSM/ beside it)")->required();
  cmd->add_option("--crs", args->crs,
                  "CRS of the cloud, as the config's `crs` key (e.g. EPSG:25832); default: the LAS file's own");
  cmd->add_option("--offset", args->offset, "X,Y,Z added to every point (clouds written in a local frame), metres")
      ->delimiter(',');
  cmd->add_option("--extent", args->extent, "XMIN,YMIN,XMAX,YMAX of the DSM, metres; default: the cloud's bounds")
      ->delimiter(',');
  cmd->add_option("--max-hole", args->max_hole_m, "Holes up to this size (m, each side) are filled")
      ->capture_default_str();
  cmd->add_option("--quantile", args->quantile,
                  "Cell height: this quantile of the z of the cell's points (0.5: the median, as runs use; 1: the "
                  "highest point)")
      ->capture_default_str();
  cmd->add_option("--memory-gb", args->memory_gb, "Memory budget, GiB (a quarter of it holds points being gridded)")
      ->capture_default_str();
  cmd->callback([args, exit_code] {
    SetupLogging("info");
    *exit_code = RunGuarded([&] { return DsmCommand(*args); });
  });
}

}  // namespace sacfuse::cli
