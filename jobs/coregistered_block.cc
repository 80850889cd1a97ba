#include "jobs/coregistered_block.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>

#include "config/output_layout.h"
#include "config/version.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/view_identity.h"
#include "io/json_text.h"

namespace sacfuse {

// The summary as coregistration.json keeps it: one list of fields for writing and reading.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(CoregistrationSummary, median_rotation_deg, max_rotation_deg, median_shift_m,
                                   max_shift_m, median_rms_before_m, median_rms_after_m)

namespace {

constexpr const char* kFormat = "sacfuse-coregistration-1";

// The coregistration.* keys and values: what the poses depend on besides the inputs.
nlohmann::json OptionsJson(const JobConfig& config) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [key, value] : JobConfigValues(config)) {
    if (key.rfind("coregistration.", 0) == 0) j[key] = value;
  }
  return j;
}

// Each view's depth map decimated, with the camera of the decimated raster.
std::vector<CoregistrationInput> ReadDecimated(const DepthBlock& input, const CoregistrationOptions& o,
                                               int* max_decimation) {
  const std::vector<View>& views = input.views();
  std::vector<CoregistrationInput> out(views.size());
  std::vector<int> factor(views.size(), 1);
  tbb::parallel_for(size_t{0}, views.size(), [&](size_t i) {
    const DepthRasterSize size = input.DepthSize(views[i]);
    const int k = CoregistrationDecimation(size.width, size.height, o.max_pixels_per_view);
    const PinholeCamera cam = views[i].camera.Scaled(size.width, size.height);
    out[i].view = views[i];
    // Only the rows the decimation keeps are read (1 / k of each map where the format allows it).
    out[i].depth = DecimateDepthRows(input.ReadDepthRows(views[i], DecimatedRows(size.height, k)), k);
    out[i].depth_camera = {out[i].depth.width, out[i].depth.height, cam.fx / k, cam.fy / k, cam.cx / k, cam.cy / k};
    factor[i] = k;
  }, tbb::simple_partitioner());
  *max_decimation = *std::max_element(factor.begin(), factor.end());
  return out;
}

nlohmann::json PoseJson(const Rigid3d& p) {
  const Eigen::Quaterniond& q = p.rotation;
  return {{"qw", q.w()}, {"qx", q.x()}, {"qy", q.y()}, {"qz", q.z()},
          {"tx", p.translation.x()}, {"ty", p.translation.y()}, {"tz", p.translation.z()}};
}

Rigid3d PoseFromJson(const nlohmann::json& j) {
  Rigid3d p;
  p.rotation = Eigen::Quaterniond(j.at("qw").get<double>(), j.at("qx").get<double>(), j.at("qy").get<double>(),
                                  j.at("qz").get<double>());
  p.translation = {j.at("tx").get<double>(), j.at("ty").get<double>(), j.at("tz").get<double>()};
  return p;
}

nlohmann::json ResultJson(const DepthBlock& input, const CoregistrationResult& r, const std::string& digest,
                          const JobConfig& config, int decimation) {
  nlohmann::json views = nlohmann::json::array();
  for (size_t i = 0; i < r.views.size(); ++i) {
    const ViewCorrection& v = r.views[i];
    views.push_back({{"name", input.views()[i].name}, {"cam_from_world", PoseJson(v.cam_from_world)},
                     {"rotation_deg", v.rotation_deg}, {"shift_m", {v.shift_m.x(), v.shift_m.y(), v.shift_m.z()}},
                     {"samples", v.samples}, {"residuals_before", v.residuals_before},
                     {"residuals_after", v.residuals_after}, {"rms_before_m", v.rms_before_m},
                     {"rms_after_m", v.rms_after_m}});
  }
  nlohmann::json iterations = nlohmann::json::array();
  for (const CoregistrationIteration& it : r.iterations) {
    iterations.push_back({{"residuals", it.residuals}, {"weighted_rms_m", it.weighted_rms_m},
                          {"median_step_deg", it.median_step_deg}, {"median_step_m", it.median_step_m}});
  }
  return {{"format", kFormat}, {"version", FullVersionString()}, {"inputs_digest", digest}, {"options", OptionsJson(config)},
          {"decimation", decimation}, {"pairs", r.pairs}, {"summary", r.summary}, {"iterations", iterations},
          {"views", views}};
}

