// End-to-end: the HTML run report as `sacfuse run` and `sacfuse report` write it for a simulated tiny block,
// untiled and tiled: a self-contained page (only relative links to files that exist beside it, pictures that
// decode), the same page and pictures on one thread as on every core, the right "before" counts per view, scores
// once scored, corrupt inputs and an unwritable report folder that do not fail anything, and a headless-Chromium
// screenshot that shows the map (skipped without chromium).
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "config/job_config.h"
#include "report/report_colours.h"
#include "report/report_data.h"
#include "report/report_html.h"
#include "tests/support/block_suite.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using testing::ReadFileBytes;
using testing::ReadJsonFile;
using testing::RunCommand;
using testing::SacfuseBinary;
using testing::ShellQuote;

class ReportEndToEndTest : public testing::TinyBlockSuite {
 protected:
  static void SetUpTestSuite() {
    SimulateBlock();
    std::string out;
    ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(WriteConfig("untiled")), &out), 0) << out;
    ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(WriteConfig("tiled", "tiling: {tile_size_m: 20}\n")),
                         &out),
              0)
        << out;
  }
  // A SAC config with scoring, output in Out(name).
  static fs::path WriteConfig(const std::string& name, const std::string& extra = "", bool score = true) {
    const fs::path path = Config(name);
    std::ofstream(path) << "input: {path: " << Block().string() << "}\n"
                        << "output: {dir: " << Out(name).string() << "}\n"
                        << extra
                        << (score ? "evaluation: {reference: " + (Block() / "reference.las").string() +
                                        ", mask: " + (Block() / "eval_mask.png").string() +
                                        ", gsd_m: " + std::to_string(BlockGsd()) + "}\n"
                                  : "");
    return path;
  }
  static std::string Page(const fs::path& report_dir) { return ReadFileBytes(report_dir / "index.html"); }
};

// Every src= / href= of the page.
std::vector<std::string> References(const std::string& html) {
  std::vector<std::string> refs;
  const std::regex re("(?:src|href)\\s*=\\s*['\"]([^'\"]*)['\"]");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), re); it != std::sregex_iterator(); ++it) {
    refs.push_back((*it)[1].str());
  }
  return refs;
}

