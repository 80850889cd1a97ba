#pragma once
// The run report page (report/index.html): one static HTML file with inline CSS and inline SVG, referring only
// to the PNG pictures beside it by relative name (no network, no scripts, no external fonts). Pure: data in,
// text out.
#include <string>
#include <vector>

#include "report/report_colours.h"
#include "report/report_data.h"
#include "report/report_figures.h"

namespace sacfuse {

// View colours of a report (by view order of run_report.json; see report/report_colours.h).
std::vector<Rgb> ReportViewColours(const ReportData& data);

// The whole page.
std::string RenderReportPage(const ReportData& data, const ReportFigures& figures);

// Redundancy removed by fusion: 1 - out / in (0 when in is 0).
double RedundancyRemoved(uint64_t points_in, uint64_t points_out);

}  // namespace sacfuse
