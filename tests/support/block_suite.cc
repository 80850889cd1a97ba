#include "tests/support/block_suite.h"

#include <fstream>

namespace sacfuse::testing {

void TinyBlockSuite::SimulateBlock() {
  dir_ = new TempDir();
  std::string out;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " simulate --preset tiny --seed 3 --out " + ShellQuote(Block()), &out), 0)
      << out;
}

void TinyBlockSuite::TearDownTestSuite() {
  delete dir_;
  dir_ = nullptr;
}

double TinyBlockSuite::BlockGsd() { return ReadJsonFile(Block() / "metadata.json").at("gsd_m").get<double>(); }

std::string WithoutLasCreationDate(std::string las_bytes) {
  constexpr size_t kCreationDateOffset = 90;
  if (las_bytes.size() > kCreationDateOffset + 4) las_bytes.replace(kCreationDateOffset, 4, 4, '\0');
  return las_bytes;
}

size_t CountFilesNamedWith(const std::filesystem::path& dir, const std::string& part) {
  size_t n = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    n += e.path().filename().string().find(part) != std::string::npos ? 1 : 0;
  }
  return n;
}

nlohmann::json ReadJsonFile(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

double EvalF1(const std::filesystem::path& eval_json, size_t index) {
  return ReadJsonFile(eval_json).at("scores").at(index).at("f1").get<double>();
}

}  // namespace sacfuse::testing
