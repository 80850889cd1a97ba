#pragma once
// JSON text of the files sacfuse writes (run_report.json, run_state.json, markers, plans, eval.json...). Paths and
// view names are bytes: a path may hold bytes that are not UTF-8 (any byte but '/' and NUL is allowed), which JSON
// cannot carry. nlohmann-json throws at dump on them, after the work is done; here they are replaced by U+FFFD
// instead, so every JSON file is written and valid (the log carries the bytes as they are).
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace sacfuse {

// j.dump(indent) with invalid UTF-8 in strings replaced by U+FFFD; never throws for string contents.
std::string JsonText(const nlohmann::json& j, int indent = -1);
// `text` as a JSON string written by JsonText reads back: each invalid UTF-8 sequence replaced by U+FFFD (valid
// UTF-8 is unchanged). For comparing a live value with one read back from a file.
std::string ValidUtf8(const std::string& text);

}  // namespace sacfuse
