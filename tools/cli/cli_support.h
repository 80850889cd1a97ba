#pragma once
// Shared pieces of the subcommands: logging setup, progress display, error-to-exit-code mapping.
#include <chrono>
#include <functional>
#include <mutex>
#include <string>

namespace sacfuse::cli {

// Exit codes of every subcommand.
constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;      // bad input data or a failed run
constexpr int kExitConfigError = 2;  // bad config or command line

// Console logging at `level`; when `log_file` is given, everything is also appended there (created if needed).
void SetupLogging(const std::string& level, const std::string& log_file = "");

// Runs `body`, turning sacfuse exceptions into a logged message and an exit code.
int RunGuarded(const std::function<int()>& body);

// Prints "stage done/total (pct%) elapsed, ETA" to stderr at most once a second and at the end of each stage.
class ProgressPrinter {
 public:
  void operator()(const std::string& stage, size_t done, size_t total);

 private:
  std::mutex mutex_;
  std::string stage_;
  std::chrono::steady_clock::time_point stage_start_;
  std::chrono::steady_clock::time_point last_print_;
};

}  // namespace sacfuse::cli
