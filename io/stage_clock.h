#pragma once
// The wall and CPU seconds of each stage of a job, in the order the stages ran: run_report.json's "stages" and the
// log's stage table (jobs/run_fusion.h). Stages follow one another (a stage's own work may be parallel): CPU seconds
// are the process's (user + system, io/resource_usage.h) between the stage's start and end, so they include every
// thread's work, and cpu_s / wall_s is the stage's mean parallelism.
#include <chrono>
#include <string>
#include <vector>

namespace sacfuse {

struct StageTime {
  std::string name;
  double wall_s = 0.0;
  double cpu_s = 0.0;
  double peak_rss_mib = 0.0;  // the process's peak RSS so far, at the stage's end (it rose in this stage when
                              // it exceeds the previous stage's)
  double rss_mib = 0.0;       // the process's RSS at the stage's end
};

class StageClock {
 public:
  StageClock();  // the first stage starts now
  // Ends the stage that started at the previous Mark (or at construction) and names it; the next one starts now.
  const StageTime& Mark(const std::string& name);
  // Restarts the current stage now, leaving the time since the previous Mark out of every stage.
  void Skip();
  const std::vector<StageTime>& stages() const { return stages_; }
  // Since construction.
  double TotalWallSeconds() const;
  double TotalCpuSeconds() const;

 private:
  std::chrono::steady_clock::time_point start_, stage_start_;
  double cpu_start_ = 0.0, stage_cpu_start_ = 0.0;
  std::vector<StageTime> stages_;
};

// "stage  wall s  CPU s  CPU/wall  peak RSS MiB" lines, one per stage and a total, for the log.
std::string FormatStageTable(const std::vector<StageTime>& stages, double total_wall_s, double total_cpu_s);

}  // namespace sacfuse
