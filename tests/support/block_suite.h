#pragma once
// Shared pieces of the end-to-end suites that drive the sacfuse binary: one simulated block per suite, config and
// output paths inside it, and small readers of what runs leave behind.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/test_support.h"

namespace sacfuse::testing {

// Base fixture: SetUpTestSuite puts the block of `sacfuse simulate --preset tiny --seed 3` into a temporary folder
// (derived suites that need more call SimulateBlock() first in their own SetUpTestSuite): a copy of the one block
// every suite shares, simulated once per build of the binary (kept beside it in <build>/test-blocks), so each suite
// may change its copy.
class TinyBlockSuite : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { SimulateBlock(); }
  static void TearDownTestSuite();
  // Fails the suite (fatal) when simulate fails; `extra_args` are added to the simulate command line.
  static void SimulateBlock(const std::string& extra_args = "");

  static std::filesystem::path Dir() { return dir_->path(); }
  static std::filesystem::path Block() { return Dir() / "block"; }
  static std::filesystem::path Config(const std::string& name) { return Dir() / (name + ".yaml"); }
  static std::filesystem::path Out(const std::string& name) { return Dir() / name; }
  static double BlockGsd();  // from the block's metadata.json

 private:
  static inline TempDir* dir_ = nullptr;
};

// LAS bytes with the header's creation day and year (offset 90, 2 x u16) blanked: two runs of one job agree on
// everything else.
std::string WithoutLasCreationDate(std::string las_bytes);
// Files below `dir` (recursive) whose name contains `part`.
size_t CountFilesNamedWith(const std::filesystem::path& dir, const std::string& part);
nlohmann::json ReadJsonFile(const std::filesystem::path& path);
// Primary F1 at threshold `index` of an eval.json.
double EvalF1(const std::filesystem::path& eval_json, size_t index);

}  // namespace sacfuse::testing
