#pragma once
// An advisory lock on a file, flock(2): shared or exclusive, released by the kernel when the descriptor closes or
// the process dies (also by kill -9), so a lock is never left behind by a crash. The file itself stays (removing a
// lock file races with the next locker); its contents describe the holder for those who find it locked.
// NFS: Linux emulates flock with whole-file POSIX record locks there (NFSv4: the server's lock state, released when
// the client's lease lapses, ~90 s after a client dies; NFSv3: the NLM lock manager, lockd). POSIX locks of a
// process are dropped when ANY of its descriptors of the file closes, so a process must not open a lock file it
// holds a second time (a lock file's contents are read only by processes that do not hold it). With `local_lock=flock|all` or
// `nolock` mounts the locks are local to each client and exclude nothing across hosts.
#include <string>

namespace sacfuse {

class FileLock {
 public:
  enum class Mode { kShared, kExclusive };
  enum class Outcome {
    kLocked,
    kBusy,         // another process holds a conflicting lock
    kUnsupported,  // the file system refuses locks (ENOLCK, EOPNOTSUPP, ...): see error()
  };
  // Opens or creates `path` (its folder must exist; Error when it cannot be opened) and locks it. Without `wait`,
  // a conflicting lock is retried every 20 ms for `patience_s` (so a lock held only for a moment by a probe,
  // LockIsFree, is not taken for a holder) before kBusy; with `wait`, blocks until the lock is granted.
  FileLock(const std::string& path, Mode mode, double patience_s = 0.0, bool wait = false);
  ~FileLock();
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

  Outcome outcome() const { return outcome_; }
  bool locked() const { return outcome_ == Outcome::kLocked; }
  const std::string& path() const { return path_; }
  const std::string& error() const { return error_; }  // kUnsupported: the OS's reason
  // Replaces the file's contents through the held descriptor (a description of the holder); Error on failure.
  void WriteContents(const std::string& text);
  // Drops the lock (and the descriptor) before destruction.
  void Release();

 private:
  std::string path_;
  int fd_ = -1;
  Outcome outcome_ = Outcome::kBusy;
  std::string error_;
};

// Whether `mode` could be locked now: locks and unlocks at once (a probe). A file that does not exist is free.
// File systems that refuse locks count as free.
bool LockIsFree(const std::string& path, FileLock::Mode mode);

}  // namespace sacfuse
