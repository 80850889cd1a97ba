#include "jobs/ortho_product.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>

#include <spdlog/spdlog.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "config/output_layout.h"
#include "core/error.h"
#include "core/ortho_rule.h"
#include "io/gdal_raster.h"
#include "io/point_cloud_file.h"
#include "io/raster_assembly.h"
#include "io/resource_usage.h"
#include "jobs/auto_tiling.h"
#include "jobs/view_batches.h"
#include "tiles/memory_model.h"
#include "tiles/tile_manifest.h"
#include "tiles/tile_marker.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;

RasterFormat OrthoRasterFormat(const std::string& crs_wkt) {
  RasterFormat f;
  f.bands = 4;
  f.type = RasterSampleType::kByte;
  f.crs_wkt = crs_wkt;
  f.rgba = true;
  f.overview_resampling = "AVERAGE";
  return f;
}

RasterOutput OrthoRasterOutput(const JobConfig& config, bool blocks) {
  RasterOutput out;
  out.blocks = blocks;
  out.single_path = OrthoPath(config);
  out.blocks_dir = OrthoBlocksDir(config);
  out.vrt_path = OrthoVrtPath(config);
  return out;
}

Box2d BoxOf(const CellWindow& w) { return Box2d(w.west(), w.south(), w.east(), w.north()); }

// The SAC-selected view of every cell of `block` (north-up, -1 = none): the source view of the cell's point whose
// float height is nearest the cell's DSM height (the median point, whose height the DSM holds exactly), ties to
// the lower view index. Reads the points of the clouds whose bounds meet the block, the clouds and each chunk's
// points on the job's threads: a cell keeps the least (|dz| bits, view) pair, which does not depend on the order in
// which its points come (|dz| >= 0, so its float bits order as the values).
std::vector<int32_t> SelectedViews(const std::vector<OrthoCloud>& clouds, const CellWindow& block, const DsmPatch& dsm,
                                   size_t view_count) {
  constexpr uint64_t kNone = ~uint64_t{0};
  std::vector<std::atomic<uint64_t>> best(block.size());
  for (std::atomic<uint64_t>& b : best) b.store(kNone, std::memory_order_relaxed);
  const Box2d box = BoxOf(block);
  const double cell = block.cell_m;
  std::vector<const OrthoCloud*> meeting;
  for (const OrthoCloud& c : clouds) {
    if (!c.bounds.IsEmpty() && c.bounds.Intersects(box)) meeting.push_back(&c);
  }
  tbb::parallel_for(size_t{0}, meeting.size(), [&](size_t c) {
    PointCloudFile cloud(meeting[c]->path);
    CloudChunk chunk;
    while (cloud.Read(&chunk, kCloudReadChunkPoints) > 0) {
      tbb::parallel_for(tbb::blocked_range<size_t>(0, chunk.xyz.size(), 4096),
                        [&](const tbb::blocked_range<size_t>& range) {
        for (size_t k = range.begin(); k < range.end(); ++k) {
          const Eigen::Vector3d& p = chunk.xyz[k];
          const uint16_t source = chunk.source_id[k];
          if (source == 0 || source > view_count || !p.allFinite()) continue;
          const int64_t col = CellIndexOf(p.x(), cell), row = CellIndexOf(p.y(), cell);
          if (!block.Contains(col, row)) continue;
          const float h = dsm.z[dsm.window.Index(col, row)];
          if (!std::isfinite(h)) continue;
          uint32_t dz_bits = 0;
          const float dz = std::abs(static_cast<float>(p.z()) - h);
          std::memcpy(&dz_bits, &dz, sizeof(dz_bits));
          const uint64_t key = (static_cast<uint64_t>(dz_bits) << 32) | static_cast<uint32_t>(source - 1);
          std::atomic<uint64_t>& b = best[block.Index(col, row)];
          uint64_t seen = b.load(std::memory_order_relaxed);
          while (key < seen && !b.compare_exchange_weak(seen, key, std::memory_order_relaxed)) {
          }
        }
      });
    }
  });
  std::vector<int32_t> view(block.size(), -1);
  for (size_t i = 0; i < view.size(); ++i) {
    const uint64_t b = best[i].load(std::memory_order_relaxed);
    if (b != kNone) view[i] = static_cast<int32_t>(b & 0xffffffffu);
  }
  return view;
}

}  // namespace

std::vector<OrthoCloud> TiledRunClouds(const JobConfig& config, const TilePlan& plan) {
  const std::string tiles_dir = TilesDir(config);
  std::vector<OrthoCloud> clouds;
  for (const std::string& id : TileIdsWithViews(plan)) {
    const auto marker = ReadTileDoneMarker(tiles_dir, id);
    if (!marker) throw Error(TileDonePath(tiles_dir, id) + ": done marker vanished before the ortho was made");
    if (marker->points == 0) continue;
    clouds.push_back({TileCloudPath(tiles_dir, *marker),
                      Box2d(marker->min[0], marker->min[1], marker->max[0], marker->max[1])});
  }
  return clouds;
}

OrthoCloud FusedCloud(const std::string& path) {
  PointCloudFile cloud(path);
  return {path, cloud.bounds_xy()};
}

void RemoveOrthoFiles(const JobConfig& config) {
  RemoveEarlierRasterFiles("ortho", {OrthoPath(config), OrthoVrtPath(config), OrthoBlocksDir(config)});
}

