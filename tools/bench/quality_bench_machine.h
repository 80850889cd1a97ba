#pragma once
// `sacfuse bench`: the machine a bench ran on, for the header of its tables (cores as nproc counts them, RAM and
// the CPU model from /proc), and the time it ran.
#include <string>

namespace sacfuse::bench {

struct MachineInfo {
  int cores = 0;             // cores this process may use (sched_getaffinity, as nproc); 0 = unknown
  double ram_gib = 0.0;      // MemTotal of /proc/meminfo, GiB; 0 = unknown
  std::string cpu_model;     // first "model name" of /proc/cpuinfo; "unknown" when absent
};

MachineInfo ReadMachineInfo();
// "2 cores, 23.4 GiB RAM, Intel(R) Xeon(R) ..."
std::string DescribeMachine(const MachineInfo& machine);
// Now in UTC, "YYYY-MM-DD HH:MM:SS UTC".
std::string UtcNow();

}  // namespace sacfuse::bench
