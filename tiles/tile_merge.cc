#include "tiles/tile_merge.h"

#include <exception>
#include <memory>
#include <optional>

#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include "config/output_layout.h"
#include "config/result_settings.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/las_reader.h"
#include "io/test_pause.h"
#include "io/vpc_writer.h"
#include "tiles/tile_manifest.h"
#include "tiles/tile_marker.h"

namespace sacfuse {
namespace {

constexpr size_t kMergeChunkPoints = 1 << 16;

// A tile file opened, checked and, when its chunks can be copied, with its last chunk decoded: made on any thread,
// appended in grid order. An error stays here until the tile's turn, so a merge fails on the first bad tile in
// grid order whatever the threads.
struct PreparedTile {
  std::unique_ptr<LasReader> reader;
  std::optional<LazAppendPart> part;  // unset: every point is read and written
  std::vector<LasPoint> points;       // without `part`, a small tile's points, read ahead
  bool read_ahead = false;
  std::exception_ptr error;
};

// The plan's tiles that have views (the others have no file), grid order.
std::vector<const PlannedTile*> TilesWithViews(const TilePlan& plan) {
  std::vector<const PlannedTile*> tiles;
  for (const PlannedTile& tile : plan.tiles) {
    if (!tile.views.empty()) tiles.push_back(&tile);
  }
  return tiles;
}

}  // namespace

uint64_t MergeTileLas(const std::vector<std::string>& tile_las_paths, const std::string& out_path,
                      const CloudFileOptions& cloud, const std::function<void(size_t, size_t)>& progress,
                      const std::function<void()>& before_commit) {
  const LasWriterOptions& options = cloud.las;
  if (!options.offset) throw Error("MergeTileLas: a shared offset is required");
  const Eigen::Vector3d scale = options.scale_xyz ? *options.scale_xyz : Eigen::Vector3d::Constant(options.scale_m);
  const std::unique_ptr<PointCloudWriter> out = OpenPointCloudWriter(out_path, cloud);
  PointCloudWriter& writer = *out;
  // A pipeline: the tiles ahead are opened and their last, partial LAZ chunks decoded and stored as the writer's
  // records (into LAS or COPC: small tiles' points decoded) on the pool (the writer's layout and offset are fixed,
  // PrepareLazAppend only reads them) while the writer appends the tiles before them in grid order (copying full
  // chunks and the prepared records, coding the gathered last points in parallel batches), so the file is the same
  // as a tile-by-tile merge for any thread count. At most one tile per thread plus one is held at once (each at
  // most 65,536 decoded points, ~5 MB).
  const size_t tokens = static_cast<size_t>(tbb::this_task_arena::max_concurrency()) + 1;
  size_t next = 0, done = 0;
  std::vector<LasPoint> chunk;
  tbb::parallel_pipeline(
      tokens,
      tbb::make_filter<void, size_t>(tbb::filter_mode::serial_in_order,
                                     [&](tbb::flow_control& control) -> size_t {
                                       if (next == tile_las_paths.size()) control.stop();
                                       return next++;
                                     }) &
          tbb::make_filter<size_t, std::shared_ptr<PreparedTile>>(
              tbb::filter_mode::parallel,
              [&](size_t i) {
                auto tile = std::make_shared<PreparedTile>();
                try {
                  tile->reader = std::make_unique<LasReader>(tile_las_paths[i]);
                  const LasHeader& h = tile->reader->header();
                  if (h.scale != scale || h.offset != *options.offset) {
                    throw InputError(tile_las_paths[i],
                                     "scale/offset differ from the run's shared ones; rerun this tile");
                  }
                  // LAZ tiles into a LAZ cloud: the chunks are copied. Otherwise (LAS, COPC) every point is read.
                  tile->part = writer.PrepareLazAppend(*tile->reader);
                  // A tile of one read is read here too (a large one is decoded in parallel batches as written).
                  if (!tile->part && h.point_count <= kMergeChunkPoints) {
                    tile->reader->Read(&tile->points, kMergeChunkPoints);
                    tile->read_ahead = true;
                  }
                } catch (...) {
                  tile->error = std::current_exception();
                }
                return tile;
              }) &
          tbb::make_filter<std::shared_ptr<PreparedTile>, void>(
              tbb::filter_mode::serial_in_order, [&](const std::shared_ptr<PreparedTile>& tile) {
                if (tile->error) std::rethrow_exception(tile->error);
                LasReader& reader = *tile->reader;
                if (tile->part) {
                  writer.AppendLaz(reader, *tile->part);
                } else if (tile->read_ahead) {
                  writer.WritePoints(tile->points.data(), tile->points.size());
                } else {
                  while (reader.Read(&chunk, kMergeChunkPoints) > 0) writer.WritePoints(chunk.data(), chunk.size());
                }
                if (progress) progress(++done, tile_las_paths.size());
              }));
  if (before_commit) before_commit();
  writer.Close();
  return writer.num_points();
}

MergeResult MergeTiledRun(const JobConfig& config, const DepthBlock& input, const TilePlan& plan,
                          const std::vector<ViewIdentity>& identities, const CloudFileOptions& cloud,
                          const std::string& fused_las_path,
                          const std::function<void(const std::string&, size_t, size_t)>& progress,
                          const std::function<void()>& before_commit) {
  const std::string tiles_dir = TilesDir(config);
  const std::string hash = ResultSettingsHash(config);
  std::vector<std::string> merge_order;  // LAS files of the tiles that have points, grid order
  std::vector<std::pair<std::string, std::string>> checked;  // tile id, its marker's text as checked
  MergeResult merged;
  // Every tile's marker checked in parallel (each reads its marker and its file's header), then taken in grid
  // order, so the first tile in that order that is not done is the one reported.
  struct CheckedTile {
    TileCheck check;
    std::string marker_text;
    std::optional<TileDoneMarker> marker;
    std::exception_ptr error;
  };
  const std::vector<const PlannedTile*> with_views = TilesWithViews(plan);
  std::vector<CheckedTile> checks(with_views.size());
  tbb::parallel_for(size_t{0}, with_views.size(), [&](size_t i) {
    const PlannedTile& tile = *with_views[i];
    CheckedTile& c = checks[i];
    try {
      const TileInputs inputs = TileInputsOf(tile, input.views(), identities);
      c.check = VerifyTileDone(tiles_dir, tile.id, hash, /*full_checksum=*/false, &inputs);
      if (!c.check.done) return;
      c.marker_text = ReadSmallFile(TileDonePath(tiles_dir, tile.id));
      c.marker = ReadTileDoneMarker(tiles_dir, tile.id);
    } catch (...) {
      c.error = std::current_exception();
    }
  });
  for (size_t i = 0; i < with_views.size(); ++i) {
    const PlannedTile& tile = *with_views[i];
    const CheckedTile& c = checks[i];
    if (c.error) std::rethrow_exception(c.error);
    if (!c.check.done) {
      throw Error("tile " + tile.id + " is not done for this job (" + c.check.reason + "): nothing merged into " +
                  fused_las_path + "; compute it with this config (`sacfuse run` or `sacfuse tile CONFIG --id " +
                  tile.id + "`)");
    }
    checked.emplace_back(tile.id, c.marker_text);
    const auto& marker = c.marker;
    if (!marker) throw Error(TileDonePath(tiles_dir, tile.id) + ": done marker vanished before the merge");
    if (marker->points > 0) merge_order.push_back(TileCloudPath(tiles_dir, *marker));
    for (const auto& [view, n] : marker->points_per_view) {
      if (view >= merged.points_per_view.size()) merged.points_per_view.resize(view + 1, 0);
      merged.points_per_view[view] += n;
    }
  }
  const auto markers_unchanged = [&] {
    PauseAtTestPoint("merge:before_commit");
    for (const auto& [id, text] : checked) {
      if (ReadSmallFile(TileDonePath(tiles_dir, id)) != text) {
        throw Error("tile " + id + " was rewritten by another process during the merge (" +
                    TileDonePath(tiles_dir, id) + " changed): nothing merged into " + fused_las_path +
                    "; run the merge again when no other worker of another config writes " + tiles_dir);
      }
    }
    if (before_commit) before_commit();
  };
  merged.points = MergeTileLas(
      merge_order, fused_las_path, cloud,
      [&](size_t done, size_t n) {
        if (progress) progress("merge", done, n);
      },
      markers_unchanged);
  spdlog::info("merged {} tile files ({} points) into {}", merge_order.size(), merged.points, fused_las_path);
  WriteVirtualPointCloud(TileIndexPath(config), merge_order, ParseProjectCrs(config.crs));
  spdlog::info("indexed the {} tile files in {}", merge_order.size(), TileIndexPath(config));
  return merged;
}

std::vector<std::string> MissingTiles(const JobConfig& config, const DepthBlock& input, const TilePlan& plan,
                                      const std::vector<ViewIdentity>& identities) {
  const std::string tiles_dir = TilesDir(config);
  const std::string hash = ResultSettingsHash(config);
  // The tiles' checksums in parallel: each reads its whole file.
  const std::vector<const PlannedTile*> with_views = TilesWithViews(plan);
  std::vector<char> done(with_views.size(), 0);
  tbb::parallel_for(size_t{0}, with_views.size(), [&](size_t i) {
    const TileInputs inputs = TileInputsOf(*with_views[i], input.views(), identities);
    done[i] = VerifyTileDone(tiles_dir, with_views[i]->id, hash, true, &inputs).done;
  });
  std::vector<std::string> missing;
  for (size_t i = 0; i < with_views.size(); ++i) {
    if (!done[i]) missing.push_back(with_views[i]->id);
  }
  return missing;
}

}  // namespace sacfuse
