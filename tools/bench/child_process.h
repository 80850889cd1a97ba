#pragma once
// Running an external program as a child process and measuring it: wall time, the child's peak RSS and CPU
// time from wait4()'s rusage (no /usr/bin/time needed). Its stdout and stderr stream into a log file as it runs.
#include <string>
#include <vector>

namespace sacfuse {

struct ChildResult {
  int exit_code = -1;        // the child's exit status; 128 + N when it was killed by signal N (as a shell says)
  int term_signal = 0;       // N when killed by a signal, else 0
  double wall_s = 0.0;       // fork to reaped, seconds (steady clock)
  double peak_rss_mib = 0.0;  // ru_maxrss of the child (Linux reports KiB), MiB
  // This process's anonymous resident memory when it forked, MiB. Linux counts the pages a child inherits at fork
  // into its ru_maxrss even though exec drops them at once (so does /usr/bin/time's figure, from a tiny parent):
  // peak_rss_mib is never below about this, and a child that needs less than it is over-reported. Freed heap is
  // returned to the system (malloc_trim) before the fork to keep it small.
  double parent_rss_at_fork_mib = 0.0;
  double user_s = 0.0;       // CPU time of the child
  double system_s = 0.0;
};

// Full path of an executable: `name` itself when it contains a '/', else the first match on $PATH.
// "" when there is none (or it is not executable).
std::string FindExecutable(const std::string& name);

// Runs argv[0] (looked up on $PATH when it has no '/') with argv[1..], stdin from /dev/null, stdout and stderr
// appended to `log_path` (created with its folder; "" = inherited from this process). Waits for it.
// Throws sacfuse::Error when the log cannot be opened, fork fails, or the program cannot be executed (the message
// names the program and errno's text); a program that runs and fails is reported through exit_code.
ChildResult RunChildProcess(const std::vector<std::string>& argv, const std::string& log_path);

}  // namespace sacfuse
