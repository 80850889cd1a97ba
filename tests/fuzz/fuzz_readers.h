#pragma once
// The bodies of sacfuse's fuzz targets: one per reader of user files. Each writes the fuzzer's bytes to the
// file(s) the reader expects in a scratch folder and runs the reader the way a run opens that input. The contract
// under test: a reader either succeeds or throws sacfuse::Error (InputError, ConfigError); anything else (a crash,
// a sanitizer report, another exception, a hang, unbounded memory) is a finding. Shared by the libFuzzer
// executables (tests/fuzz/fuzz_*.cc, SACFUSE_FUZZ=ON) and the regression test of the default suite
// (tests/fuzz/fuzz_regression_test.cc), which replays tests/fuzz/regressions/<target>/*.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace sacfuse::fuzz {

// The target names: colmap_text, colmap_binary, colmap_array, openmvs_dmap, tiff_depth, camera_yaml, camera_csv,
// las, job_config, superpixel_cache.
const std::vector<std::string>& TargetNames();

// Runs target `name` on one input. Returns normally when the reader succeeded or threw sacfuse::Error (printed
// to stderr when SACFUSE_FUZZ_VERBOSE is set); lets any other exception escape (libFuzzer then reports it as a
// crash).
void RunTarget(const std::string& name, const uint8_t* data, size_t size);

// Inputs of the multi-file targets (colmap_text, colmap_binary) hold their files one after another, separated by
// this line; a seed is cameras + kFileSeparator + images + kFileSeparator + points3D.
constexpr const char* kFileSeparator = "\n#--sacfuse-fuzz-next-file--\n";

}  // namespace sacfuse::fuzz
