#pragma once
// Process resource figures for run reports and benchmarks.
namespace sacfuse {
double PeakRssMiB();        // peak resident set size of this process so far, MiB
double ProcessCpuSeconds();  // user + system CPU time of this process, seconds
double CurrentRssMiB();      // resident set size of this process now, MiB (0 where /proc is not available)
}  // namespace sacfuse
