#include "io/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <fcntl.h>
#include <unistd.h>

#include "core/error.h"
#include "io/process_identity.h"

namespace sacfuse {
namespace {

void FsyncFd(int fd, const std::string& what) {
  if (::fsync(fd) != 0) throw Error(what + ": fsync failed: " + std::strerror(errno));
}

// The host as it appears in temporary file names.
std::string HostInFileName(const std::string& host) {
  std::string name = host.substr(0, 64);
  for (char& c : name) {
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
                       c == '-' || c == '_';
    if (!plain) c = '_';
  }
  return name;
}

bool AllDigits(const std::string& t) {
  return !t.empty() && t.size() <= 18 && t.find_first_not_of("0123456789") == std::string::npos;
}

}  // namespace

std::string TemporaryPathFor(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  static const std::string host = HostInFileName(ThisHostName());
  return path + ".tmp-" + host + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

std::optional<TemporaryFileOwner> TemporaryFileOwnerOf(const std::string& file_name) {
  const size_t pos = file_name.rfind(".tmp-");
  if (pos == std::string::npos || pos == 0) return std::nullopt;
  const std::string tail = file_name.substr(pos + 5);  // [<host>-]<pid>-<n>
  const size_t last = tail.rfind('-');
  if (last == std::string::npos || last == 0 || !AllDigits(tail.substr(last + 1))) return std::nullopt;
  const std::string head = tail.substr(0, last);  // [<host>-]<pid>
  const size_t dash = head.rfind('-');
  TemporaryFileOwner owner;
  const std::string pid = dash == std::string::npos ? head : head.substr(dash + 1);
  if (!AllDigits(pid)) return std::nullopt;
  owner.pid = std::stoll(pid);
  if (dash != std::string::npos) {
    owner.host = head.substr(0, dash);
    if (owner.host.empty()) return std::nullopt;
  }
  return owner;
}

bool IsTemporaryFileName(const std::string& file_name) { return TemporaryFileOwnerOf(file_name).has_value(); }

bool TemporaryFileOwnerIsOnThisHost(const TemporaryFileOwner& owner) {
  return !owner.host.empty() && owner.host == HostInFileName(ThisHostName());
}

bool TemporaryFileOwnerIsGone(const TemporaryFileOwner& owner) {
  return TemporaryFileOwnerIsOnThisHost(owner) && ProcessIsGone(ThisHostName(), owner.pid);
}

std::vector<std::string> RemoveTemporaryFiles(const std::string& dir, bool recursive,
                                              const std::function<bool(const TemporaryFileOwner&)>& removable) {
  namespace fs = std::filesystem;
  std::error_code ec;
  std::vector<std::string> removed;
  if (!fs::is_directory(dir, ec)) return removed;
  std::vector<fs::path> temporary;
  const auto visit = [&](const fs::directory_entry& entry) {
    const bool file = entry.is_regular_file(ec);
    // A work folder named like a temporary file (io/copc_writer.h) goes with everything in it.
    const bool folder = !file && entry.is_directory(ec);
    if (!file && !folder) return;
    const std::optional<TemporaryFileOwner> owner = TemporaryFileOwnerOf(entry.path().filename().string());
    if (owner && removable(*owner)) temporary.push_back(entry.path());
  };
  if (recursive) {
    for (const auto& entry : fs::recursive_directory_iterator(dir, ec)) visit(entry);
  } else {
    for (const auto& entry : fs::directory_iterator(dir, ec)) visit(entry);
  }
  for (const auto& path : temporary) {
    if (fs::remove_all(path, ec) > 0) removed.push_back(path.string());
  }
  return removed;
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

std::string ReadSmallFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

}  // namespace sacfuse
