// End-to-end: the command line as scripts and users drive it — the version (CMakeLists.txt's project VERSION,
// printed by --version and written into the outputs), --set and --output-dir (recorded in the effective YAML and in
// the resume hash like a YAML key), the global -v / -q / --log-level, progress redrawn in place only on a terminal,
// and the --json outputs of status, validate and plan with their documented keys.
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/las_reader.h"
#include "tests/support/block_suite.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using testing::ReadFileBytes;
using testing::ReadJsonFile;
using testing::RunCommand;
using testing::SacfuseBinary;
using testing::ShellQuote;

bool Contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// "0.2.0" from CMakeLists.txt's `project(sacfuse VERSION 0.2.0 ...)`.
std::string ProjectVersion() {
  const std::string cmake = ReadFileBytes(testing::SourceDir() / "CMakeLists.txt");
  std::smatch m;
  if (!std::regex_search(cmake, m, std::regex(R"(project\(sacfuse VERSION ([0-9]+\.[0-9]+\.[0-9]+))"))) return "";
  return m[1];
}

// stdout and stderr of a command, apart.
struct Output {
  int code = 0;
  std::string out, err;
};

class CliOptionsTest : public testing::TinyBlockSuite {
 protected:
  // The block, and one tiled run of it (union, no co-registration: fast) into Out("tiled") whose files and console
  // the tests read; every other run names its own --output-dir.
  static void SetUpTestSuite() {
    SimulateBlock();
    std::ofstream(Config("union")) << "input: {path: " << Block().string() << "}\n"
                                   << "output: {dir: " << Out("union").string() << "}\n"
                                   << "fusion: {method: union}\n"
                                   << "coregistration: {enabled: false}\n"
                                   << "tiling: {tile_size_m: 40, halo_m: 5}\n";
    tiled_run_ = new Output(Sacfuse("run " + UnionConfig() + " --output-dir " + ShellQuote(Out("tiled"))));
    ASSERT_EQ(tiled_run_->code, 0) << tiled_run_->out << tiled_run_->err;
  }
  static void TearDownTestSuite() {
    delete tiled_run_;
    tiled_run_ = nullptr;
    TinyBlockSuite::TearDownTestSuite();
  }

  static Output Sacfuse(const std::string& args) {
    const fs::path err_file = Dir() / "stderr.txt";
    Output o;
    o.code = RunCommand("{ " + SacfuseBinary() + " " + args + " 2>" + ShellQuote(err_file) + "; }", &o.out);
    o.err = ReadFileBytes(err_file);
    return o;
  }

  static std::string UnionConfig() { return ShellQuote(Config("union")); }
  static std::string TiledDir() { return " --output-dir " + ShellQuote(Out("tiled")); }

  static inline Output* tiled_run_ = nullptr;
};

TEST_F(CliOptionsTest, VersionIsTheProjectVersionEverywhere) {
  const std::string release = ProjectVersion();
  ASSERT_FALSE(release.empty()) << "no project(sacfuse VERSION x.y.z) in CMakeLists.txt";
  const Output flag = Sacfuse("--version");
  ASSERT_EQ(flag.code, 0) << flag.err;
  // "sacfuse 0.2.0", or "sacfuse 0.2.0 (git <describe>)" when built from a git checkout.
  EXPECT_TRUE(std::regex_match(flag.out, std::regex("sacfuse " + std::regex_replace(release, std::regex("\\."), "\\.") +
                                                    "( \\(git [^)]+\\))?\n")))
      << flag.out;
  EXPECT_EQ(Sacfuse("version").out, flag.out);
  const std::string full = flag.out.substr(0, flag.out.size() - 1);
  EXPECT_EQ(ReadJsonFile(Out("tiled") / "run_report.json").at("version"), full);
  EXPECT_EQ(ReadJsonFile(Out("tiled") / "plan.json").at("version"), full);
  EXPECT_TRUE(Contains(ReadFileBytes(Out("tiled") / "sacfuse.effective.yaml"), "written by " + full + ".\n"));
  EXPECT_TRUE(Contains(ReadFileBytes(Out("tiled") / "report" / "index.html"), full));
  // The LAS header names the release alone (32 bytes; equal for every build of a release).
  EXPECT_EQ(LasReader((Out("tiled") / "fused.laz").string()).header().generating_software, "sacfuse " + release);
}

