#pragma once
// The state of the last `sacfuse run` of a job, DIR/run_state.json, written atomically: "running" when it starts,
// "succeeded" or "failed" (with the error) when it ends; a run killed meanwhile leaves "running" with a pid that
// is gone. The final outputs (fused.las/laz, run_report.json, eval.json, report/) are each replaced by a rename
// only once complete and only by a run that got that far, so after a failed run they are the previous run's: the
// state says so (`sacfuse status` and `sacfuse report` show it).
#include <cstdint>
#include <optional>
#include <string>

#include "config/job_config.h"

namespace sacfuse {

struct RunState {
  std::string status;  // "running" | "failed" | "succeeded"
  int64_t started_unix_ns = 0, ended_unix_ns = 0;
  std::string error;  // failed: why
  int64_t pid = 0;
  std::string host;
  int64_t last_success_unix_ns = 0;  // end of the last run that succeeded (0: none recorded)
};

std::optional<RunState> ReadRunState(const JobConfig& config);  // nullopt: none, or unreadable
// Writes "running" (keeping the previous last success); returns the previous state.
std::optional<RunState> MarkRunStarted(const JobConfig& config);
// A run refused for its config or command line (nothing computed, nothing replaced): puts `previous` back (or
// removes the state when there was none).
void MarkRunRefused(const JobConfig& config, const std::optional<RunState>& previous);
// Writes "succeeded" (last success = now) or "failed" with `error`.
void MarkRunEnded(const JobConfig& config, bool succeeded, const std::string& error = "");

// What to tell the user about the last run, one or two lines, e.g.
// "last run FAILED at 2026-11-25 12:31:07 UTC: <error>\nfused.laz is from the previous successful run at ...";
// *failed (may be null) is set when the last run failed or was interrupted. "" when there is no state.
std::string DescribeRunState(const JobConfig& config, bool* failed = nullptr);

}  // namespace sacfuse
