#include "jobs/run_fusion.h"

#include <chrono>
#include <filesystem>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "core/backproject.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/colmap_workspace.h"
#include "io/las_writer.h"
#include "jobs/resource_usage.h"
#include "jobs/version.h"

namespace sacfuse {
namespace {

// Counts points per source view on their way to the real sink.
class CountingSink : public PointSink {
 public:
  explicit CountingSink(PointSink& next) : next_(next) {}
  void Write(const FusedPoint* points, size_t count) override {
    for (size_t i = 0; i < count; ++i) {
      if (points[i].view_index >= per_view_.size()) per_view_.resize(points[i].view_index + 1, 0);
      ++per_view_[points[i].view_index];
    }
    next_.Write(points, count);
  }
  uint64_t count(uint32_t view) const { return view < per_view_.size() ? per_view_[view] : 0; }

 private:
  PointSink& next_;
  std::vector<uint64_t> per_view_;
};

LasWriterOptions MakeLasOptions(const OutputOptions& output) {
  LasWriterOptions o;
  o.version_minor = output.las_version == "1.2" ? 2 : 4;
  o.scale_m = output.scale_m;
  o.generating_software = VersionString();
  return o;
}

void WriteRunReport(const RunSummary& s, const JobConfig& config) {
  nlohmann::json views = nlohmann::json::array();
  for (const auto& v : s.views) {
    views.push_back({{"name", v.name}, {"input_pixels", v.input_pixels}, {"output_points", v.output_points}});
  }
  const nlohmann::json j = {{"version", VersionString()},
                            {"config", config.source_file},
                            {"method", s.method},
                            {"fused_las", s.las_path},
                            {"input_points", s.input_points},
                            {"output_points", s.output_points},
                            {"wall_seconds", s.wall_seconds},
                            {"cpu_seconds", s.cpu_seconds},
                            {"peak_rss_mib", s.peak_rss_mib},
                            {"views", views}};
  WriteFileAtomically(s.report_path, j.dump(2) + "\n");
}

}  // namespace

std::string FusedLasPath(const JobConfig& config) {
  return (std::filesystem::path(config.output.dir) / "fused.las").string();
}

RunSummary RunFusionJob(const JobConfig& config, const RunProgress& progress) {
  ValidateJobConfig(config);
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = ProcessCpuSeconds();
  std::filesystem::create_directories(config.output.dir);

  RunSummary summary;
  summary.method = config.fusion.method;
  summary.las_path = FusedLasPath(config);
  summary.effective_config_path = (std::filesystem::path(config.output.dir) / "sacfuse.effective.yaml").string();
  summary.report_path = (std::filesystem::path(config.output.dir) / "run_report.json").string();
  WriteFileAtomically(summary.effective_config_path, DumpJobConfig(config, true));

  const ColmapWorkspace workspace(config.input.path, config.input.depth_type == "photometric"
                                                         ? ColmapDepthType::kPhotometric
                                                         : ColmapDepthType::kGeometric);
  const auto& views = workspace.views();
  if (views.empty()) throw InputError(config.input.path, "the workspace has no images to fuse");
  spdlog::info("input: {} views from {}", views.size(), config.input.path);
  spdlog::info("fusion method: {} (every valid depth pixel becomes a point; no fusion)", config.fusion.method);

  LasWriter writer(summary.las_path, MakeLasOptions(config.output));
  CountingSink counting(writer);
  for (size_t i = 0; i < views.size(); ++i) {
    const View& view = views[i];
    const DepthMap depth = workspace.ReadDepthMap(view);
    const RgbImage image = workspace.ReadImage(view);
    ViewRunStats stats;
    stats.name = view.name;
    stats.input_pixels = BackprojectDepthMap(view, depth, &image, counting);
    summary.input_points += stats.input_pixels;
    summary.views.push_back(stats);
    if (progress) progress("fuse", i + 1, views.size());
  }
  writer.Close();
  summary.output_points = writer.num_points();
  for (size_t i = 0; i < views.size(); ++i) summary.views[i].output_points = counting.count(views[i].index);

  summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  summary.cpu_seconds = ProcessCpuSeconds() - cpu_start;
  summary.peak_rss_mib = PeakRssMiB();
  WriteRunReport(summary, config);
  spdlog::info("wrote {} points to {} in {:.1f} s (peak RSS {:.0f} MiB)", summary.output_points, summary.las_path,
               summary.wall_seconds, summary.peak_rss_mib);
  return summary;
}

}  // namespace sacfuse
