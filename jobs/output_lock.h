#pragma once
// One output folder, one writer (the way databases and build tools guard their folders):
//   DIR/sacfuse.lock          held exclusively by `sacfuse run` and `sacfuse merge` for their whole life
//                             (io/file_lock.h: flock, released by the kernel when the process dies). A second run or
//                             merge refuses at once, naming the holder's command, pid, host and start time, or
//                             waits for it (--wait). The file describes its holder (JSON): command, pid, host,
//                             start, and once known the result-settings hash and inputs digest of its job.
//   DIR/sacfuse.workers.lock  held shared by `sacfuse tile`, `sacfuse plan` and `sacfuse report`, which work beside
//                             a run by design; a writer takes it exclusively for a moment to prove that no other
//                             process is in the folder before it removes temporary files it cannot attribute.
// A `tile` worker accepts no work for another job: while a writer holds DIR with another result-settings hash or
// inputs digest, the worker refuses (CheckWorkerMatchesWriter). The second line of defence, which holds without
// any lock (NFS mounts without working locks, workers of older versions): a tile counts as done only when its
// marker carries the config hash and the inputs of the process that reads it (tiles/tile_marker.h), and a merge
// re-checks every marker before and after it writes the cloud (tiles/tile_merge.h).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "config/job_config.h"
#include "io/file_lock.h"

namespace sacfuse {

// Who holds DIR/sacfuse.lock, from its contents.
struct OutputWriter {
  std::string command;  // "run" | "merge"
  int64_t pid = 0;
  std::string host;
  int64_t started_unix_ns = 0;
  std::string config_hash;    // ResultSettingsHash of its resolved config ("" until known)
  std::string inputs_digest;  // IdentitiesDigest of its views ("" until known)
};
// "`sacfuse run` (pid 123 on host vm, started 2026-11-28 23:40:01 UTC)".
std::string DescribeOutputWriter(const OutputWriter& writer);

class OutputWriterLock {
 public:
  // Creates DIR and takes DIR/sacfuse.lock for `command` ("run", "merge"). Held by another process: throws Error
  // naming it ("... is writing <DIR>; one output folder has one writer: ..."), or with `wait` logs whom it waits
  // for and blocks until it is free. A file system that refuses locks: a warning, and the command goes on without
  // the lock (docs/output-folder.md says what then stays safe).
  OutputWriterLock(const JobConfig& config, const std::string& command, bool wait = false);
  // Records the job's result-settings hash and inputs digest in the lock file (read by `sacfuse tile` workers).
  void Record(const std::string& config_hash, const std::string& inputs_digest);
  bool locked() const { return lock_->locked(); }

 private:
  std::unique_ptr<FileLock> lock_;
  OutputWriter me_;
};

// The process holding DIR/sacfuse.lock now (probed without waiting), nullopt when none. The description is
// empty-fielded when the holder has not written it yet.
std::optional<OutputWriter> LiveOutputWriter(const JobConfig& config);

// Whether the process `pid` of `host` held DIR/sacfuse.lock (its description is in the file) and no longer does:
// it is gone, on any host whose locks reach this file. False when that cannot be told (another holder since, or
// a file system without locks).
bool OutputWriterIsGone(const JobConfig& config, const std::string& host, int64_t pid);

// The shared lock of `tile`, `plan` and `report` (blocks while a writer removes temporary files, a moment).
class OutputWorkerLock {
 public:
  explicit OutputWorkerLock(const JobConfig& config);

 private:
  std::unique_ptr<FileLock> lock_;
};

// For a `sacfuse tile` worker of result-settings hash `config_hash` and inputs digest `inputs_digest`: throws
// Error when a live writer holds DIR for a job with another hash or digest (its merge would not take this
// worker's tiles), naming the writer and what differs. Passes when there is no writer or it has not recorded
// them yet (the markers are then the check).
void CheckWorkerMatchesWriter(const JobConfig& config, const std::string& config_hash,
                              const std::string& inputs_digest);

// Deletes the temporary files ("<name>.tmp-<host>-<pid>-<n>", io/atomic_file.h) in DIR, DIR/tiles, DIR/report and
// the superpixel cache (recursive) whose writer is provably gone: named with this host and a pid that is not
// alive. A writer (`writer` held) also removes those it cannot attribute (other hosts', older versions') in the
// folders inside DIR when no other process is there: DIR/sacfuse.workers.lock is free and no tile claim is live.
// Logs each; returns how many were removed.
size_t RemoveTemporaryFilesOfGoneProcesses(const JobConfig& config, const OutputWriterLock* writer);

// After a run or merge wrote its cloud (config/output_layout.h FusedLasPath): removes the clouds of the other
// output.format values left by an earlier run (they would stay beside the new cloud, stale), logged.
void RemoveOtherFormatCloud(const JobConfig& config);

}  // namespace sacfuse
