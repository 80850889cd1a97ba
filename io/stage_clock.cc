#include "io/stage_clock.h"

#include <algorithm>
#include <cstdio>

#include "io/resource_usage.h"

namespace sacfuse {
namespace {

double Since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

StageClock::StageClock()
    : start_(std::chrono::steady_clock::now()), stage_start_(start_), cpu_start_(ProcessCpuSeconds()),
      stage_cpu_start_(cpu_start_) {}

const StageTime& StageClock::Mark(const std::string& name) {
  const auto now = std::chrono::steady_clock::now();
  const double cpu = ProcessCpuSeconds();
  stages_.push_back({name, std::chrono::duration<double>(now - stage_start_).count(), cpu - stage_cpu_start_,
                     PeakRssMiB(), CurrentRssMiB()});
  stage_start_ = now;
  stage_cpu_start_ = cpu;
  return stages_.back();
}

void StageClock::Skip() {
  stage_start_ = std::chrono::steady_clock::now();
  stage_cpu_start_ = ProcessCpuSeconds();
}

double StageClock::TotalWallSeconds() const { return Since(start_); }

double StageClock::TotalCpuSeconds() const { return ProcessCpuSeconds() - cpu_start_; }

std::string FormatStageTable(const std::vector<StageTime>& stages, double total_wall_s, double total_cpu_s) {
  size_t width = 5;  // "total"
  for (const StageTime& s : stages) width = std::max(width, s.name.size());
  std::string out;
  char line[256];
  const auto row = [&](const std::string& name, double wall, double cpu, double peak_mib) {
    std::snprintf(line, sizeof(line), "  %-*s %9.2f %9.2f %8.2f %9.0f\n", static_cast<int>(width), name.c_str(),
                  wall, cpu, wall > 0 ? cpu / wall : 0.0, peak_mib);
    out += line;
  };
  std::snprintf(line, sizeof(line), "  %-*s %9s %9s %8s %9s\n", static_cast<int>(width), "stage", "wall s", "CPU s",
                "CPU/wall", "peak MiB");
  out += line;
  for (const StageTime& s : stages) row(s.name, s.wall_s, s.cpu_s, s.peak_rss_mib);
  row("total", total_wall_s, total_cpu_s, PeakRssMiB());
  return out;
}

}  // namespace sacfuse
