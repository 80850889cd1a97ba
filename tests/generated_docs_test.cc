// The committed reference pages are what the binary generates: docs/configuration.md from the option table and
// docs/cli.md from every command's --help (`sacfuse gen-docs`); a renamed flag or key, or a new one, fails here
// until the pages are regenerated. Also: the man page covers every command, and CITATION.cff carries the version of
// CMakeLists.txt.
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using testing::ReadFileBytes;
using testing::RunCommand;
using testing::SacfuseBinary;
using testing::SourceDir;

constexpr const char* kRegenerate = "regenerate the pages with tools/gen_docs.sh (or: build/bin/sacfuse gen-docs "
                                    "configuration --out docs/configuration.md; build/bin/sacfuse gen-docs cli --out "
                                    "docs/cli.md) and commit them";

// `sacfuse gen-docs WHAT`, run once per WHAT.
const std::string& Generated(const std::string& what) {
  static std::map<std::string, std::string> pages;
  if (!pages.count(what)) {
    std::string out;
    EXPECT_EQ(RunCommand(SacfuseBinary() + " gen-docs " + what + " 2>/dev/null", &out), 0) << out;
    pages[what] = out;
  }
  return pages[what];
}

// The first line where two texts differ, for the failure message.
std::string FirstDifference(const std::string& committed, const std::string& generated) {
  size_t line = 1, i = 0;
  while (i < committed.size() && i < generated.size() && committed[i] == generated[i]) line += committed[i++] == '\n';
  const auto line_at = [](const std::string& text, size_t pos) {
    const size_t begin = text.rfind('\n', pos == 0 ? 0 : pos - 1);
    const size_t start = begin == std::string::npos ? 0 : begin + 1;
    return text.substr(start, text.find('\n', start) - start);
  };
  return "line " + std::to_string(line) + ":\n  committed: " + line_at(committed, i) +
         "\n  generated: " + line_at(generated, i);
}

void ExpectCommittedPageIsGenerated(const std::string& page, const std::string& what) {
  const fs::path path = SourceDir() / "docs" / page;
  ASSERT_TRUE(fs::exists(path)) << path << " is missing: " << kRegenerate;
  const std::string committed = ReadFileBytes(path);
  const std::string generated = Generated(what);
  EXPECT_TRUE(committed == generated) << "docs/" << page << " differs from `sacfuse gen-docs " << what << "` at "
                                      << FirstDifference(committed, generated) << "\n" << kRegenerate;
}

TEST(GeneratedDocsTest, ConfigurationPageIsTheOptionTable) {
  ExpectCommittedPageIsGenerated("configuration.md", "configuration");
  // Every key of --print-defaults is on the page.
  std::string defaults;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " run --print-defaults", &defaults), 0);
  const std::string page = Generated("configuration");
  std::string section;
  const std::regex key_line(R"(^(\s*)([a-z_]+):(.*)$)");
  size_t keys = 0;
  std::istringstream lines(defaults);
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (line.empty() || line[0] == '#' || !std::regex_match(line, m, key_line)) continue;
    if (m[1].length() == 0 && m[3].length() == 0) {
      section = m[2];
      continue;
    }
    const std::string key = m[1].length() == 0 ? m[2].str() : section + "." + m[2].str();
    EXPECT_NE(page.find("- **`" + key + "`**"), std::string::npos) << key;
    ++keys;
  }
  EXPECT_GT(keys, 80u);
}

TEST(GeneratedDocsTest, CliPageIsEveryCommandsHelp) {
  ExpectCommittedPageIsGenerated("cli.md", "cli");
  // The page holds exactly what --help prints.
  const std::string page = Generated("cli");
  for (const char* command : {"", "run", "status", "bench"}) {
    std::string help;
    ASSERT_EQ(RunCommand(SacfuseBinary() + " " + command + " --help", &help), 0) << command;
    EXPECT_NE(page.find("```text\n" + help + "```\n"), std::string::npos) << "sacfuse " << command << " --help";
  }
}

TEST(GeneratedDocsTest, ManPageCoversEveryCommand) {
  const std::string man = Generated("man");
  EXPECT_EQ(man.rfind(".TH SACFUSE 1 ", 0), 0u) << man.substr(0, 200);
  std::string help;
  ASSERT_EQ(RunCommand(SacfuseBinary() + " --help", &help), 0);
  // Every command line of --help ("  name   description") has its section.
  const std::regex command_line(R"(^  ([a-z][a-z-]*) {2,})");
  size_t commands = 0;
  std::istringstream lines(help.substr(help.find("Commands")));
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (!std::regex_search(line, m, command_line)) continue;
    EXPECT_NE(man.find(".SS \"sacfuse " + std::regex_replace(m[1].str(), std::regex("-"), "\\-") + "\""),
              std::string::npos)
        << m[1];
    ++commands;
  }
  EXPECT_GE(commands, 14u) << help;
}

TEST(GeneratedDocsTest, CitationCarriesTheProjectVersion) {
  std::smatch cmake, cff;
  const std::string cmake_text = ReadFileBytes(SourceDir() / "CMakeLists.txt");
  const std::string cff_text = ReadFileBytes(SourceDir() / "CITATION.cff");
  ASSERT_TRUE(std::regex_search(cmake_text, cmake, std::regex(R"(project\(sacfuse VERSION ([0-9.]+))")));
  ASSERT_TRUE(std::regex_search(cff_text, cff, std::regex(R"(\nversion: ([0-9.]+)\n)")));
  EXPECT_EQ(cff[1], cmake[1]) << "CITATION.cff's version must follow CMakeLists.txt's project VERSION";
}

}  // namespace
}  // namespace sacfuse
