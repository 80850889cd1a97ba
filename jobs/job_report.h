#pragma once
// The HTML report of a job (report/report_writer.h) with the job's input: what `sacfuse run` writes at its end and
// `sacfuse report` rewrites.
#include "config/job_config.h"
#include "report/report_writer.h"

namespace sacfuse {

// Default report options whose open_input opens config.input (jobs/open_input.h) when the report needs it.
ReportOptions JobReportOptions(const JobConfig& config);

}  // namespace sacfuse
