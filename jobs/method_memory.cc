#include "jobs/method_memory.h"

#include <cmath>

namespace sacfuse {
namespace {

constexpr double kTsdfVoxelBytesPerPixelAt4Gsd = 50.0;  // voxel 1 GSD, truncation 4 GSD (measured, see .h)
constexpr uint64_t kComparisonBytesPerPixel = 8;         // colours with the views and per-pixel state (see .h)

}  // namespace

uint64_t MethodExtraBytesPerDepthPixel(const FusionOptions& fusion) {
  if (fusion.method == FusionMethodKind::kSac) return 0;
  if (fusion.method != FusionMethodKind::kTsdf) return kComparisonBytesPerPixel;
  const double voxel = fusion.tsdf.voxel_size_gsd;
  const double scale = (fusion.tsdf.truncation_gsd / 4.0) / (voxel * voxel * voxel);
  return kComparisonBytesPerPixel + static_cast<uint64_t>(std::ceil(kTsdfVoxelBytesPerPixelAt4Gsd * scale));
}

uint64_t MethodTileBytes(const PlannedTile& tile, const FusionOptions& fusion) {
  return tile.memory_bytes + MethodExtraBytesPerDepthPixel(fusion) * tile.window_pixels;
}

FusionOptions WithTsdfMemoryLimit(const JobConfig& config) {
  FusionOptions fusion = config.fusion;
  if (fusion.tsdf.max_memory_gb <= 0) fusion.tsdf.max_memory_gb = config.resources.memory_gb;
  return fusion;
}

}  // namespace sacfuse
