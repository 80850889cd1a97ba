#pragma once
// The independent LAS/LAZ/COPC readers of the npm packages in tests/las_js (installed by tools/install_deps.sh with
// `npm ci --prefix tests/las_js`), for the tests that read our files with them (tests/las_js_reader_test.cc,
// tests/copc_js_reader_test.cc): whether they can run here, and what they and our reader decode.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/las_reader.h"
#include "tests/support/block_suite.h"
#include "tests/support/test_support.h"

namespace sacfuse::testing {

namespace las_js {
namespace fs = std::filesystem;
using nlohmann::json;

// tests/las_js (SACFUSE_LAS_JS overrides it).
inline fs::path LasJsDir() {
  if (const char* dir = std::getenv("SACFUSE_LAS_JS")) return dir;
  return SourceDir() / "tests" / "las_js";
}

// Why the independent reader cannot run here, or nullopt when it can.
inline std::optional<std::string> ReaderUnavailable() {
  std::string out;
  if (RunCommand("node --version", &out) != 0) return "node is not installed (tools/install_deps.sh installs it)";
  if (!fs::exists(LasJsDir() / "node_modules" / "@loaders.gl" / "las" / "package.json")) {
    return (LasJsDir() / "node_modules").string() + " is missing (run `npm ci --prefix tests/las_js`, as "
                                                    "tools/install_deps.sh does)";
  }
  for (const char* package : {"laz-perf", "copc"}) {
    if (!fs::exists(LasJsDir() / "node_modules" / package / "package.json")) {
      return (LasJsDir() / "node_modules" / package).string() + " is missing (run `npm ci --prefix tests/las_js`)";
    }
  }
  return std::nullopt;
}

inline bool UnderCi() {
  const char* ci = std::getenv("CI");
  return ci != nullptr && std::string(ci) == "true";
}

}  // namespace las_js

// Skips the test with a message when node or tests/las_js/node_modules is missing, except under CI (CI=true),
// where that is a failure: CI installs them.
#define REQUIRE_READER()                                                               \
  do {                                                                                 \
    if (const auto why = ::sacfuse::testing::las_js::ReaderUnavailable()) {            \
      if (::sacfuse::testing::las_js::UnderCi()) {                                     \
        FAIL() << "CI=true but the independent LAS reader is not installed: " << *why; \
      }                                                                                \
      GTEST_SKIP() << "independent LAS reader unavailable: " << *why;                  \
    }                                                                                  \
  } while (0)

namespace las_js {

// `sacfuse validate` passes the file.
inline void ExpectValid(const fs::path& las) {
  std::string out;
  EXPECT_EQ(RunCommand(SacfuseBinary() + " validate " + ShellQuote(las), &out), 0) << out;
  EXPECT_NE(out.find(": ok ("), std::string::npos) << out;
}

// Runs tests/las_js/decode_laz.mjs on `laz`; returns its JSON (the records are in <laz>.<decoder>.bin).
inline json DecodeLaz(const fs::path& laz) {
  const fs::path out = fs::path(laz).replace_extension(".decode.json");
  const fs::path err = fs::path(laz).replace_extension(".decode.err");
  const std::string cmd = "cd " + ShellQuote(LasJsDir()) + " && node decode_laz.mjs " + ShellQuote(laz) + " " +
                          ShellQuote(laz) + " > " + ShellQuote(out) + " 2> " + ShellQuote(err);
  std::string ignored;
  EXPECT_EQ(RunCommand(cmd, &ignored), 0) << cmd << "\n" << ReadFileBytes(err);
  std::ifstream in(out);
  return json::parse(in);
}

// The point records of an uncompressed LAS file.
inline std::string LasPointRecords(const fs::path& las) {
  LasHeader h;
  { LasReader reader(las.string()); h = reader.header(); }
  return ReadFileBytes(las).substr(h.offset_to_point_data, h.point_count * h.point_record_length);
}

// The records of `las`, sorted: the same points in any order give the same string.
inline std::string SortedPointRecords(const fs::path& las) {
  LasHeader h;
  { LasReader reader(las.string()); h = reader.header(); }
  const std::string all = LasPointRecords(las);
  std::vector<std::string> records;
  for (size_t at = 0; at < all.size(); at += h.point_record_length) {
    records.push_back(all.substr(at, h.point_record_length));
  }
  std::sort(records.begin(), records.end());
  std::string sorted;
  for (const std::string& r : records) sorted += r;
  return sorted;
}

// The suites that read the files of `sacfuse run` on the tiny block: the block (when the readers can run) and run
// configs with crs EPSG:25832; `output_extra` goes inside `output: {...}`, `extra` after it (whole lines).
class RunSuite : public TinyBlockSuite {
 protected:
  static void SetUpTestSuite() {
    if (!ReaderUnavailable()) SimulateBlock();
  }
  static fs::path WriteConfig(const std::string& name, const std::string& output_extra, const std::string& extra) {
    std::ofstream(Config(name)) << "crs: EPSG:25832\n"
                                << "input: {format: colmap, path: " << Block().string() << "}\n"
                                << "output: {dir: " << Out(name).string() << output_extra << "}\n"
                                << extra;
    return Config(name);
  }
};

}  // namespace las_js
}  // namespace sacfuse::testing