OrthoOutcome MakeOrthoOfRun(const JobConfig& config, const DepthBlock& input, const DsmOutcome& dsm,
                            const std::vector<OrthoCloud>& clouds) {
  if (!OrthoWanted(config) || !dsm.written) {
    RemoveOrthoFiles(config);
    return {};
  }
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = ProcessCpuSeconds();
  const RasterFile dsm_file(dsm.path);
  const CellWindow extent = dsm_file.window();
  const double cell = extent.cell_m;
  const OrthoRule rule = OrthoRuleForCell(cell);
  const int64_t halo = OrthoHaloCells(rule, cell);
  std::vector<OrthoView> views;
  for (const View& v : input.views()) views.push_back(OrthoViewOf(v.index, v.camera, v.cam_from_world));

  const bool blocks = RasterLayoutIsBlocks(config.output.raster_layout, extent);
  if (blocks) {
    RemoveQuietly(OrthoPath(config));
  } else {
    RemoveQuietly(OrthoVrtPath(config));
    RemoveQuietly(OrthoBlocksDir(config));
  }
  // Decoded images held at once: one per thread, within a quarter of the memory budget (at least one).
  uint64_t largest_image_bytes = 1;
  for (const View& v : input.views()) {
    largest_image_bytes = std::max<uint64_t>(largest_image_bytes, uint64_t{3} * v.camera.width * v.camera.height);
  }
  const size_t images_in_flight = static_cast<size_t>(std::clamp<uint64_t>(
      MemoryBudgetBytes(config.resources.memory_gb) / 4 / largest_image_bytes, 1, EffectiveThreads(config)));
  OrthoOutcome out;
  const BlockMaker make = [&](const CellWindow& block, uint64_t* cells_with_value) {
    const CellWindow outer = block.Grown(halo);
    const DsmPatch patch = MakeDsmPatch(outer, dsm_file.ReadFloat(outer));
    const std::vector<int32_t> selected = SelectedViews(clouds, block, patch, views.size());
    const std::vector<int32_t> chosen = OrthoCellViews(patch, block, selected, views, rule);
    const size_t n = block.size();
    std::vector<uint8_t> rgba(4 * n, 0);
    std::vector<std::vector<size_t>> cells_of_view(views.size());  // by view: each image decoded once for the block
    for (size_t i = 0; i < n; ++i) {
      if (chosen[i] >= 0) {
        cells_of_view[static_cast<size_t>(chosen[i])].push_back(i);
        ++(chosen[i] == selected[i] ? out.cells_selected_view : out.cells_other_view);
      } else {
        const int64_t col = block.col0 + static_cast<int64_t>(i % block.cols);
        const int64_t row = block.row0 + block.rows - 1 - static_cast<int64_t>(i / block.cols);
        if (std::isfinite(patch.z[outer.Index(col, row)])) ++out.cells_unseen;
      }
    }
    // The views on the job's threads, each decoding its image and colouring its own cells; at most
    // `images_in_flight` images decoded at once. The views with the most cells first, so that no long one starts
    // last.
    std::vector<size_t> order;  // the views with cells, by index
    for (size_t v = 0; v < cells_of_view.size(); ++v) {
      if (!cells_of_view[v].empty()) order.push_back(v);
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return cells_of_view[a].size() > cells_of_view[b].size(); });
    std::atomic<uint64_t> coloured{0}, reads{0};
    ForEachViewInFlight(order.size(), images_in_flight, [&](size_t o) {
      const size_t v = order[o];
      const std::vector<size_t>& cells = cells_of_view[v];
      const View& view = input.views()[v];
      const RgbImage image = input.ReadImage(view);
      ++reads;
      if (image.empty()) return;  // an input without images: those cells stay transparent
      const PinholeCamera camera = view.camera.Scaled(image.width, image.height);
      for (const size_t i : cells) {
        const int64_t col = block.col0 + static_cast<int64_t>(i % block.cols);
        const int64_t row = block.row0 + block.rows - 1 - static_cast<int64_t>(i / block.cols);
        const std::array<uint8_t, 3> rgb = CellColour(image, camera, view.cam_from_world,
                                                      CellPoint(col, row, cell, patch.z[outer.Index(col, row)]), cell);
        for (int c = 0; c < 3; ++c) rgba[c * n + i] = rgb[c];
        rgba[3 * n + i] = 255;
      }
      coloured += cells.size();
    });
    *cells_with_value += coloured.load();
    out.image_reads += reads.load();
    return rgba;
  };
  const AssemblyStats stats =
      AssembleRasterBlocks(extent, make, OrthoRasterFormat(dsm_file.crs_wkt()), OrthoRasterOutput(config, blocks));
  out.written = true;
  out.path = stats.files.front();
  out.cols = extent.cols;
  out.rows = extent.rows;
  out.cells_coloured = stats.cells_with_value;
  out.files = stats.files.size();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.cpu_seconds = ProcessCpuSeconds() - cpu_start;
  out.peak_rss_mib = PeakRssMiB();
  spdlog::info("ortho: {} ({} x {} cells, {:.1f} % coloured: {} from the SAC-selected view, {} from another view; {} "
               "cells with a height no view sees; {} image reads) in {:.1f} s ({:.1f} s CPU)",
               out.path, out.cols, out.rows, out.cells_coloured * 100.0 / std::max<double>(1, extent.size()),
               out.cells_selected_view, out.cells_other_view, out.cells_unseen, out.image_reads, out.seconds, out.cpu_seconds);
  return out;
}

}  // namespace sacfuse
