#include "tiles/tile_merge.h"


#include <spdlog/spdlog.h>

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

}  // namespace

uint64_t MergeTileLas(const std::vector<std::string>& tile_las_paths, const std::string& out_path,
                      const CloudFileOptions& cloud, const std::function<void(size_t, size_t)>& progress,
                      const std::function<void()>& before_commit) {
  const LasWriterOptions& options = cloud.las;
  if (!options.offset) throw Error("MergeTileLas: a shared offset is required");
  const Eigen::Vector3d scale = options.scale_xyz ? *options.scale_xyz : Eigen::Vector3d::Constant(options.scale_m);
  const std::unique_ptr<PointCloudWriter> out = OpenPointCloudWriter(out_path, cloud);
  PointCloudWriter& writer = *out;
  std::vector<LasPoint> chunk;
  for (size_t i = 0; i < tile_las_paths.size(); ++i) {
    LasReader reader(tile_las_paths[i]);
    const LasHeader& h = reader.header();
    if (h.scale != scale || h.offset != *options.offset) {
      throw InputError(tile_las_paths[i], "scale/offset differ from the run's shared ones; rerun this tile");
    }
    // LAZ tiles into a LAZ cloud: the chunks are copied. Otherwise (LAS output) every point is decoded.
    if (!writer.AppendLaz(reader)) {
      while (reader.Read(&chunk, kMergeChunkPoints) > 0) writer.WritePoints(chunk.data(), chunk.size());
    }
    if (progress) progress(i + 1, tile_las_paths.size());
  }
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
  for (const PlannedTile& tile : plan.tiles) {
    if (tile.views.empty()) continue;
    const TileInputs inputs = TileInputsOf(tile, input.views(), identities);
    const TileCheck check = VerifyTileDone(tiles_dir, tile.id, hash, /*full_checksum=*/false, &inputs);
    if (!check.done) {
      throw Error("tile " + tile.id + " is not done for this job (" + check.reason + "): nothing merged into " +
                  fused_las_path + "; compute it with this config (`sacfuse run` or `sacfuse tile CONFIG --id " +
                  tile.id + "`)");
    }
    checked.emplace_back(tile.id, ReadSmallFile(TileDonePath(tiles_dir, tile.id)));
    const auto marker = ReadTileDoneMarker(tiles_dir, tile.id);
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
  std::vector<std::string> missing;
  for (const PlannedTile& tile : plan.tiles) {
    if (tile.views.empty()) continue;
    const TileInputs inputs = TileInputsOf(tile, input.views(), identities);
    if (!VerifyTileDone(tiles_dir, tile.id, hash, true, &inputs).done) missing.push_back(tile.id);
  }
  return missing;
}

}  // namespace sacfuse
