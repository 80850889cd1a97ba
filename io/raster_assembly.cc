#include "io/raster_assembly.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <optional>
#include <set>

#include "core/error.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;

std::string BlockName(const CellBlock& b) { return std::to_string(b.bx) + "_" + std::to_string(b.by) + ".tif"; }

// The format's nodata value in place of NaN (float32 products carry a finite nodata value).
void ToNodata(std::vector<float>* v, const RasterFormat& format) {
  if (!format.nodata || std::isnan(*format.nodata)) return;
  const float nd = static_cast<float>(*format.nodata);
  for (float& x : *v) {
    if (std::isnan(x)) x = nd;
  }
}

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
    std::vector<float> values = finish(read_raw(outer), outer, block);
    for (const float v : values) *cells_with_value += std::isnan(v) ? 0 : 1;
    ToNodata(&values, format);
    std::vector<uint8_t> bytes(values.size() * sizeof(float));
    std::memcpy(bytes.data(), values.data(), bytes.size());
    return bytes;
  };
  return AssembleRasterBlocks(extent, make, format, output);
}

}  // namespace sacfuse
