#include "io/file_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>

#include "core/error.h"

namespace sacfuse {
namespace {

// flock(2), retried on EINTR; 0 or the errno value.
int Flock(int fd, int operation) {
  while (::flock(fd, operation) != 0) {
    if (errno != EINTR) return errno;
  }
  return 0;
}

bool IsBusy(int err) { return err == EWOULDBLOCK || err == EAGAIN; }

}  // namespace

FileLock::FileLock(const std::string& path, Mode mode, double patience_s, bool wait) : path_(path) {
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw Error(path + ": cannot open lock file: " + std::strerror(errno));
  const int op = mode == Mode::kExclusive ? LOCK_EX : LOCK_SH;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::duration<double>(patience_s);
  for (;;) {
    const int err = Flock(fd_, wait ? op : op | LOCK_NB);
    if (err == 0) {
      outcome_ = Outcome::kLocked;
      return;
    }
    if (!IsBusy(err)) {
      outcome_ = Outcome::kUnsupported;
      error_ = std::strerror(err);
      break;
    }
    if (std::chrono::steady_clock::now() >= give_up) {
      outcome_ = Outcome::kBusy;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ::close(fd_);
  fd_ = -1;
}

FileLock::~FileLock() { Release(); }

void FileLock::Release() {
  if (fd_ >= 0) ::close(fd_);  // closing drops the lock
  fd_ = -1;
  if (outcome_ == Outcome::kLocked) outcome_ = Outcome::kBusy;
}

void FileLock::WriteContents(const std::string& text) {
  if (fd_ < 0) throw Error(path_ + ": lock not held");
  if (::ftruncate(fd_, 0) != 0 ||
      ::pwrite(fd_, text.data(), text.size(), 0) != static_cast<ssize_t>(text.size())) {
    throw Error(path_ + ": cannot write lock file: " + std::strerror(errno));
  }
}

bool LockIsFree(const std::string& path, FileLock::Mode mode) {
  // NFS grants an exclusive (POSIX) lock only on a descriptor open for writing.
  int fd = ::open(path.c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0 && mode == FileLock::Mode::kShared) fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return true;
  const int err = Flock(fd, (mode == FileLock::Mode::kExclusive ? LOCK_EX : LOCK_SH) | LOCK_NB);
  ::close(fd);  // drops the probe's lock
  return !IsBusy(err);
}

}  // namespace sacfuse