TEST_F(CliOptionsTest, SetAndOutputDirActLikeYamlKeysAndAreRecorded) {
  const fs::path out = Out("set");
  const Output run = Sacfuse("run " + UnionConfig() + " -q --set tiling.tile_size_m=0 --set output.format=las " +
                             "--set 'evaluation.tau_gsd=[1, 3]' --output-dir " + ShellQuote(out));
  ASSERT_EQ(run.code, 0) << run.out << run.err;
  EXPECT_EQ(run.err, "");  // -q: no info, no progress
  EXPECT_TRUE(Contains(run.out, "fused cloud: " + (out / "fused.las").string())) << run.out;  // results on stdout
  EXPECT_TRUE(fs::exists(out / "fused.las"));  // uncompressed and untiled: both --set applied
  EXPECT_FALSE(fs::exists(out / "tiles"));
  EXPECT_FALSE(fs::exists(Out("union")));  // output.dir of the file is left alone
  const std::string effective = ReadFileBytes(out / "sacfuse.effective.yaml");
  EXPECT_TRUE(Contains(effective, "--set tiling.tile_size_m=0 --set output.format=las --set evaluation.tau_gsd=[1, "
                                  "3] --output-dir " + out.string()))
      << effective;
  EXPECT_TRUE(Contains(effective, "  dir: \"" + out.string() + "\"\n")) << effective;
  EXPECT_TRUE(Contains(effective, "  format: \"las\"\n")) << effective;
  EXPECT_TRUE(Contains(effective, "  tau_gsd: [1.0, 3.0]\n")) << effective;
  // Errors name the option, exit 2, and nothing is written.
  const Output bad = Sacfuse("run " + UnionConfig() + " --set fusion.tua_m=1 --output-dir " + ShellQuote(Out("bad")));
  EXPECT_EQ(bad.code, 2) << bad.out << bad.err;
  EXPECT_TRUE(Contains(bad.err, "--set fusion.tua_m: unknown key; allowed in fusion:")) << bad.err;
  EXPECT_FALSE(fs::exists(Out("bad") / "fused.laz"));
  const Output range = Sacfuse("run " + UnionConfig() + " --threads -2 --output-dir " + ShellQuote(Out("bad")));
  EXPECT_EQ(range.code, 2);
  EXPECT_TRUE(Contains(range.err, "--threads resources.threads = -2: must be >= 0")) << range.err;
  const Output syntax = Sacfuse("plan " + UnionConfig() + " --set fusion.tau_m");
  EXPECT_EQ(syntax.code, 2);
  EXPECT_TRUE(Contains(syntax.err, "--set fusion.tau_m: expected KEY=VALUE")) << syntax.err;
}

// A tiled run resumed with a different --set recomputes every tile (the resume hash takes the --set like a YAML
// key); status (which checks the tiles against the hash as a resumed run does) needs the same --set to see them
// as done.
TEST_F(CliOptionsTest, ResumeHashTakesTheSet) {
  const std::string run = "run " + UnionConfig() + " --output-dir " + ShellQuote(Out("resume"));
  const Output first = Sacfuse(run);
  ASSERT_EQ(first.code, 0) << first.out << first.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(first.out, m, std::regex("tiles: ([0-9]+) computed, 0 done and skipped"))) << first.out;
  const std::string tiles = m[1];
  const Output changed = Sacfuse(run + " --set output.scale_m=0.0025");
  ASSERT_EQ(changed.code, 0) << changed.out << changed.err;
  EXPECT_TRUE(Contains(changed.out, "tiles: " + tiles + " computed, 0 done and skipped")) << changed.out;
  const std::string status = "status " + UnionConfig() + " --output-dir " + ShellQuote(Out("resume")) + " --json";
  const nlohmann::json other = nlohmann::json::parse(Sacfuse(status).out);
  EXPECT_TRUE(other.at("settings_changed").get<bool>());
  EXPECT_EQ(other.at("counts").at("done"), 0);
  const nlohmann::json same = nlohmann::json::parse(Sacfuse(status + " --set output.scale_m=0.0025").out);
  EXPECT_FALSE(same.at("settings_changed").get<bool>());
  EXPECT_EQ(same.at("counts").at("done"), std::stoi(tiles));
}