void ExpectSelfContained(const fs::path& report_dir) {
  const std::string html = ReadFileBytes(report_dir / "index.html");
  ASSERT_FALSE(html.empty()) << report_dir;
  EXPECT_EQ(html.find("http:"), std::string::npos);
  EXPECT_EQ(html.find("https:"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  const std::vector<std::string> refs = References(html);
  EXPECT_GE(refs.size(), 3u) << "map and two cross-section panels";
  for (const std::string& ref : refs) {
    EXPECT_FALSE(fs::path(ref).is_absolute()) << ref;
    EXPECT_EQ(ref.find(".."), std::string::npos) << ref;
    EXPECT_EQ(ref.find(':'), std::string::npos) << ref;
    EXPECT_TRUE(fs::is_regular_file(report_dir / ref)) << ref;
  }
  size_t pngs = 0;
  for (const auto& e : fs::directory_iterator(report_dir)) {
    if (e.path().extension() != ".png") continue;
    ++pngs;
    const cv::Mat img = cv::imread(e.path().string(), cv::IMREAD_COLOR);
    EXPECT_FALSE(img.empty()) << e.path();
    EXPECT_GT(img.cols, 100) << e.path();
  }
  EXPECT_EQ(pngs, 3u);
}

TEST_F(ReportEndToEndTest, UntiledRunWritesASelfContainedReportWithScores) {
  const fs::path report = Out("untiled") / "report";
  ExpectSelfContained(report);
  const std::string html = Page(report);
  // The scores of eval.json are on the page (the run scores before it writes the report).
  const nlohmann::json eval = ReadJsonFile(Out("untiled") / "eval.json");
  char f1[32];
  std::snprintf(f1, sizeof(f1), "%.1f %%", 100.0 * eval.at("scores").at(0).at("f1").get<double>());
  EXPECT_NE(html.find(std::string(f1) + "</div><div class='k'>F1"), std::string::npos) << f1;
  EXPECT_EQ(html.find("Not scored yet"), std::string::npos);
  for (const char* part : {"1. Source views", "2. Points per view", "3. Cross-section", "4. Tiles", "Untiled run",
                           "5. Numbers", "6. Configuration used", "redundancy removed", "nadir/", "oblique_"}) {
    EXPECT_NE(html.find(part), std::string::npos) << part;
  }
  const nlohmann::json figures = ReadJsonFile(report / "figures.json");
  EXPECT_TRUE(figures.at("profile").at("present").get<bool>());
  EXPECT_GT(figures.at("profile").at("before_in_strip").get<uint64_t>(),
            figures.at("profile").at("after_in_strip").get<uint64_t>()) << "fusion removes redundant points";
  EXPECT_GT(figures.at("profile").at("reference_in_strip").get<uint64_t>(), 0u);
  EXPECT_GT(figures.at("profile").at("strip").at("relief_m").get<double>(), 5.0) << "through a building";
}

TEST_F(ReportEndToEndTest, BeforeCountsAreTheValidDepthPixelsPerViewUntiledAndTiled) {
  const nlohmann::json untiled = ReadJsonFile(Out("untiled") / "run_report.json");
  const nlohmann::json tiled = ReadJsonFile(Out("tiled") / "run_report.json");
  ASSERT_EQ(untiled.at("views").size(), tiled.at("views").size());
  uint64_t sum = 0;
  for (size_t i = 0; i < untiled.at("views").size(); ++i) {
    const uint64_t n = untiled.at("views")[i].at("input_pixels").get<uint64_t>();
    EXPECT_GT(n, 0u) << "view " << i;
    EXPECT_EQ(tiled.at("views")[i].at("input_pixels").get<uint64_t>(), n) << "view " << i;
    sum += n;
  }
  EXPECT_EQ(untiled.at("input_points").get<uint64_t>(), sum);
  EXPECT_EQ(tiled.at("input_points").get<uint64_t>(), sum);
  // Untiled SAC reads each valid pixel exactly once: the same total as its own count.
  EXPECT_EQ(untiled.at("sac").at("pixels_in").get<uint64_t>(), sum);
}

TEST_F(ReportEndToEndTest, TiledRunShowsItsTilesAndReadsOnlyTheStripsTiles) {
  const fs::path report = Out("tiled") / "report";
  ExpectSelfContained(report);
  const std::string html = Page(report);
  const nlohmann::json manifest = ReadJsonFile(Out("tiled") / "tiles" / "manifest.json");
  const size_t tiles = manifest.at("tiles").size();
  ASSERT_GT(tiles, 4u);
  EXPECT_NE(html.find("done (" + std::to_string(tiles) + ")"), std::string::npos);
  EXPECT_NE(html.find("Wall time per tile"), std::string::npos);
  for (const auto& id : manifest.at("tiles")) {
    EXPECT_NE(html.find("<title>tile " + id.get<std::string>() + ": done"), std::string::npos) << id;
  }
  const std::string source = ReadJsonFile(report / "figures.json").at("profile").at("after_source");
  EXPECT_NE(source.find("tile files"), std::string::npos) << source;
  EXPECT_LT(std::stoul(source), tiles) << source;
}

TEST_F(ReportEndToEndTest, ReportCommandWritesElsewhereAndLeavesTheRunAlone) {
  const fs::path run_page = Out("untiled") / "report" / "index.html";
  const auto before = fs::last_write_time(run_page);
  const fs::path elsewhere = Dir() / "elsewhere";
  std::string out;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " report " + ShellQuote(Config("untiled")) + " --out " +
                           ShellQuote(elsewhere),
                       &out),
            0)
      << out;
  EXPECT_NE(out.find("report: " + (elsewhere / "index.html").string()), std::string::npos) << out;
  ExpectSelfContained(elsewhere);
  EXPECT_EQ(fs::last_write_time(run_page), before);
  // The same page but for the time it was written.
  const auto strip_time = [](std::string html) {
    return std::regex_replace(html, std::regex("report written [0-9: -]+|pictures took [0-9.]+ s \\(process peak RSS [0-9]+"), "");
  };
  EXPECT_EQ(strip_time(Page(elsewhere)), strip_time(Page(Out("untiled") / "report")));
  // On one thread (the run used every core): the same page and the same pictures, byte for byte.
  const fs::path one_thread = Dir() / "one_thread";
  ASSERT_EQ(RunCommand(SacfuseBinary() + " report " + ShellQuote(Config("untiled")) +
                           " --set resources.threads=1 --out " + ShellQuote(one_thread),
                       &out),
            0)
      << out;
  EXPECT_EQ(strip_time(Page(one_thread)), strip_time(Page(Out("untiled") / "report")));
  for (const char* png : {"map.png", "profile_after.png", "profile_before.png"}) {
    EXPECT_TRUE(ReadFileBytes(one_thread / png) == ReadFileBytes(Out("untiled") / "report" / png)) << png;
  }
}

TEST_F(ReportEndToEndTest, CorruptRunFilesGiveAPageWithWarnings) {
  const fs::path dir = Out("corrupt");
  const fs::path config = WriteConfig("corrupt", "fusion: {method: union}\n", /*score=*/false);
  std::string out;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(config), &out), 0) << out;
  ExpectSelfContained(dir / "report");
  std::ofstream(dir / "run_report.json") << "{\"views\": [";      // truncated
  fs::resize_file(dir / "fused.laz", 200);                           // header only, cut short
  ASSERT_EQ(RunCommand(SacfuseBinary() + " report " + ShellQuote(config), &out), 0) << out;
  const std::string html = Page(dir / "report");
  EXPECT_NE(html.find("run_report.json unreadable"), std::string::npos);
  EXPECT_NE(html.find("fused.laz unreadable"), std::string::npos);
  EXPECT_NE(html.find("No map"), std::string::npos);
  // No output folder at all: exit 1 naming it.
  std::ofstream(Config("nowhere")) << "input: {path: " << Block().string() << "}\noutput: {dir: "
                                   << (Dir() / "never_ran").string() << "}\n";
  EXPECT_EQ(RunCommand(SacfuseBinary() + " report " + ShellQuote(Config("nowhere")), &out), 1);
  EXPECT_NE(out.find("never_ran"), std::string::npos) << out;
}

