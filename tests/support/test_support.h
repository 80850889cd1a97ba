#pragma once
// Helpers for tests: a per-test temporary directory and the location of ../shared research data.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace sacfuse::testing {

// Whether this build carries a sanitizer (tools/sanitize.sh, tools/fuzz.sh): their shadow memory counts in a
// process's RSS (TSan ~5-10x), so tests of a memory budget skip their RSS bound there.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool kSanitizedBuild = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
inline constexpr bool kSanitizedBuild = true;
#else
inline constexpr bool kSanitizedBuild = false;
#endif
#else
inline constexpr bool kSanitizedBuild = false;
#endif

// A fresh empty directory under the system temp dir, removed when the object dies
// (kept when SACFUSE_KEEP_TEST_DIRS is set, for debugging).
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

// The shared research-data folder ($SACFUSE_SHARED, else ../shared next to the source tree), or nullopt when
// absent. Tests that need it call GTEST_SKIP() with a message when this is empty.
std::optional<std::filesystem::path> SharedDir();

// Path of the built sacfuse binary ($SACFUSE_BIN), for end-to-end tests.
std::string SacfuseBinary();

// The source tree ($SACFUSE_SOURCE_DIR, set by CTest for the end-to-end tests, else three folders above this
// file), for tests of committed files (generated docs, CMakeLists.txt's version).
std::filesystem::path SourceDir();

// Whole file as bytes ("" when it cannot be read).
std::string ReadFileBytes(const std::filesystem::path& path);

// A path as one single-quoted shell word (embedded quotes escaped).
std::string ShellQuote(const std::filesystem::path& path);

// Runs a shell command, returns its exit code; stdout+stderr go to *output when given.
int RunCommand(const std::string& command, std::string* output = nullptr);

// A shell command running in the background, its stdout+stderr collected in a file, for tests that race
// processes (with io/test_pause.h's SACFUSE_TEST_PAUSE to make the race deterministic). `env` entries
// ("NAME=value") are added to its environment. Killed (SIGKILL) if still running when destroyed.
class BackgroundCommand {
 public:
  explicit BackgroundCommand(const std::string& command, const std::vector<std::string>& env = {});
  ~BackgroundCommand();
  BackgroundCommand(const BackgroundCommand&) = delete;
  BackgroundCommand& operator=(const BackgroundCommand&) = delete;
  int pid() const { return pid_; }
  // Waits for it to end (at most `timeout_s`, then kills it and returns -1); its output into *output.
  int Wait(std::string* output = nullptr, double timeout_s = 300);
  // Whether it has ended (without waiting).
  bool Finished();
  // Its output so far.
  std::string Output() const;
  // Waits until its output contains `text`; false when it ends or `timeout_s` passes first.
  bool WaitForOutput(const std::string& text, double timeout_s = 120);

 private:
  int pid_ = -1;
  int status_ = -1;
  bool done_ = false;
  TempDir dir_;  // holds the output file
};

// The pid of a child process that has exited and been reaped: a pid that is not alive (for tests of clean-ups that
// keep files of live writers only).
int64_t GonePid();

// Waits until `path` exists; false after `timeout_s`.
bool WaitForFile(const std::filesystem::path& path, double timeout_s = 120);

}  // namespace sacfuse::testing
