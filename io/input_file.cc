#include "io/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/error.h"

namespace sacfuse {
namespace {

std::string KindOf(mode_t mode) {
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a file";
}

}  // namespace

void ThrowInputOsError(const std::string& path, const std::string& what, int err) {
  if (err == ENOENT) throw InputError(path, "missing " + what + ": it does not exist (cannot open it)");
  throw InputError(path, "cannot open " + what + ": " + std::strerror(err));
}

void CheckInputFile(const std::string& path, const std::string& what) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) ThrowInputOsError(path, what, errno);
  if (!S_ISREG(st.st_mode)) {
    throw InputError(path, "cannot read " + what + ": it is " + KindOf(st.st_mode) + ", not a regular file");
  }
  // Permission (and any other reason the OS has) shows only on open; non-blocking in case the path was swapped.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) ThrowInputOsError(path, what, errno);
  ::close(fd);
}

std::ifstream OpenInputStream(const std::string& path, const std::string& what) {
  CheckInputFile(path, what);
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) ThrowInputOsError(path, what, errno != 0 ? errno : EIO);
  return in;
}

}  // namespace sacfuse
