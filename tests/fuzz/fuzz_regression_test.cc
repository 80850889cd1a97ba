// Replays every reproducer the fuzzers found (tests/fuzz/regressions/<target>/<file>) through the same target
// bodies: each must now end in success or a sacfuse::Error. A reproducer that crashes, trips a sanitizer or
// throws anything else fails this test (or kills it, which CTest reports as a failure).
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "tests/fuzz/fuzz_readers.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;

fs::path RegressionDir() {
  const char* env = std::getenv("SACFUSE_FUZZ_REGRESSIONS");
  return env != nullptr ? fs::path(env) : fs::path("tests/fuzz/regressions");
}

TEST(FuzzRegressionTest, EveryKeptReproducerEndsInSuccessOrASacfuseError) {
  const fs::path root = RegressionDir();
  ASSERT_TRUE(fs::is_directory(root)) << root;
  int replayed = 0;
  for (const std::string& target : fuzz::TargetNames()) {
    const fs::path dir = root / target;
    if (!fs::is_directory(dir)) continue;
    for (const auto& entry : fs::directory_iterator(dir)) {
      const std::string bytes = testing::ReadFileBytes(entry.path());
      SCOPED_TRACE(entry.path().string());
      EXPECT_NO_THROW(fuzz::RunTarget(target, reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()));
      ++replayed;
    }
  }
  for (const auto& entry : fs::directory_iterator(root)) {
    const std::string name = entry.path().filename().string();
    bool known = false;
    for (const std::string& t : fuzz::TargetNames()) known = known || t == name;
    EXPECT_TRUE(known || !entry.is_directory()) << "regressions/" << name << " is not a fuzz target";
  }
  EXPECT_GT(replayed, 0);
}

}  // namespace
}  // namespace sacfuse
