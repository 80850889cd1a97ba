#pragma once
// EvalReport as JSON (for `sacfuse eval --json` and scripts comparing runs). Fractions are in [0, 1], lengths
// in metres; the alignment is a row-major 4 x 4 array of rows; histogram keys are the source IDs as strings;
// `version` names the sacfuse that wrote it (config/version.h).
#include <string>

#include "eval/eval.h"

namespace sacfuse {

std::string EvalReportToJson(const EvalReport& report, int indent = 2);
// Writes EvalReportToJson atomically (temporary file, fsync, rename); throws Error on I/O failure.
void WriteEvalReportJson(const EvalReport& report, const std::string& path);

}  // namespace sacfuse
