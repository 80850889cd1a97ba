#include "tiles/tile_merge.h"

#include <spdlog/spdlog.h>

#include "config/output_layout.h"
#include "config/result_settings.h"
#include "core/error.h"
#include "io/las_reader.h"
#include "io/vpc_writer.h"
#include "tiles/tile_manifest.h"
#include "tiles/tile_marker.h"

namespace sacfuse {
namespace {
constexpr size_t kMergeChunkPoints = 1 << 16;
}  // namespace

uint64_t MergeTileLas(const std::vector<std::string>& tile_las_paths, const std::string& out_path,
                      const CloudFileOptions& cloud, const std::function<void(size_t, size_t)>& progress) {
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
  writer.Close();
  return writer.num_points();
}

MergeResult MergeTiledRun(const JobConfig& config, const TilePlan& plan, const CloudFileOptions& cloud,
                          const std::string& fused_las_path,
                          const std::function<void(const std::string&, size_t, size_t)>& progress) {
  const std::string tiles_dir = TilesDir(config);
  std::vector<std::string> merge_order;  // LAS files of the tiles that have points, grid order
  MergeResult merged;
  for (const std::string& id : TileIdsWithViews(plan)) {
    const auto marker = ReadTileDoneMarker(tiles_dir, id);
    if (!marker) throw Error(TileDonePath(tiles_dir, id) + ": done marker vanished before the merge");
    if (marker->points > 0) merge_order.push_back(TileCloudPath(tiles_dir, *marker));
    for (const auto& [view, n] : marker->points_per_view) {
      if (view >= merged.points_per_view.size()) merged.points_per_view.resize(view + 1, 0);
      merged.points_per_view[view] += n;
    }
  }
  merged.points = MergeTileLas(merge_order, fused_las_path, cloud, [&](size_t done, size_t n) {
    if (progress) progress("merge", done, n);
  });
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
