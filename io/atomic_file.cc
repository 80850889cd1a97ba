#include "io/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fcntl.h>
#include <unistd.h>

#include "core/error.h"

namespace sacfuse {
namespace {
void FsyncFd(int fd, const std::string& what) {
  if (::fsync(fd) != 0) throw Error(what + ": fsync failed: " + std::strerror(errno));
}
}  // namespace

std::string TemporaryPathFor(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  return path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

void FsyncPath(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) throw Error(path + ": cannot open for fsync: " + std::strerror(errno));
  try {
    FsyncFd(fd, path);
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
}

void CommitTemporaryFile(const std::string& temp_path, const std::string& final_path) {
  FsyncPath(temp_path);
  if (std::rename(temp_path.c_str(), final_path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    std::remove(temp_path.c_str());
    throw Error(final_path + ": cannot rename " + temp_path + " into place: " + reason);
  }
  auto parent = std::filesystem::path(final_path).parent_path();
  if (parent.empty()) parent = ".";
  const int dfd = ::open(parent.c_str(), O_RDONLY | O_DIRECTORY);
  if (dfd >= 0) {
    ::fsync(dfd);  // best effort: some file systems refuse fsync on folders
    ::close(dfd);
  }
}

void WriteFileAtomically(const std::string& path, const std::string& contents) {
  const auto parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  const std::string tmp = TemporaryPathFor(path);
  FILE* f = std::fopen(tmp.c_str(), "wb");
  if (f == nullptr) throw Error(path + ": cannot create " + tmp + ": " + std::strerror(errno));
  const bool ok = std::fwrite(contents.data(), 1, contents.size(), f) == contents.size();
  CloseAndCommitTemporaryFile(f, ok, tmp, path);
}

void CloseAndCommitTemporaryFile(FILE* file, bool write_ok, const std::string& temp_path,
                                 const std::string& final_path) {
  const bool closed = std::fclose(file) == 0;
  if (!write_ok || !closed) {
    std::remove(temp_path.c_str());
    throw Error(final_path + ": write failed (disk full?)");
  }
  CommitTemporaryFile(temp_path, final_path);
}

}  // namespace sacfuse
