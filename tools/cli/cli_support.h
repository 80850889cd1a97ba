#pragma once
// Shared pieces of the subcommands: logging setup, console verbosity (the global -v / -q / --log-level), progress
// display, error-to-exit-code mapping.
#include <chrono>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

namespace sacfuse::cli {

// Exit codes of every subcommand.
constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;      // bad input data or a failed run
constexpr int kExitConfigError = 2;  // bad config or command line

// The spdlog level names --log-level takes, most verbose first.
const std::vector<std::string>& LogLevelNames();
// What the console shows, chosen once by the global options before the command runs: a level name, or "" for
// each command's own default (run: log.level; status, report: warnings). Progress lines show only at info or more
// verbose.
void SetConsoleLevel(const std::string& level);

// Console logging at `level` (or the console level the global options set); when `log_file` is given, everything
// at `level` is also appended there (created if needed): the file keeps the config's log.level whatever -q or -v
// do to the console.
void SetupLogging(const std::string& level, const std::string& log_file = "");

// `text` with its words wrapped into lines of at most `width` characters; blank lines (paragraphs) are kept. For the
// footers of --help, which CLI11 prints as they are.
std::string WrapText(const std::string& text, size_t width = 100);

// Runs `body`, turning sacfuse exceptions into a logged message and an exit code.
int RunGuarded(const std::function<int()>& body);

// "stage done/total (pct%) elapsed, ETA" on stderr. On a terminal one line redrawn in place (\r) at most 4 times
// a second and ended at the end of each stage (a log message clears it first); in a log or a pipe one line at most
// once a second and at the end of each stage. Nothing when the console is quieter than info (-q).
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
