#include "jobs/superpixel_cache.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/colour_raster_io.h"
#include "io/superpixel_io.h"
#include "io/json_text.h"

namespace sacfuse {
namespace fs = std::filesystem;
namespace {

// "<dir>/a.jpg.spx" -> "<dir>/a.jpg.inputs-spx.json" (so a file named with ".spx" or ".rgb" is a cache file).
std::string RecordPath(const std::string& cache_path) {
  const size_t dot = cache_path.rfind('.');
  return cache_path.substr(0, dot) + ".inputs-" + cache_path.substr(dot + 1) + ".json";
}

// Records the inputs a cache file was made from, and the cache file as written (after it is in place).
void WriteCacheRecord(const std::string& cache_path, const ViewIdentity& inputs) {
  const nlohmann::json j = {{"inputs", nlohmann::json::parse(ViewIdentityJson(inputs))},
                            {"file", nlohmann::json::parse(FileIdentityJson(IdentifyFile(cache_path)))}};
  WriteFileAtomically(RecordPath(cache_path), JsonText(j, 2) + "\n");
}

// "" when the cache file at `cache_path` (which exists) was made from inputs equal to `inputs` in `parts` and is
// unchanged since; otherwise why not (*inputs_changed: because of the inputs).
std::string CheckCacheRecord(const std::string& cache_path, const ViewIdentity& inputs, unsigned parts,
                             bool* inputs_changed) {
  std::ifstream in(RecordPath(cache_path));
  if (!in) return "no record of the inputs it was made from (" + RecordPath(cache_path) + ")";
  std::ostringstream text;
  text << in.rdbuf();
  std::optional<ViewIdentity> recorded;
  std::optional<FileIdentity> file;
  try {
    const nlohmann::json j = nlohmann::json::parse(text.str());
    recorded = ParseViewIdentityJson(j.at("inputs").dump());
    file = ParseFileIdentityJson(j.at("file").dump());
  } catch (const std::exception&) {
  }
  if (!recorded || !file) return "its input record " + RecordPath(cache_path) + " is unreadable";
  const std::string change = DescribeViewChange(*recorded, inputs, parts);
  if (!change.empty()) {
    *inputs_changed = true;
    return change;
  }
  if (!(IdentifyFile(cache_path) == *file)) return "the cache file " + cache_path + " changed since it was written";
  return "";
}

// The record check, then `header_ok` (reads the header; throws Error for a bad file).
template <typename HeaderOk>
CacheCheck CheckCache(const std::string& path, const ViewIdentity& inputs, unsigned parts, HeaderOk header_ok) {
  CacheCheck check;
  if (!fs::exists(path)) return check;
  check.reason = CheckCacheRecord(path, inputs, parts, &check.inputs_changed);
  if (!check.reason.empty()) return check;
  try {
    if (!header_ok()) {
      check.reason = "made with other options or another raster size";
      return check;
    }
  } catch (const Error& e) {
    check.reason = std::string("unreadable: ") + e.what();
    return check;
  }
  check.current = true;
  return check;
}

}  // namespace

CacheCheck CheckSuperpixelCache(const std::string& cache_dir, const View& view, int width, int height,
                                const SuperpixelOptions& options, const ViewIdentity& inputs) {
  const std::string path = SuperpixelCachePath(cache_dir, view.name);
  return CheckCache(path, inputs, kDepthInput | kImageInput, [&] {
    const SuperpixelFileInfo info = ReadSuperpixelInfo(path);
    return info.options_hash == SuperpixelOptionsHash(options) && info.width == width && info.height == height;
  });
}

void LogCacheCheck(const CacheCheck& check, const View& view, const char* what) {
  if (check.current || check.reason.empty()) return;
  if (check.inputs_changed) {
    spdlog::info("{}: {}: its {} are recomputed", ViewLabel(view), check.reason, what);
  } else {
    spdlog::warn("{}: {} cache not reused ({}): recomputed", ViewLabel(view), what, check.reason);
  }
}

SuperpixelMap LoadOrComputeSuperpixels(const std::string& cache_dir, const View& view,
                                       const std::function<const RgbImage&()>& image,
                                       const DepthMap& depth, const SuperpixelOptions& options,
                                       const ViewIdentity& inputs, bool* computed, LabelPacking packing) {
  const std::string path = SuperpixelCachePath(cache_dir, view.name);
  const CacheCheck check = CheckSuperpixelCache(cache_dir, view, depth.width, depth.height, options, inputs);
  if (check.current) {
    try {
      SuperpixelMap map = ReadSuperpixels(path);
      if (computed != nullptr) *computed = false;
      return map;
    } catch (const Error& e) {
      spdlog::warn("{}: superpixel cache {} is corrupt ({}): recomputed", ViewLabel(view), path, e.what());
    }
  } else {
    LogCacheCheck(check, view, "superpixels");
  }
  SuperpixelMap map = ComputeSuperpixels(image(), depth, options, packing);
  fs::create_directories(fs::path(path).parent_path());
  WriteSuperpixels(path, map, SuperpixelOptionsHash(options));
  WriteCacheRecord(path, inputs);
  if (computed != nullptr) *computed = true;
  return map;
}

CacheCheck CheckColourCache(const std::string& cache_dir, const View& view, int width, int height,
                            const ViewIdentity& inputs) {
  const std::string path = ColourCachePath(cache_dir, view.name);
  return CheckCache(path, inputs, kImageInput, [&] {
    const ColourRasterInfo info = ReadColourRasterInfo(path);
    return info.width == width && info.height == height;
  });
}

void WriteColourCache(const std::string& cache_dir, const View& view, const RgbImage& colours,
                      const ViewIdentity& inputs) {
  const std::string path = ColourCachePath(cache_dir, view.name);
  WriteColourRaster(path, colours);
  WriteCacheRecord(path, inputs);
}

}  // namespace sacfuse
