#pragma once
// Warnings about input files that do not stop a run: a truncated image that still decodes, libtiff's warnings
// about a depth raster, a depth map without one valid pixel. Each goes to spdlog's warn level (so into
// sacfuse.log) as "<file>: <message>", once per file and message however often the file is read (tiles re-read
// windows of the same rasters).
#include <string>

namespace sacfuse {

void WarnAboutInput(const std::string& file, const std::string& message);

}  // namespace sacfuse
