#include "jobs/output_layout.h"

#include <filesystem>

namespace sacfuse {
namespace {

std::string InOutputDir(const JobConfig& config, const std::string& name) {
  return (std::filesystem::path(config.output.dir) / name).string();
}

}  // namespace

std::string FusedLasPath(const JobConfig& config) { return InOutputDir(config, "fused." + config.output.format); }
std::string EffectiveConfigPath(const JobConfig& config) { return InOutputDir(config, "sacfuse.effective.yaml"); }
std::string RunReportPath(const JobConfig& config) { return InOutputDir(config, "run_report.json"); }
std::string LogPath(const JobConfig& config) { return InOutputDir(config, "sacfuse.log"); }
std::string RunStatePath(const JobConfig& config) { return InOutputDir(config, "run_state.json"); }
std::string TilesDir(const JobConfig& config) { return InOutputDir(config, "tiles"); }

}  // namespace sacfuse
