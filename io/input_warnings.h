#pragma once
// Warnings about input files that do not stop a run: a truncated image that still decodes, libtiff's warnings
// about a depth raster, a depth map without one valid pixel, and every default that replaces missing input data
// (no sparse points: heights from the depth maps; no scene heights at all: the config's z range; views without
// images: grey points). Each goes to spdlog's warn level (so into sacfuse.log) as "<file>: <message>", once per
// file and message however often the file is read (tiles re-read windows of the same rasters), and is kept for
// run_report.json's "warnings" and the HTML report.
#include <string>
#include <vector>

namespace sacfuse {

void WarnAboutInput(const std::string& file, const std::string& message);
// Every warning WarnAboutInput gave in this process, "<file>: <message>", in the order given.
std::vector<std::string> InputWarningsGiven();

}  // namespace sacfuse