void Summarise(const nlohmann::json& file, CoregistrationOutcome* o) {
  o->summary = file.at("summary").get<CoregistrationSummary>();
  o->decimation = file.at("decimation").get<int>();
}

// The poses of a current DIR/coregistration.json, or none (no file, other inputs or options, unreadable).
bool ReadCurrent(const std::string& path, const DepthBlock& input, const std::string& digest,
                 const JobConfig& config, nlohmann::json* file, std::vector<Rigid3d>* poses) {
  if (!std::filesystem::exists(path)) return false;
  CoregistrationOutcome checked;
  try {
    std::ifstream in(path);
    *file = nlohmann::json::parse(in);
    if (file->at("format") != kFormat) return false;
    if (file->at("inputs_digest") != digest) {
      spdlog::info("co-registration: {} was made from other inputs; computing again", path);
      return false;
    }
    if (file->at("options") != OptionsJson(config)) {
      spdlog::info("co-registration: {} was made with other coregistration.* options; computing again", path);
      return false;
    }
    const nlohmann::json& views = file->at("views");
    if (views.size() != input.views().size()) return false;
    Summarise(*file, &checked);  // throws when the summary is missing or malformed
    poses->clear();
    for (size_t i = 0; i < views.size(); ++i) {
      if (views[i].at("name") != input.views()[i].name) return false;
      poses->push_back(PoseFromJson(views[i].at("cam_from_world")));
    }
    return true;
  } catch (const std::exception& e) {
    spdlog::warn("co-registration: {} cannot be read ({}); computing again", path, e.what());
    return false;
  }
}

}  // namespace

std::unique_ptr<DepthBlock> WithCoregisteredPoses(const JobConfig& config, std::unique_ptr<DepthBlock> input,
                                                  CoregistrationOutcome* outcome) {
  CoregistrationOutcome local;
  CoregistrationOutcome& out = outcome != nullptr ? *outcome : local;
  out.enabled = config.coregistration.enabled;
  if (!out.enabled) return input;
  const auto start = std::chrono::steady_clock::now();
  const std::string path = CoregistrationPath(config);
  const std::string digest = IdentitiesDigest(IdentifyBlock(*input).views);
  nlohmann::json file;
  std::vector<Rigid3d> poses;
  out.reused = ReadCurrent(path, *input, digest, config, &file, &poses);
  if (!out.reused) {
    int decimation = 1;
    const std::vector<CoregistrationInput> decimated = ReadDecimated(*input, config.coregistration, &decimation);
    spdlog::info("co-registration: {} depth maps read and decimated (k <= {}) in {:.1f} s", decimated.size(),
                 decimation, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    const CoregistrationResult result = Coregister(decimated, config.coregistration);
    for (size_t i = 0; i < result.iterations.size(); ++i) {
      const CoregistrationIteration& it = result.iterations[i];
      spdlog::info("co-registration pass {}: {} residuals, weighted rms {:.3f} m{}", i, it.residuals,
                   it.weighted_rms_m,
                   i + 1 < result.iterations.size()
                       ? fmt::format(", step median {:.4f} deg, {:.3f} m", it.median_step_deg, it.median_step_m)
                       : std::string(" (after the last step)"));
    }
    file = ResultJson(*input, result, digest, config, decimation);
    std::filesystem::create_directories(config.output.dir);
    WriteFileAtomically(path, JsonText(file, 1) + "\n");
    for (const ViewCorrection& v : result.views) poses.push_back(v.cam_from_world);
  }
  Summarise(file, &out);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const CoregistrationSummary& m = out.summary;
  spdlog::info("co-registration of {} views {} in {:.1f} s: rotation median {:.4f} / max {:.4f} deg, shift median "
               "{:.3f} / max {:.3f} m, residual rms median {:.3f} -> {:.3f} m ({})",
               poses.size(), out.reused ? "reused" : "computed", out.seconds, m.median_rotation_deg,
               m.max_rotation_deg, m.median_shift_m, m.max_shift_m, m.median_rms_before_m, m.median_rms_after_m, path);
  return std::make_unique<ReposedBlock>(std::move(input), poses);
}

}  // namespace sacfuse
