#include "tools/sim/sgbm_workspace.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "tools/sim/sgbm_depth.h"
#include "tools/sim/stereo_sources.h"

namespace sacfuse::sim {
namespace {

constexpr size_t kCachedImages = 12;

// The views of the model as the matcher sees them: cameras at the depth raster's size, written poses, sorted ids of
// the sparse points each observes.
std::vector<StereoView> StereoViews(const ColmapModel& model, int depth_downsample) {
  std::vector<StereoView> views;
  views.reserve(model.images.size());
  for (const ColmapImage& image : model.images) {
    const ColmapCamera& c = model.cameras.at(image.camera_id);
    if (c.model != "PINHOLE" || c.params.size() != 4) throw Error("sgbm: camera of " + image.name + " is not PINHOLE");
    PinholeCamera camera{static_cast<int>(c.width), static_cast<int>(c.height), c.params[0], c.params[1],
                         c.params[2],                c.params[3]};
    const int ds = std::max(1, depth_downsample);
    if (ds > 1) camera = camera.Scaled(std::max(1, camera.width / ds), std::max(1, camera.height / ds));
    StereoView view;
    view.name = image.name;
    view.camera = camera;
    view.cam_from_world = {image.cam_from_world_rotation, image.cam_from_world_translation};
    for (const ColmapPoint2D& p : image.points2D) {
      if (p.point3D_id != UINT64_MAX) view.point_ids.push_back(p.point3D_id);
    }
    std::sort(view.point_ids.begin(), view.point_ids.end());
    view.point_ids.erase(std::unique(view.point_ids.begin(), view.point_ids.end()), view.point_ids.end());
    views.push_back(std::move(view));
  }
  return views;
}

double SortedQuantile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return 0.0;
  return sorted[std::min(sorted.size() - 1, static_cast<size_t>(q * static_cast<double>(sorted.size())))];
}

void AddErrorStatistics(const DepthMap& depth, const DepthMap& truth, SgbmViewReport* report) {
  if (truth.width != depth.width || truth.height != depth.height) return;
  std::vector<double> errors;
  for (size_t p = 0; p < depth.num_pixels(); ++p) {
    if (IsValidDepth(depth.data[p]) && IsValidDepth(truth.data[p])) {
      errors.push_back(std::abs(static_cast<double>(depth.data[p]) - truth.data[p]));
    }
  }
  if (errors.empty()) return;
  std::sort(errors.begin(), errors.end());
  report->median_abs_error_m = SortedQuantile(errors, 0.5);
  report->p90_abs_error_m = SortedQuantile(errors, 0.9);
  const auto over = std::upper_bound(errors.begin(), errors.end(), 1.0);
  report->share_over_1m = static_cast<double>(errors.end() - over) / static_cast<double>(errors.size());
}

}  // namespace

SgbmPassSummary RunSgbmPass(const ColmapModel& model, const SgbmDepthOptions& options, const SgbmPassIo& io) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<StereoView> views = StereoViews(model, io.depth_downsample);
  SparsePoints points;
  for (const auto& [id, p] : model.points3D) points.emplace(id, p.xyz);
  const std::vector<std::vector<uint32_t>> sources = ChooseStereoSources(views, points, options.sources);

  std::map<uint32_t, cv::Mat> cache;
  std::vector<uint32_t> cache_order;
  const GreyImageLoader grey = [&](uint32_t i) -> cv::Mat {
    const auto it = cache.find(i);
    if (it != cache.end()) return it->second;
    const std::string path = (std::filesystem::path(io.images_dir) / views[i].name).string();
    cv::Mat image = cv::imread(path, cv::IMREAD_GRAYSCALE);
    if (image.empty()) throw Error(path + ": cannot read the image of view " + views[i].name + " for matching");
    if (image.cols != views[i].camera.width || image.rows != views[i].camera.height) {
      cv::Mat resized;
      cv::resize(image, resized, cv::Size(views[i].camera.width, views[i].camera.height), 0, 0, cv::INTER_AREA);
      image = resized;
    }
    if (cache.size() >= kCachedImages) {
      cache.erase(cache_order.front());
      cache_order.erase(cache_order.begin());
    }
    cache.emplace(i, image);
    cache_order.push_back(i);
    return image;
  };

  SgbmPassSummary summary;
  for (uint32_t v = 0; v < views.size(); ++v) {
    const auto view_start = std::chrono::steady_clock::now();
    const SgbmViewDepth result = ComputeSgbmDepth(v, views, points, sources[v], grey, options);
    io.write_maps(v, result.depth);
    SgbmViewReport report;
    report.name = views[v].name;
    for (const uint32_t s : result.sources) report.sources.push_back(views[s].name);
    report.pair_valid_fraction = result.pair_valid_fraction;
    report.valid_fraction = result.valid_fraction;
    if (io.true_depth) AddErrorStatistics(result.depth, io.true_depth(v), &report);
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - view_start).count();
    for (const float d : result.depth.data) summary.valid_pixels += IsValidDepth(d) ? 1 : 0;
    summary.pairs += result.sources.size();
    summary.match_seconds += result.match_seconds;
    summary.views.push_back(std::move(report));
    if (io.progress) io.progress(v + 1, views.size());
  }
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace sacfuse::sim