TEST_F(CliOptionsTest, QuietVerboseAndLogLevelSetTheConsoleOnly) {
  // The suite's run, without options: info lines and progress lines, one each (stderr is not a terminal).
  EXPECT_TRUE(Contains(tiled_run_->err, "] info ")) << tiled_run_->err;
  EXPECT_TRUE(Contains(tiled_run_->err, "\n  tiles ")) << tiled_run_->err;
  EXPECT_TRUE(Contains(tiled_run_->err, " ETA ")) << tiled_run_->err;
  EXPECT_FALSE(Contains(tiled_run_->err, "\r"));
  EXPECT_FALSE(Contains(tiled_run_->err, "] debug "));
  // The log file follows log.level (info), not the console.
  EXPECT_TRUE(Contains(ReadFileBytes(Out("tiled") / "sacfuse.log"), "[info]"));
  // plan logs at info (and at debug that it reuses the shared plan.json).
  const std::string plan = "plan " + UnionConfig() + TiledDir();
  const Output normal = Sacfuse(plan);
  ASSERT_EQ(normal.code, 0) << normal.err;
  EXPECT_TRUE(Contains(normal.err, "] info ")) << normal.err;
  EXPECT_FALSE(Contains(normal.err, "] debug ")) << normal.err;
  for (const std::string& quiet : {"-q " + plan, plan + " --quiet", "--log-level warn " + plan}) {
    const Output q = Sacfuse(quiet);
    ASSERT_EQ(q.code, 0) << quiet << "\n" << q.err;
    EXPECT_EQ(q.err, "") << quiet;
    EXPECT_TRUE(Contains(q.out, "plan: ")) << quiet;  // results still on stdout
  }
  for (const std::string& verbose : {"-v " + plan, plan + " --log-level debug"}) {
    const Output v = Sacfuse(verbose);
    ASSERT_EQ(v.code, 0) << verbose << "\n" << v.err;
    EXPECT_TRUE(Contains(v.err, "] debug ")) << verbose << "\n" << v.err;
  }
  const Output only_errors = Sacfuse("--log-level error " + plan + " --set resources.memory_gb=0");
  EXPECT_EQ(only_errors.code, 2);
  EXPECT_TRUE(Contains(only_errors.err, "] error ")) << only_errors.err;
  const Output both = Sacfuse("-q -v version");
  EXPECT_EQ(both.code, 2);
  EXPECT_TRUE(Contains(both.err, "give one of them")) << both.err;
  EXPECT_EQ(Sacfuse("--log-level loud version").code, 2);
}

// On a terminal (a pseudo-terminal from script(1)) the progress lines are redrawn in place: \r, the line, erase to
// its end (ESC [K); a small simulated block shows several stages.
TEST_F(CliOptionsTest, ProgressRedrawsInPlaceOnATerminal) {
  if (RunCommand("script --version >/dev/null 2>&1") != 0) GTEST_SKIP() << "script(1) (util-linux) not installed";
  const std::string command = SacfuseBinary() + " simulate --preset tiny --area 20 --no-obliques --pixel-scale 0.25 " +
                              "--no-consistency-graphs --out " + ShellQuote(Out("tty"));
  std::string out;
  ASSERT_EQ(RunCommand("script -qefc " + ShellQuote(command) + " /dev/null </dev/null", &out), 0) << out;
  EXPECT_TRUE(Contains(out, "\r  views ")) << out;
  EXPECT_TRUE(Contains(out, "\033[K")) << out;
  EXPECT_TRUE(Contains(out, "simulated block: ")) << out;
}

