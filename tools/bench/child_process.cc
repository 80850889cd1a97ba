#include "tools/bench/child_process.h"

#include <fcntl.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "core/error.h"

namespace sacfuse {
namespace {

bool IsExecutableFile(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

double Seconds(const timeval& t) { return t.tv_sec + t.tv_usec * 1e-6; }

// Anonymous resident memory of this process (RssAnon in /proc/self/status), MiB; 0 when unavailable. These are
// the pages a forked child starts with (file-backed pages are not copied at fork).
double AnonymousRssMiB() {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return 0.0;
  char line[256];
  double kib = 0.0;
  while (std::fgets(line, sizeof(line), f)) {
    if (std::strncmp(line, "RssAnon:", 8) == 0) {
      kib = std::strtod(line + 8, nullptr);
      break;
    }
  }
  std::fclose(f);
  return kib / 1024.0;
}

// Writes all of `size` bytes (the child's report of a failed exec), ignoring errors.
void WriteAll(int fd, const void* data, size_t size) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, p, size);
    if (n <= 0 && errno != EINTR) return;
    if (n > 0) {
      p += n;
      size -= static_cast<size_t>(n);
    }
  }
}

}  // namespace

std::string FindExecutable(const std::string& name) {
  if (name.empty()) return "";
  if (name.find('/') != std::string::npos) return IsExecutableFile(name) ? name : "";
  const char* path_env = std::getenv("PATH");
  const std::string path = path_env ? path_env : "/usr/local/bin:/usr/bin:/bin";
  size_t begin = 0;
  while (begin <= path.size()) {
    const size_t end = std::min(path.find(':', begin), path.size());
    const std::string dir = end > begin ? path.substr(begin, end - begin) : ".";
    const std::string candidate = dir + "/" + name;
    if (IsExecutableFile(candidate)) return candidate;
    begin = end + 1;
  }
  return "";
}

ChildResult RunChildProcess(const std::vector<std::string>& argv, const std::string& log_path) {
  if (argv.empty()) throw Error("RunChildProcess: no program given");
  const std::string program = FindExecutable(argv[0]);
  if (program.empty()) throw Error("cannot run \"" + argv[0] + "\": not found or not executable");

  int log_fd = -1;
  if (!log_path.empty()) {
    const auto parent = std::filesystem::path(log_path).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    log_fd = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (log_fd < 0) throw InputError(log_path, std::string("cannot open log file: ") + std::strerror(errno));
  }
  // The child reports a failed exec through this close-on-exec pipe; a successful exec closes it unwritten.
  int report[2];
  if (::pipe2(report, O_CLOEXEC) != 0) {
    if (log_fd >= 0) ::close(log_fd);
    throw Error(std::string("pipe failed: ") + std::strerror(errno));
  }
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args[0] = const_cast<char*>(program.c_str());
  args.push_back(nullptr);

#ifdef __GLIBC__
  ::malloc_trim(0);  // give freed heap back first: the child's ru_maxrss counts what it inherits
#endif
  const double parent_rss_mib = AnonymousRssMiB();
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int err = errno;
    ::close(report[0]);
    ::close(report[1]);
    if (log_fd >= 0) ::close(log_fd);
    throw Error(std::string("fork failed: ") + std::strerror(err));
  }
  if (pid == 0) {
    // Child: only async-signal-safe calls from here on.
    ::close(report[0]);
    const int null_fd = ::open("/dev/null", O_RDONLY);
    if (null_fd >= 0) ::dup2(null_fd, STDIN_FILENO);
    if (log_fd >= 0) {
      ::dup2(log_fd, STDOUT_FILENO);
      ::dup2(log_fd, STDERR_FILENO);
    }
    ::execv(program.c_str(), args.data());
    const int err = errno;
    WriteAll(report[1], &err, sizeof(err));
    ::_exit(127);
  }
  ::close(report[1]);
  if (log_fd >= 0) ::close(log_fd);
  int exec_errno = 0;
  ssize_t got = 0;
  do {
    got = ::read(report[0], &exec_errno, sizeof(exec_errno));
  } while (got < 0 && errno == EINTR);
  ::close(report[0]);

  int status = 0;
  rusage usage{};
  pid_t waited = 0;
  do {
    waited = ::wait4(pid, &status, 0, &usage);
  } while (waited < 0 && errno == EINTR);
  const auto end = std::chrono::steady_clock::now();
  if (waited < 0) throw Error("wait4 for \"" + program + "\" failed: " + std::strerror(errno));
  if (got == static_cast<ssize_t>(sizeof(exec_errno))) {
    throw Error("cannot execute \"" + program + "\": " + std::strerror(exec_errno));
  }

  ChildResult result;
  if (WIFEXITED(status)) {
    result.exit_code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    result.term_signal = WTERMSIG(status);
    result.exit_code = 128 + result.term_signal;
  }
  result.wall_s = std::chrono::duration<double>(end - start).count();
  result.peak_rss_mib = usage.ru_maxrss / 1024.0;  // KiB on Linux
  result.parent_rss_at_fork_mib = parent_rss_mib;
  result.user_s = Seconds(usage.ru_utime);
  result.system_s = Seconds(usage.ru_stime);
  return result;
}

}  // namespace sacfuse
