#include "jobs/output_lock.h"

#include <unistd.h>

#include <filesystem>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "config/output_layout.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/json_text.h"
#include "io/process_identity.h"
#include "tiles/tile_claim.h"

namespace sacfuse {
namespace fs = std::filesystem;
namespace {

// A probe of another process (LiveOutputWriter, a `tile` worker starting) holds the lock for a moment: a writer
// retries this long before it calls the folder busy.
constexpr double kWriterLockPatienceS = 1.0;

std::string WriterJson(const OutputWriter& w) {
  return JsonText({{"command", w.command},
                   {"pid", w.pid},
                   {"host", w.host},
                   {"started_unix_ns", w.started_unix_ns},
                   {"started", UtcText(w.started_unix_ns)},
                   {"config_hash", w.config_hash},
                   {"inputs_digest", w.inputs_digest}},
                  2) +
         "\n";
}

// The holder described in the lock file; nullopt while it is being written or when it is not ours.
std::optional<OutputWriter> ParseWriter(const std::string& text) {
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    OutputWriter w;
    w.command = j.at("command").get<std::string>();
    w.pid = j.at("pid").get<int64_t>();
    w.host = j.at("host").get<std::string>();
    w.started_unix_ns = j.at("started_unix_ns").get<int64_t>();
    w.config_hash = j.value("config_hash", "");
    w.inputs_digest = j.value("inputs_digest", "");
    return w;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::string DescribeHolder(const std::string& lock_path) {
  const auto w = ParseWriter(ReadSmallFile(lock_path));
  return w ? DescribeOutputWriter(*w) : "another sacfuse process (starting: " + lock_path + " names no holder yet)";
}

}  // namespace

std::string DescribeOutputWriter(const OutputWriter& w) {
  return "`sacfuse " + w.command + "` (pid " + std::to_string(w.pid) + " on host " + w.host + ", started " +
         UtcText(w.started_unix_ns) + ")";
}

OutputWriterLock::OutputWriterLock(const JobConfig& config, const std::string& command, bool wait) {
  fs::create_directories(config.output.dir);
  const std::string path = WriterLockPath(config);
  lock_ = std::make_unique<FileLock>(path, FileLock::Mode::kExclusive, kWriterLockPatienceS);
  if (lock_->outcome() == FileLock::Outcome::kBusy) {
    const std::string holder = DescribeHolder(path);
    if (!wait) {
      throw Error(config.output.dir + ": " + holder + " is writing this output folder; one output folder has one "
                  "writer: wait for it to finish (`sacfuse " + command + " --wait` waits; `sacfuse status CONFIG` "
                  "shows it), or give this config another output.dir");
    }
    spdlog::info("waiting for {} to finish writing {}", holder, config.output.dir);
    lock_ = std::make_unique<FileLock>(path, FileLock::Mode::kExclusive, 0.0, /*wait=*/true);
  }
  if (lock_->outcome() == FileLock::Outcome::kUnsupported) {
    spdlog::warn("{}: the file system refuses locks ({}): `sacfuse {}` goes on without the one-writer lock, so a "
                 "second run or merge on this folder is not refused (the tiles' config hashes and inputs are still "
                 "checked before a merge; see docs/output-folder.md)",
                 path, lock_->error(), command);
    return;
  }
  me_.command = command;
  me_.pid = static_cast<int64_t>(::getpid());
  me_.host = ThisHostName();
  me_.started_unix_ns = NowUnixNs();
  lock_->WriteContents(WriterJson(me_));
}

void OutputWriterLock::Record(const std::string& config_hash, const std::string& inputs_digest) {
  if (!lock_->locked()) return;
  me_.config_hash = config_hash;
  me_.inputs_digest = inputs_digest;
  lock_->WriteContents(WriterJson(me_));
}

std::optional<OutputWriter> LiveOutputWriter(const JobConfig& config) {
  const std::string path = WriterLockPath(config);
  if (LockIsFree(path, FileLock::Mode::kShared)) return std::nullopt;
  return ParseWriter(ReadSmallFile(path)).value_or(OutputWriter{});
}

bool OutputWriterIsGone(const JobConfig& config, const std::string& host, int64_t pid) {
  const std::string path = WriterLockPath(config);
  const std::optional<OutputWriter> last = ParseWriter(ReadSmallFile(path));
  return last && last->pid == pid && last->host == host && LockIsFree(path, FileLock::Mode::kShared);
}

OutputWorkerLock::OutputWorkerLock(const JobConfig& config) {
  fs::create_directories(config.output.dir);
  lock_ = std::make_unique<FileLock>(WorkersLockPath(config), FileLock::Mode::kShared, 0.0, /*wait=*/true);
}

void CheckWorkerMatchesWriter(const JobConfig& config, const std::string& config_hash,
                              const std::string& inputs_digest) {
  const std::optional<OutputWriter> writer = LiveOutputWriter(config);
  if (!writer) return;
  std::string differs;
  if (!writer->config_hash.empty() && writer->config_hash != config_hash) {
    differs = "other result-affecting settings (config hash " + writer->config_hash + ", this worker's " +
              config_hash + ")";
  } else if (!writer->inputs_digest.empty() && writer->inputs_digest != inputs_digest) {
    differs = "other inputs (inputs digest " + writer->inputs_digest + ", this worker's " + inputs_digest +
              ": a depth map, image or pose changed since it started)";
  }
  if (differs.empty()) return;
  throw Error(config.output.dir + ": " + DescribeOutputWriter(*writer) + " is writing this output folder with " +
              differs + "; its merge would not take this worker's tiles: run the workers with that run's config "
              "and inputs, or give this config another output.dir");
}

size_t RemoveTemporaryFilesOfGoneProcesses(const JobConfig& config, const OutputWriterLock* writer) {
  const std::string tiles_dir = TilesDir(config);
  // Held exclusively while the wider rule removes: workers starting meanwhile wait for it.
  std::unique_ptr<FileLock> workers;
  bool alone = false;
  if (writer != nullptr && writer->locked()) {
    workers = std::make_unique<FileLock>(WorkersLockPath(config), FileLock::Mode::kExclusive);
    alone = workers->locked() && !AnyLiveTileClaim(tiles_dir, config.tiling.claim_timeout_s);
  }
  size_t removed = 0, kept = 0;
  const auto remove = [&](const std::string& dir, bool recursive, bool inside_dir) {
    const auto removable = [&](const TemporaryFileOwner& owner) {
      if (TemporaryFileOwnerIsGone(owner)) return true;
      // Alone in DIR: what cannot be attributed (other hosts', older versions') is left by processes that are gone;
      // a live pid of this host is never among them.
      if (alone && inside_dir && !TemporaryFileOwnerIsOnThisHost(owner)) return true;
      ++kept;
      return false;
    };
    for (const std::string& path : RemoveTemporaryFiles(dir, recursive, removable)) {
      spdlog::info("removed {} (left by a process that is gone)", path);
      ++removed;
    }
  };
  remove(config.output.dir, false, true);
  remove(tiles_dir, false, true);
  remove(ReportDir(config), false, true);
  remove(DsmBlocksDir(config), false, true);
  remove(SuperpixelCacheDir(config), true, config.fusion.superpixel_cache_dir.empty());
  if (removed > 0) spdlog::info("removed {} temporary files left by processes that are gone", removed);
  if (kept > 0) {
    spdlog::info("kept {} temporary files whose writers may be alive (other hosts or other sacfuse processes in "
                 "this folder)", kept);
  }
  return removed;
}

void RemoveOtherFormatCloud(const JobConfig& config) {
  for (const std::string format : {"laz", "las", "copc"}) {
    if (format == config.output.format) continue;
    const std::string other = FusedPathOfFormat(config, format);
    std::error_code ec;
    if (!fs::exists(other, ec)) continue;
    if (fs::remove(other, ec)) {
      spdlog::info("removed {}: the cloud of an earlier run with output.format {} (this one wrote {})", other, format,
                   FusedLasPath(config));
    } else {
      spdlog::warn("{} (an earlier run's cloud with another output.format) is stale and could not be removed: {}",
                   other, ec.message());
    }
  }
}

}  // namespace sacfuse
