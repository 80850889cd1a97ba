#include "tests/fuzz/fuzz_readers.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <stdexcept>

#include <spdlog/spdlog.h>

#include "config/job_config.h"
#include "core/error.h"
#include "io/colmap_array.h"
#include "io/colmap_workspace.h"
#include "io/las_reader.h"
#include "io/las_validate.h"
#include "io/openmvs_block.h"
#include "io/openmvs_dmap.h"
#include "io/raster_block.h"
#include "io/superpixel_io.h"
#include "io/tiff_depth.h"

namespace sacfuse::fuzz {
namespace {

namespace fs = std::filesystem;

// Whole rasters are read only up to this size: the readers allocate what a (checked) header declares, and in a
// run a depth raster's size must match its camera first. Larger ones are read by a window.
constexpr uint64_t kMaxWholePixels = uint64_t{1} << 22;

// A fresh scratch folder per input, under a per-process root (tmpfs when there is one).
fs::path Scratch() {
  static const fs::path root = [] {
    const fs::path base = fs::exists("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
    return base / ("sacfuse-fuzz-" + std::to_string(::getpid()));
  }();
  std::error_code ec;
  fs::remove_all(root, ec);
  fs::create_directories(root);
  return root;
}

void Write(const fs::path& path, const std::string& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << bytes;
}

std::vector<std::string> Split(const std::string& bytes, size_t parts) {
  std::vector<std::string> out;
  const std::string sep = kFileSeparator;
  size_t begin = 0;
  while (out.size() + 1 < parts) {
    const size_t end = bytes.find(sep, begin);
    if (end == std::string::npos) break;
    out.push_back(bytes.substr(begin, end - begin));
    begin = end + sep.size();
  }
  out.push_back(bytes.substr(std::min(begin, bytes.size())));
  out.resize(parts);
  return out;
}

// Reads what a run reads of every view of a block: sizes, whole depth maps (when not huge), a window, images.
void ReadViews(const DepthBlock& block) {
  for (const View& view : block.views()) {
    const DepthRasterSize size = block.DepthSize(view);
    if (static_cast<uint64_t>(size.width) * size.height <= kMaxWholePixels) block.ReadDepthMap(view);
    block.ReadDepthWindow(view, PixelWindow{0, std::min(size.height, 8), 0, std::min(size.width, 8)});
  }
  block.SceneHeights();
}

void ColmapModel(const std::string& bytes, const char* ext) {
  const fs::path dir = Scratch();
  const std::vector<std::string> files = Split(bytes, 3);
  const char* stems[] = {"cameras", "images", "points3D"};
  for (int i = 0; i < 3; ++i) Write(dir / "sparse" / (std::string(stems[i]) + ext), files[i]);
  const ColmapWorkspace ws(dir.string(), ColmapDepthType::kGeometric);
  ws.SceneHeights();
}

void ColmapArray(const std::string& bytes) {
  const fs::path path = Scratch() / "a.jpg.geometric.bin";
  Write(path, bytes);
  const ColmapArrayShape shape = ReadColmapArrayShape(path.string());
  if (static_cast<uint64_t>(shape.width) * shape.height * shape.channels <= kMaxWholePixels) {
    ReadColmapArray(path.string());
  }
  ReadColmapArrayWindow(path.string(), PixelWindow{0, std::min(shape.height, 8), 0, std::min(shape.width, 8)});
}

void OpenMvsDmap(const std::string& bytes) {
  const fs::path dir = Scratch();
  const fs::path path = dir / "depth0000.dmap";
  Write(path, bytes);
  const DmapHeader h = ReadDmapHeader(path.string());
  if (h.has(kDmapNormals)) ReadDmapNormals(path.string());
  if (h.has(kDmapConfidence)) ReadDmapConfidence(path.string());
  if (h.has(kDmapViews)) ReadDmapViews(path.string());
  const OpenMvsBlock block(dir.string());
  ReadViews(block);
}

void TiffDepth(const std::string& bytes) {
  const fs::path path = Scratch() / "depth.tif";
  Write(path, bytes);
  TiffDepthReader reader(path.string());
  const TiffDepthInfo& info = reader.info();
  if (static_cast<uint64_t>(info.width) * info.height <= kMaxWholePixels) {
    reader.ReadWindow(PixelWindow{0, info.height, 0, info.width});
  }
  reader.ReadWindow(PixelWindow{info.height / 2, std::min(info.height, info.height / 2 + 4), info.width / 2,
                                std::min(info.width, info.width / 2 + 4)});
}

// A camera file with one 16 x 12 depth raster every view may name (depth.tif), as a RasterBlock opens it.
void CameraFile(const std::string& bytes, const char* name) {
  const fs::path dir = Scratch();
  Write(dir / name, bytes);
  static const std::string depth = [] {
    const fs::path p = fs::temp_directory_path() / ("sacfuse-fuzz-depth-" + std::to_string(::getpid()) + ".tif");
    WriteTiffDepth(p.string(), DepthMap(16, 12, 1, 50.0f), {});
    std::ifstream in(p, std::ios::binary);
    std::string b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    fs::remove(p);
    return b;
  }();
  Write(dir / "depth.tif", depth);
  const RasterBlock block((dir / name).string(), DepthKind::kRange, "EPSG:25832");
  for (const View& view : block.views()) {
    if (block.DepthMapPath(view) == (dir / "depth.tif").string()) block.ReadDepthMap(view);
  }
}

void Las(const std::string& bytes) {
  const fs::path path = Scratch() / "points.las";
  Write(path, bytes);
  ValidateLasFile(path.string());  // never throws for content: findings are returned
  LasReader reader(path.string());
  std::vector<LasPoint> points;
  while (reader.Read(&points, 4096) > 0) {
  }
}

void JobConfigText(const std::string& bytes) { ParseJobConfig(bytes, "fuzz.yaml", "/base"); }

// Our superpixel cache (io/superpixel_io.h): a run reads it back from disk, where it may be truncated or corrupt;
// the header's sizes must match the file length, so what the readers allocate is bounded by the input.
void SuperpixelCache(const std::string& bytes) {
  const fs::path path = Scratch() / "view.spx";
  Write(path, bytes);
  const SuperpixelFileInfo info = ReadSuperpixelInfo(path.string());
  ReadSuperpixelClusters(path.string());
  ReadSuperpixels(path.string());
  if (info.height > 0) {
    ReadSuperpixelRows(path.string(), info.height / 2, std::min(info.height, info.height / 2 + 70));
    ReadSuperpixelLabelWindow(path.string(), PixelWindow{info.height / 2, std::min(info.height, info.height / 2 + 4),
                                                         info.width / 2, std::min(info.width, info.width / 2 + 4)});
  }
}

const std::map<std::string, std::function<void(const std::string&)>>& Targets() {
  static const std::map<std::string, std::function<void(const std::string&)>> targets = {
      {"colmap_text", [](const std::string& b) { ColmapModel(b, ".txt"); }},
      {"colmap_binary", [](const std::string& b) { ColmapModel(b, ".bin"); }},
      {"colmap_array", ColmapArray},
      {"openmvs_dmap", OpenMvsDmap},
      {"tiff_depth", TiffDepth},
      {"camera_yaml", [](const std::string& b) { CameraFile(b, "cameras.yaml"); }},
      {"camera_csv", [](const std::string& b) { CameraFile(b, "cameras.csv"); }},
      {"las", Las},
      {"job_config", JobConfigText},
      {"superpixel_cache", SuperpixelCache},
  };
  return targets;
}

}  // namespace

const std::vector<std::string>& TargetNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& [name, fn] : Targets()) n.push_back(name);
    return n;
  }();
  return names;
}

void RunTarget(const std::string& name, const uint8_t* data, size_t size) {
  static const bool quiet = [] {
    spdlog::set_level(spdlog::level::off);  // input warnings are expected and would flood the fuzzer's output
    return true;
  }();
  (void)quiet;
  const auto it = Targets().find(name);
  if (it == Targets().end()) throw std::invalid_argument("unknown fuzz target " + name);
  try {
    it->second(std::string(reinterpret_cast<const char*>(data), size));
  } catch (const Error& e) {
    // The contract: a clear error. SACFUSE_FUZZ_VERBOSE=1 prints it (to see which seeds a reader accepts).
    static const bool verbose = std::getenv("SACFUSE_FUZZ_VERBOSE") != nullptr;
    if (verbose) std::fprintf(stderr, "%s: %s\n", name.c_str(), e.what());
  }
}

}  // namespace sacfuse::fuzz
