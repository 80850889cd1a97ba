#pragma once
// How much memory the steps of a run take, so tile sizes and tile parallelism can be chosen from
// `resources.memory_gb` before anything is loaded. Coefficients were measured with /usr/bin/time -v on simulated
// blocks (docs/concepts.md, "The memory budget") and carry a margin; peak RSS of real runs is reported next to the estimate.
#include <cstdint>
#include <string>
#include <vector>

#include "io/depth_block.h"

namespace sacfuse {

constexpr uint64_t kMiB = uint64_t{1} << 20;
constexpr uint64_t kGiB = uint64_t{1} << 30;

// Bytes a SAC tile holds per pixel of its views' depth windows: float32 depth (4) + superpixel label (~0.6 in
// per-block palettes: core/superpixel_labels.h; 2 or 4 where blocks meet too many labels) + the point-verdict memo
// (0.5) + SAC's working memory (nodes, correspondences, labels, emitted points: ~1.5 measured); colours only of
// the emitting view (FusionNeeds::colours_one_view_at_a_time). Measured ~7 B/px of peak RSS per window pixel on the
// Dortmund preset at pixel scale 0.25 (800 m tiles, 2026-11-27, with u16 labels and a 1-byte memo; 10.6 B/px with
// int32 labels and every view's colours); 12 keeps the margin the earlier 20 had over 12.5 measured. The comparison
// methods add their own (jobs/method_memory.h).
constexpr uint64_t kTileBytesPerWindowPixel = 12;
// Untiled SAC holds every view whole: per depth pixel as a tile (12), plus the decoded image (3 B per image
// pixel, a bound: the images are decoded a few at a time). Measured ~10 B/px on aerial-bench Montpellier
// (2026-11-27; 14.4 B/px on the small block with int32 labels and every view's colours).
constexpr uint64_t kUntiledBytesPerDepthPixel = 12;
constexpr uint64_t kBytesPerImagePixel = 3;
// The superpixel pass holds one view at a time: depth (4) + image on the depth grid and as Lab (6) + labels (4 while
// SLIC numbers them, then 2) + colour cache raster (3) + SLIC blocks in flight, ~20 B per depth pixel, plus the
// decoded image.
constexpr uint64_t kSuperpixelPassBytesPerDepthPixel = 20;
// The process itself: code, workspace model, logs, LAS writer buffers.
constexpr uint64_t kProcessBaseBytes = 128 * kMiB;

// Pixel counts of a workspace's depth rasters and images (depth sizes from the headers; no raster is read).
struct BlockPixels {
  std::vector<uint64_t> depth_pixels;  // per view
  std::vector<uint64_t> image_pixels;  // per view (camera size)
  uint64_t total_depth_pixels() const;
  uint64_t total_image_pixels() const;
};
BlockPixels MeasureBlockPixels(const DepthBlock& input);

// A byte count for messages, with a unit that shows it: "1.25 GiB", "3.4 MiB", "512 KiB", "0 B".
std::string ByteSizeText(uint64_t bytes);

// Byte budget of resources.memory_gb.
uint64_t MemoryBudgetBytes(double memory_gb);
// Share of the budget kept for superpixel cluster tables shared by tiles (jobs/cluster_table_cache.h).
uint64_t ClusterCacheBudgetBytes(uint64_t budget_bytes);
// What is left for tiles running at once: budget - process base - cluster cache.
uint64_t TileMemoryPoolBytes(uint64_t budget_bytes);

uint64_t TileBytes(uint64_t window_pixels);
uint64_t UntiledSacBytes(const BlockPixels& pixels);
// Peak of the superpixel pass: its largest view.
uint64_t SuperpixelPassBytes(const BlockPixels& pixels);
// How many views the superpixel pass (or an untiled run's loading) may prepare at once: one, and one more per
// further thread (`threads`) as long as the budget holds it beside `held_bytes`, the run's memory while it
// prepares one view (SuperpixelPassBytes for the tiled pass, UntiledSacBytes for an untiled run); each further
// view counts as much as the largest view's preparation.
size_t SuperpixelViewsInFlight(const BlockPixels& pixels, uint64_t budget_bytes, size_t threads, uint64_t held_bytes);

}  // namespace sacfuse
