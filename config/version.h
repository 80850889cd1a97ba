#pragma once
// The version of sacfuse: the release (CMakeLists.txt's project VERSION) and, when built from a git checkout, `git
// describe --tags --always --dirty` of the build (cmake/BuildVersion.cmake, refreshed at every build).
#include <string>

namespace sacfuse {

// "0.2.0".
std::string ReleaseVersion();
// "v0.2.0-3-gabcdef0", "c5e7806-dirty"; "" when not built from a git checkout (a source tarball).
std::string GitDescription();
// "sacfuse 0.2.0": the LAS header's generating software (32 bytes at most). The release alone, so every build of
// a release writes byte-identical LAS files (tools/bench/output_identity.sh compares them across commits).
std::string VersionString();
// "sacfuse 0.2.0 (git c5e7806-dirty)", or VersionString() without git: `sacfuse --version` and the metadata of
// every output (run_report.json, eval.json, plan.json, sacfuse.effective.yaml, the HTML report, the log).
std::string FullVersionString();

}  // namespace sacfuse
