#include "jobs/job_report.h"

#include "jobs/open_input.h"

namespace sacfuse {

ReportOptions JobReportOptions(const JobConfig& config) {
  ReportOptions options;
  options.open_input = [input = config.input, crs = config.crs] { return OpenInput(input, crs); };
  return options;
}

}  // namespace sacfuse
