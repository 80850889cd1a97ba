#include "jobs/tile_merge.h"

#include "core/error.h"
#include "io/las_reader.h"

namespace sacfuse {
namespace {
constexpr size_t kMergeChunkPoints = 1 << 16;
}  // namespace

MergeResult MergeTileLas(const std::vector<std::string>& tile_las_paths, const std::string& out_path,
                         const LasWriterOptions& options, const std::function<void(size_t, size_t)>& progress) {
  if (!options.offset) throw Error("MergeTileLas: a shared offset is required");
  const Eigen::Vector3d scale = options.scale_xyz ? *options.scale_xyz : Eigen::Vector3d::Constant(options.scale_m);
  MergeResult result;
  LasWriter writer(out_path, options);
  std::vector<LasPoint> chunk;
  for (size_t i = 0; i < tile_las_paths.size(); ++i) {
    LasReader reader(tile_las_paths[i]);
    const LasHeader& h = reader.header();
    if (h.scale != scale || h.offset != *options.offset) {
      throw InputError(tile_las_paths[i], "scale/offset differ from the run's shared ones; rerun this tile");
    }
    while (reader.Read(&chunk, kMergeChunkPoints) > 0) {
      for (const LasPoint& p : chunk) {
        if (p.point_source_id == 0) continue;
        const size_t view = p.point_source_id - 1u;
        if (view >= result.points_per_view.size()) result.points_per_view.resize(view + 1, 0);
        ++result.points_per_view[view];
      }
      writer.WritePoints(chunk.data(), chunk.size());
    }
    if (progress) progress(i + 1, tile_las_paths.size());
  }
  writer.Close();
  result.points = writer.num_points();
  return result;
}

}  // namespace sacfuse
