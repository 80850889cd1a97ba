#include "jobs/job_report.h"

#include "jobs/coregistered_block.h"
#include "jobs/open_input.h"

namespace sacfuse {

ReportOptions JobReportOptions(const JobConfig& config) {
  ReportOptions options;
  // The input as fused: the 'before' cross-section shows the depth maps with the poses the fusion used.
  options.open_input = [config] { return WithCoregisteredPoses(config, OpenInput(config.input, config.crs)); };
  return options;
}

}  // namespace sacfuse
