#pragma once
// Process resource figures for run reports and benchmarks.
namespace sacfuse {
double PeakRssMiB();        // peak resident set size of this process so far, MiB
double ProcessCpuSeconds();  // user + system CPU time of this process, seconds
}  // namespace sacfuse
