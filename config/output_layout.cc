#include "config/output_layout.h"

#include <filesystem>

namespace sacfuse {
namespace {

std::string InOutputDir(const JobConfig& config, const std::string& name) {
  return (std::filesystem::path(config.output.dir) / name).string();
}

}  // namespace

std::string FusedLasPath(const JobConfig& config) { return FusedPathOfFormat(config, config.output.format); }
std::string FusedPathOfFormat(const JobConfig& config, const std::string& format) {
  return InOutputDir(config, format == "copc" ? "fused.copc.laz" : "fused." + format);
}
std::string TileIndexPath(const JobConfig& config) { return InOutputDir(config, "tiles.vpc"); }
std::string WriterLockPath(const JobConfig& config) { return InOutputDir(config, "sacfuse.lock"); }
std::string WorkersLockPath(const JobConfig& config) { return InOutputDir(config, "sacfuse.workers.lock"); }
std::string EffectiveConfigPath(const JobConfig& config) { return InOutputDir(config, "sacfuse.effective.yaml"); }
std::string RunReportPath(const JobConfig& config) { return InOutputDir(config, "run_report.json"); }
std::string EvalJsonPath(const JobConfig& config) { return InOutputDir(config, "eval.json"); }
std::string LogPath(const JobConfig& config) { return InOutputDir(config, "sacfuse.log"); }
std::string RunStatePath(const JobConfig& config) { return InOutputDir(config, "run_state.json"); }
std::string PlanJsonPath(const JobConfig& config) { return InOutputDir(config, "plan.json"); }
std::string CoregistrationPath(const JobConfig& config) { return InOutputDir(config, "coregistration.json"); }
std::string TilesDir(const JobConfig& config) { return InOutputDir(config, "tiles"); }
std::string ReportDir(const JobConfig& config) { return InOutputDir(config, "report"); }
std::string DsmPath(const JobConfig& config) { return InOutputDir(config, "dsm.tif"); }
std::string DsmVrtPath(const JobConfig& config) { return InOutputDir(config, "dsm.vrt"); }
std::string DsmBlocksDir(const JobConfig& config) { return InOutputDir(config, "dsm"); }
std::string OrthoPath(const JobConfig& config) { return InOutputDir(config, "ortho.tif"); }
std::string OrthoVrtPath(const JobConfig& config) { return InOutputDir(config, "ortho.vrt"); }
std::string OrthoBlocksDir(const JobConfig& config) { return InOutputDir(config, "ortho"); }

std::string SuperpixelCacheDir(const JobConfig& config) {
  return config.fusion.superpixel_cache_dir.empty() ? InOutputDir(config, "superpixels")
                                                    : config.fusion.superpixel_cache_dir;
}

std::string SuperpixelCachePath(const std::string& cache_dir, const std::string& image_name) {
  return (std::filesystem::path(cache_dir) / (image_name + ".spx")).string();
}

std::string ColourCachePath(const std::string& cache_dir, const std::string& image_name) {
  return (std::filesystem::path(cache_dir) / (image_name + ".rgb")).string();
}

}  // namespace sacfuse