TEST_F(CliOptionsTest, JsonOutputsParseWithTheDocumentedKeys) {
  const std::string dir = TiledDir();
  const Output status = Sacfuse("status " + UnionConfig() + dir + " --json");
  ASSERT_EQ(status.code, 0) << status.err;
  const nlohmann::json s = nlohmann::json::parse(status.out);
  for (const char* key : {"version", "output_dir", "last_run", "last_run_failed", "tiled", "settings_changed",
                          "counts", "tiles", "fused_cloud", "merged", "exit_code"}) {
    EXPECT_TRUE(s.contains(key)) << key << "\n" << status.out;
  }
  EXPECT_EQ(s.at("last_run").at("state"), "succeeded");
  for (const char* key : {"state", "description", "error", "pid", "host", "started_unix_ns", "ended_unix_ns",
                          "last_success_unix_ns"}) {
    EXPECT_TRUE(s.at("last_run").contains(key)) << key;
  }
  EXPECT_TRUE(s.at("tiled").get<bool>());
  EXPECT_TRUE(s.at("merged").get<bool>());
  const size_t tiles = s.at("tiles").size();
  EXPECT_GT(tiles, 1u);
  EXPECT_EQ(s.at("counts").at("tiles"), tiles);
  EXPECT_EQ(s.at("counts").at("done"), tiles);
  for (const char* key : {"id", "state", "reason", "claimed_by"}) EXPECT_TRUE(s.at("tiles").at(0).contains(key)) << key;

  const Output plan = Sacfuse("plan " + UnionConfig() + dir + " --json");
  ASSERT_EQ(plan.code, 0) << plan.err;
  const nlohmann::json p = nlohmann::json::parse(plan.out);
  EXPECT_EQ(p, ReadJsonFile(Out("tiled") / "plan.json"));
  for (const char* key : {"version", "tile_size_m", "halo_m", "window_margin_px", "z_range_m", "z_source", "area",
                          "grid", "bytes_per_window_pixel", "config_hash", "inputs_hash", "tiles"}) {
    EXPECT_TRUE(p.contains(key)) << key;
  }
  for (const char* key : {"id", "core", "halo", "views", "window_pixels", "memory_bytes"}) {
    EXPECT_TRUE(p.at("tiles").at(0).contains(key)) << key;
  }
  EXPECT_EQ(Sacfuse("plan " + UnionConfig() + dir + " --json --list").code, 2);

  const fs::path bad = Dir() / "bad.las";
  std::ofstream(bad) << "not a LAS file";
  const Output validate = Sacfuse("validate --json " + ShellQuote(Out("tiled") / "fused.laz") + " " + ShellQuote(bad));
  EXPECT_EQ(validate.code, 1);  // bad.las has findings
  const nlohmann::json v = nlohmann::json::parse(validate.out);
  for (const char* key : {"version", "files", "passed", "total"}) EXPECT_TRUE(v.contains(key)) << key;
  EXPECT_EQ(v.at("total"), 2);
  EXPECT_EQ(v.at("passed"), 1);
  const nlohmann::json& good = v.at("files").at(0);
  EXPECT_TRUE(good.at("ok").get<bool>());
  EXPECT_TRUE(good.at("readable").get<bool>());
  EXPECT_EQ(good.at("las_version"), "1.4");
  EXPECT_EQ(good.at("point_format"), 7);
  EXPECT_GT(good.at("point_count").get<uint64_t>(), 1000u);
  EXPECT_TRUE(good.contains("crs"));
  const nlohmann::json& broken = v.at("files").at(1);
  EXPECT_FALSE(broken.at("ok").get<bool>());
  EXPECT_FALSE(broken.at("readable").get<bool>());
  EXPECT_FALSE(broken.at("findings").empty());
  EXPECT_FALSE(broken.at("error").get<std::string>().empty());
}

TEST_F(CliOptionsTest, DevelopmentCommandsAreGroupedApartInHelp) {
  const Output help = Sacfuse("--help");
  ASSERT_EQ(help.code, 0);
  const size_t dev = help.out.find("Development commands");
  ASSERT_NE(dev, std::string::npos) << help.out;
  for (const char* command : {"bench", "colmap-fusion", "gen-docs"}) {
    const size_t at = help.out.find("\n  " + std::string(command) + " ");
    EXPECT_GT(at, dev) << command << " is not under Development commands:\n" << help.out;
  }
  for (const char* command : {"run", "plan", "status", "tile", "merge", "report", "simulate", "eval", "validate", "convert", "version"}) {
    const size_t at = help.out.find("\n  " + std::string(command) + " ");
    EXPECT_LT(at, dev) << command << " is under Development commands:\n" << help.out;
  }
}

}  // namespace
}  // namespace sacfuse
