#pragma once
// Who a process is, for files that name their writer (temporary files, tile claims, the output folder's lock,
// DIR/run_state.json): its host name, pid and start time. Whether such a writer is gone can be proven only on its
// own host.
#include <cstdint>
#include <string>

namespace sacfuse {

// gethostname(), or "unknown-host".
std::string ThisHostName();
// Whether process `pid` of `host` is known to be gone: only on this host (kill(pid, 0) fails with ESRCH); false
// for other hosts and pid <= 0 (nothing can be proven there).
bool ProcessIsGone(const std::string& host, int64_t pid);
// Wall-clock time now, ns since the Unix epoch.
int64_t NowUnixNs();
// "2026-11-25 12:31:07 UTC" for a time in ns since the Unix epoch.
std::string UtcText(int64_t unix_ns);

}  // namespace sacfuse
