#include "tests/support/block_suite.h"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include <unistd.h>

namespace sacfuse::testing {

namespace {

namespace fs = std::filesystem;

// The block of `sacfuse simulate --preset tiny --seed 3` made by this build's binary, simulated once for every
// suite: <build>/test-blocks/tiny-seed3-<binary size>-<binary mtime>. The first suite to need it simulates it
// into a folder of its own and renames that into place (a suite that loses the race drops its copy); blocks of
// older binaries are removed then. Empty path when it cannot be made (the suite then simulates its own).
fs::path CachedTinyBlock(std::string* log) {
  std::error_code ec;
  const fs::path binary = fs::canonical(SacfuseBinary(), ec);
  if (ec) return {};
  const auto size = fs::file_size(binary, ec);
  const auto mtime = fs::last_write_time(binary, ec).time_since_epoch().count();
  if (ec) return {};
  char stamp[40];
  std::snprintf(stamp, sizeof(stamp), "%ju-%016llx", static_cast<uintmax_t>(size),
                static_cast<unsigned long long>(mtime));
  const fs::path cache_dir = binary.parent_path().parent_path() / "test-blocks";
  const std::string name = std::string("tiny-seed3-") + stamp;
  const fs::path block = cache_dir / name;
  if (fs::exists(block / "sacfuse.yaml", ec)) return block;
  fs::create_directories(cache_dir, ec);
  const fs::path making = cache_dir / (name + ".making." + std::to_string(::getpid()));
  fs::remove_all(making, ec);
  if (RunCommand(SacfuseBinary() + " simulate --preset tiny --seed 3 --out " + ShellQuote(making), log) != 0) {
    fs::remove_all(making, ec);
    return {};
  }
  fs::rename(making, block, ec);
  if (ec) fs::remove_all(making, ec);  // another suite made it first
  for (const auto& e : fs::directory_iterator(cache_dir, ec)) {
    const std::string other = e.path().filename().string();
    if (other.rfind("tiny-seed3-", 0) == 0 && other.find(".making.") == std::string::npos && other != name) {
      fs::remove_all(e.path(), ec);
    }
  }
  return fs::exists(block / "sacfuse.yaml", ec) ? block : fs::path();
}

}  // namespace

void TinyBlockSuite::SimulateBlock(const std::string& extra_args) {
  dir_ = new TempDir();
  std::string out;
  // Only the plain block is shared; a suite that asks for more (`extra_args`) simulates its own.
  const fs::path cached = extra_args.empty() ? CachedTinyBlock(&out) : fs::path();
  std::error_code ec;
  if (!cached.empty()) fs::copy(cached, Block(), fs::copy_options::recursive, ec);
  if (cached.empty() || ec) {
    fs::remove_all(Block(), ec);
    ASSERT_EQ(RunCommand(SacfuseBinary() + " simulate --preset tiny --seed 3 --out " + ShellQuote(Block()) +
                             (extra_args.empty() ? "" : " " + extra_args),
                         &out),
              0)
        << out;
  }
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
