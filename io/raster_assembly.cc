#include "io/raster_assembly.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <optional>
#include <set>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "core/error.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;

std::string BlockName(const CellBlock& b) { return std::to_string(b.bx) + "_" + std::to_string(b.by) + ".tif"; }

}  // namespace

bool RasterLayoutIsBlocks(const std::string& layout, const CellWindow& extent) {
  if (layout == "tiles") return true;
  if (layout == "single") return false;
  return extent.size() > kSingleFileMaxCells;
}

AssemblyStats AssembleRasterBlocks(const CellWindow& extent, const BlockMaker& make, const RasterFormat& format,
                                   const RasterOutput& output) {
  AssemblyStats stats;
  stats.cells = extent.size();
  const std::vector<CellBlock> blocks = CellBlocksOf(extent, kAssemblyBlockCells);
  std::optional<CogBuilder> cog;
  if (!output.blocks) cog.emplace(output.single_path, extent, format);
  std::set<std::string> written;
  for (const CellBlock& block : blocks) {
    const std::vector<uint8_t> data = make(block.window, &stats.cells_with_value);
    if (data.size() != block.window.size() * SampleBytes(format.type) * static_cast<size_t>(format.bands)) {
      throw Error("AssembleRasterBlocks: a block of the wrong size");
    }
    if (cog) {
      cog->Write(block.window, data.data());
    } else {
      const std::string path = (fs::path(output.blocks_dir) / BlockName(block)).string();
      WriteRasterFile(path, block.window, format, data.data(), RasterLayout::kCog);
      written.insert(path);
      stats.files.push_back(path);
    }
    ++stats.blocks;
  }
  if (cog) {
    cog->Finish();
    stats.files.push_back(output.single_path);
    return stats;
  }
  WriteVrt(output.vrt_path, stats.files);
  // Blocks of an earlier, larger extent would be stale beside the VRT: remove what this assembly did not write.
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(output.blocks_dir, ec)) {
    if (e.path().extension() == ".tif" && !written.count(e.path().string())) fs::remove(e.path(), ec);
  }
  stats.files.insert(stats.files.begin(), output.vrt_path);
  return stats;
}

AssemblyStats AssembleRaster(const CellWindow& extent, int64_t halo_cells, const RawCellReader& read_raw,
                             const CellFinisher& finish, const RasterFormat& format, const RasterOutput& output) {
  if (format.bands != 1 || format.type != RasterSampleType::kFloat32) {
    throw Error("AssembleRaster: single-band float32 products only");
  }
  const BlockMaker make = [&](const CellWindow& block, uint64_t* cells_with_value) {
    const CellWindow outer = block.Grown(halo_cells);
    const std::vector<float> values = finish(read_raw(outer), outer, block);
    // Counted, NaN turned into the nodata value and stored as the block's bytes in one pass, by ranges of cells
    // on the job's threads.
    std::vector<uint8_t> bytes(values.size() * sizeof(float));
    const bool to_nodata = format.nodata && !std::isnan(*format.nodata);
    const float nodata = to_nodata ? static_cast<float>(*format.nodata) : 0.0f;
    *cells_with_value += tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, values.size(), size_t{1} << 14), uint64_t{0},
        [&](const tbb::blocked_range<size_t>& r, uint64_t n) {
          for (size_t i = r.begin(); i < r.end(); ++i) {
            float v = values[i];
            if (std::isnan(v)) {
              if (to_nodata) v = nodata;
            } else {
              ++n;
            }
            std::memcpy(bytes.data() + i * sizeof(float), &v, sizeof(float));
          }
          return n;
        },
        std::plus<>());
    return bytes;
  };
  return AssembleRasterBlocks(extent, make, format, output);
}

}  // namespace sacfuse
