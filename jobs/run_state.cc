#include "jobs/run_state.h"

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "io/atomic_file.h"
#include "io/json_text.h"
#include "io/process_identity.h"
#include "config/output_layout.h"
#include "jobs/output_lock.h"

namespace sacfuse {
namespace fs = std::filesystem;
namespace {

void WriteRunState(const JobConfig& config, const RunState& s) {
  const nlohmann::json j = {{"status", s.status},
                            {"started_unix_ns", s.started_unix_ns},
                            {"started", UtcText(s.started_unix_ns)},
                            {"ended_unix_ns", s.ended_unix_ns},
                            {"ended", s.ended_unix_ns ? UtcText(s.ended_unix_ns) : ""},
                            {"error", s.error},
                            {"pid", s.pid},
                            {"host", s.host},
                            {"last_success_unix_ns", s.last_success_unix_ns}};
  WriteFileAtomically(RunStatePath(config), JsonText(j, 2) + "\n");
}

}  // namespace

std::optional<RunState> ReadRunState(const JobConfig& config) {
  std::ifstream in(RunStatePath(config));
  if (!in) return std::nullopt;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    RunState s;
    s.status = j.at("status").get<std::string>();
    s.started_unix_ns = j.at("started_unix_ns").get<int64_t>();
    s.ended_unix_ns = j.at("ended_unix_ns").get<int64_t>();
    s.error = j.at("error").get<std::string>();
    s.pid = j.at("pid").get<int64_t>();
    s.host = j.at("host").get<std::string>();
    s.last_success_unix_ns = j.at("last_success_unix_ns").get<int64_t>();
    return s;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::optional<RunState> MarkRunStarted(const JobConfig& config) {
  RunState s;
  const std::optional<RunState> previous = ReadRunState(config);
  if (previous) s.last_success_unix_ns = previous->last_success_unix_ns;
  s.status = "running";
  s.started_unix_ns = NowUnixNs();
  s.pid = static_cast<int64_t>(::getpid());
  s.host = ThisHostName();
  WriteRunState(config, s);
  return previous;
}

void MarkRunRefused(const JobConfig& config, const std::optional<RunState>& previous) {
  if (previous) {
    WriteRunState(config, *previous);
  } else {
    std::error_code ec;
    fs::remove(RunStatePath(config), ec);
  }
}

void MarkRunEnded(const JobConfig& config, bool succeeded, const std::string& error) {
  RunState s = ReadRunState(config).value_or(RunState{});
  s.status = succeeded ? "succeeded" : "failed";
  s.ended_unix_ns = NowUnixNs();
  s.error = succeeded ? "" : error;
  if (succeeded) s.last_success_unix_ns = s.ended_unix_ns;
  WriteRunState(config, s);
}

std::string DescribeRunState(const JobConfig& config, bool* failed) {
  if (failed != nullptr) *failed = false;
  const auto s = ReadRunState(config);
  if (!s) return "";
  if (s->status == "succeeded") return "last run succeeded at " + UtcText(s->ended_unix_ns);
  std::string text;
  if (s->status == "failed") {
    text = "last run FAILED at " + UtcText(s->ended_unix_ns) + ": " + s->error;
  } else if (ProcessIsGone(s->host, s->pid) || OutputWriterIsGone(config, s->host, s->pid)) {
    // A "running" state whose process is gone (this host: its pid; any host: its lock released) was killed.
    text = "last run (pid " + std::to_string(s->pid) + ", started " + UtcText(s->started_unix_ns) +
           ") was INTERRUPTED: its process is gone";
  } else {
    return "a run is in progress (pid " + std::to_string(s->pid) + " on " + s->host + ", started " +
           UtcText(s->started_unix_ns) + ")";
  }
  if (failed != nullptr) *failed = true;
  const std::string fused = FusedLasPath(config);
  const std::string name = fs::path(fused).filename().string();
  struct stat st {};
  if (::stat(fused.c_str(), &st) != 0) return text + "\nno " + name + ": no run has completed";
  const int64_t written = static_cast<int64_t>(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
  if (written < s->started_unix_ns) {
    text += "\n" + name + " is from the previous successful run" +
            (s->last_success_unix_ns ? " at " + UtcText(s->last_success_unix_ns) : std::string());
  } else {
    text += "\n" + name + " was written by this run before it failed";
  }
  return text;
}

}  // namespace sacfuse
