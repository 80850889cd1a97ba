#include "tools/bench/quality_bench_machine.h"

#include <sched.h>

#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>

namespace sacfuse::bench {

MachineInfo ReadMachineInfo() {
  MachineInfo m;
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) == 0) m.cores = CPU_COUNT(&set);
  std::ifstream meminfo("/proc/meminfo");
  std::string line;
  while (std::getline(meminfo, line)) {
    if (line.rfind("MemTotal:", 0) == 0) {
      std::istringstream s(line.substr(9));
      double kib = 0;
      s >> kib;
      m.ram_gib = kib / (1024.0 * 1024.0);
      break;
    }
  }
  std::ifstream cpuinfo("/proc/cpuinfo");
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) {
      const size_t colon = line.find(':');
      if (colon != std::string::npos) m.cpu_model = line.substr(line.find_first_not_of(" \t", colon + 1));
      break;
    }
  }
  if (m.cpu_model.empty()) m.cpu_model = "unknown";
  return m;
}

std::string DescribeMachine(const MachineInfo& m) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.1f GiB RAM", m.ram_gib);
  return (m.cores > 0 ? std::to_string(m.cores) : std::string("?")) + " cores, " + text + ", " + m.cpu_model;
}

std::string UtcNow() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[64];
  std::strftime(text, sizeof(text), "%Y-%m-%d %H:%M:%S UTC", &utc);
  return text;
}

}  // namespace sacfuse::bench