TEST_F(ReportEndToEndTest, UnreadableDepthMapsCostOnlyTheBeforePanel) {
  const fs::path block = Dir() / "block_copy";
  fs::copy(Block(), block, fs::copy_options::recursive);
  const fs::path config = Config("depth_gone");
  std::ofstream(config) << "input: {path: " << block.string() << "}\noutput: {dir: " << Out("depth_gone").string()
                        << "}\nfusion: {method: union}\n";
  std::string out;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " run " + ShellQuote(config), &out), 0) << out;
  size_t truncated = 0;
  for (const auto& e : fs::recursive_directory_iterator(block / "stereo" / "depth_maps")) {
    if (e.is_regular_file()) {
      fs::resize_file(e.path(), 20);
      ++truncated;
    }
  }
  ASSERT_GT(truncated, 0u);
  ASSERT_EQ(RunCommand(SacfuseBinary() + " report " + ShellQuote(config), &out), 0) << out;
  const std::string html = Page(Out("depth_gone") / "report");
  EXPECT_NE(html.find("no &#39;before&#39; cross-section"), std::string::npos);
  EXPECT_NE(html.find("After: fused.laz"), std::string::npos);  // the other panel and the map are there
  EXPECT_EQ(html.find("profile_before.png"), std::string::npos);
  EXPECT_NE(html.find("map.png"), std::string::npos);
}

TEST_F(ReportEndToEndTest, AReportThatCannotBeWrittenDoesNotFailTheRun) {
  const fs::path dir = Out("blocked");
  fs::create_directories(dir);
  std::ofstream(dir / "report") << "a file where the report folder should go";
  std::string out;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " run " +
                           ShellQuote(WriteConfig("blocked", "fusion: {method: union}\n", /*score=*/false)),
                       &out),
            0)
      << out;
  EXPECT_TRUE(fs::exists(dir / "fused.laz"));
  EXPECT_NE(out.find("the HTML report was not written"), std::string::npos) << out;
}

// Screenshot with headless Chromium: the page renders, is not blank, and its map shows the views' colours.
TEST_F(ReportEndToEndTest, ChromiumScreenshotShowsTheMapInViewColours) {
  if (RunCommand("command -v chromium") != 0) {
    GTEST_SKIP() << "chromium not installed (apt-get install chromium); skipping the screenshot test";
  }
  const fs::path shot = Dir() / "report_shot.png";
  const fs::path page = fs::absolute(Out("untiled") / "report" / "index.html");
  std::string out;
  ASSERT_EQ(RunCommand("timeout 120 chromium --headless --no-sandbox --disable-gpu --hide-scrollbars "
                       "--screenshot=" + ShellQuote(shot) + " --window-size=1280,1200 " +
                           ShellQuote("file://" + page.string()),
                       &out),
            0)
      << out;
  const cv::Mat img = cv::imread(shot.string(), cv::IMREAD_COLOR);  // BGR
  ASSERT_FALSE(img.empty()) << out;
  EXPECT_EQ(img.cols, 1280);
  std::set<uint32_t> distinct;
  for (int r = 0; r < img.rows; r += 2) {
    for (int c = 0; c < img.cols; c += 2) {
      const cv::Vec3b p = img.at<cv::Vec3b>(r, c);
      distinct.insert(p[0] | p[1] << 8 | p[2] << 16);
    }
  }
  EXPECT_GT(distinct.size(), 2000u) << "a blank or nearly blank page";
  // Map pixels: close to some view's colour (flat roofs and ground are not shaded; the browser resamples). The
  // first 1200 px of the page hold the header and the map; the legend's swatches are too small to pass 200 px.
  JobConfig config;
  config.output.dir = Out("untiled").string();
  const std::vector<Rgb> colours = ReportViewColours(GatherReportData(config));
  ASSERT_EQ(colours.size(), 20u);
  std::vector<size_t> hits(colours.size(), 0);
  for (int r = 0; r < img.rows; ++r) {
    for (int c = 0; c < img.cols; ++c) {
      const cv::Vec3b p = img.at<cv::Vec3b>(r, c);
      for (size_t v = 0; v < colours.size(); ++v) {
        if (std::abs(p[2] - colours[v][0]) <= 6 && std::abs(p[1] - colours[v][1]) <= 6 &&
            std::abs(p[0] - colours[v][2]) <= 6) {
          ++hits[v];
          break;
        }
      }
    }
  }
  size_t views_seen = 0, total = 0;
  for (const size_t h : hits) {
    views_seen += h > 200 ? 1 : 0;
    total += h;
  }
  EXPECT_GE(views_seen, 10u) << "views whose colour covers > 200 screenshot pixels";
  EXPECT_GT(total, 40000u);
}

}  // namespace
}  // namespace sacfuse
