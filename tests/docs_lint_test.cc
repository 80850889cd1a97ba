// The user documentation (README.md, CHANGELOG.md, docs/**/*.md) speaks to users: no machine-local paths, no words
// for how the project was worked on, no commit hashes as labels of results; its links lead somewhere; every page of
// docs/ is reachable from the README; the README stays short. The rules are in docs/development.md ("Docs that
// cannot rot").
#include <filesystem>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/markdown.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using testing::MarkdownPage;

constexpr size_t kReadmeMaxLines = 200;

class DocsLintTest : public ::testing::Test {
 protected:
  void SetUp() override {
    source_ = testing::SourceDir();
    ASSERT_FALSE(source_.empty()) << "SACFUSE_SOURCE_DIR is not set (run the tests via ctest)";
    for (const fs::path& path : testing::DocPages(source_)) pages_.push_back(testing::ReadMarkdownPage(path));
    ASSERT_FALSE(pages_.empty()) << "no documentation pages under " << source_;
  }

  std::string Where(const MarkdownPage& page, size_t line_index) const {
    return fs::relative(page.path, source_).string() + ":" + std::to_string(line_index + 1);
  }

  fs::path source_;
  std::vector<MarkdownPage> pages_;
};

TEST_F(DocsLintTest, ReadmeIsShort) {
  const MarkdownPage readme = testing::ReadMarkdownPage(source_ / "README.md");
  EXPECT_LE(readme.lines.size(), kReadmeMaxLines) << "README.md has " << readme.lines.size() << " lines";
}

TEST_F(DocsLintTest, NoMachineLocalPaths) {
  static const std::regex local_path(R"((^|[^A-Za-z0-9_.~-])/(work|tmp|root)/)");
  for (const MarkdownPage& page : pages_) {
    for (size_t i = 0; i < page.lines.size(); ++i) {
      EXPECT_FALSE(std::regex_search(page.lines[i], local_path))
          << Where(page, i) << ": a path of one machine: " << page.lines[i];
    }
  }
}

TEST_F(DocsLintTest, NoWordsForHowTheProjectWasWorkedOn) {
  static const std::regex words(R"(\bsessions?\b)", std::regex::icase);
  for (const MarkdownPage& page : pages_) {
    for (size_t i = 0; i < page.lines.size(); ++i) {
      EXPECT_FALSE(std::regex_search(page.lines[i], words)) << Where(page, i) << ": " << page.lines[i];
    }
  }
}

// 7-40 lowercase hex digits with a digit and a letter, standing alone: a commit hash. The fraction or exponent of
// a number (6.3746e-05) does not count.
TEST_F(DocsLintTest, NoCommitHashesAsLabels) {
  static const std::regex token(R"((^|[^0-9A-Za-z_.])([0-9a-f]{7,40})(?![0-9A-Za-z_]))");
  for (const MarkdownPage& page : pages_) {
    for (size_t i = 0; i < page.lines.size(); ++i) {
      const std::string& line = page.lines[i];
      for (std::sregex_iterator it(line.begin(), line.end(), token), end; it != end; ++it) {
        const std::string hex = (*it)[2].str();
        const size_t after = static_cast<size_t>(it->position(2) + it->length(2));
        const bool exponent = hex.back() == 'e' && after < line.size() && (line[after] == '-' || line[after] == '+');
        const bool digit = hex.find_first_of("0123456789") != std::string::npos;
        const bool letter = hex.find_first_of("abcdef") != std::string::npos;
        EXPECT_FALSE(digit && letter && !exponent) << Where(page, i) << ": \"" << hex << "\" reads as a commit hash";
      }
    }
  }
}

// The line without its inline code spans (`...`), where a link is text, not a link.
std::string WithoutCodeSpans(const std::string& line) {
  static const std::regex span("`[^`]*`");
  return std::regex_replace(line, span, "");
}

TEST_F(DocsLintTest, RelativeLinksLeadToFilesAndHeadings) {
  static const std::regex link(R"(\]\(([^)\s]+)\))");
  for (const MarkdownPage& page : pages_) {
    for (size_t i = 0; i < page.lines.size(); ++i) {
      if (page.in_code[i]) continue;
      const std::string text = WithoutCodeSpans(page.lines[i]);
      for (std::sregex_iterator it(text.begin(), text.end(), link), end; it != end; ++it) {
        const std::string target = (*it)[1].str();
        if (target.rfind("http://", 0) == 0 || target.rfind("https://", 0) == 0 || target.rfind("mailto:", 0) == 0) {
          continue;
        }
        const size_t hash = target.find('#');
        const std::string file = target.substr(0, hash);
        const fs::path path = file.empty() ? page.path : page.path.parent_path() / file;
        if (!fs::exists(path)) {
          ADD_FAILURE() << Where(page, i) << ": the link " << target << " leads to no file";
          continue;
        }
        if (hash == std::string::npos || path.extension() != ".md") continue;
        const std::string anchor = target.substr(hash + 1);
        const std::set<std::string> anchors = testing::HeadingAnchors(testing::ReadMarkdownPage(path));
        EXPECT_TRUE(anchors.count(anchor) > 0) << Where(page, i) << ": the link " << target
                                               << " names no heading of " << path.filename().string();
      }
    }
  }
}

TEST_F(DocsLintTest, EveryDocsPageIsLinkedFromTheReadme) {
  const MarkdownPage readme = testing::ReadMarkdownPage(source_ / "README.md");
  std::string text;
  for (size_t i = 0; i < readme.lines.size(); ++i) {
    if (!readme.in_code[i]) text += readme.lines[i] + "\n";
  }
  std::error_code ec;
  for (fs::directory_iterator it(source_ / "docs", ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().extension() != ".md") continue;
    const std::string name = "docs/" + it->path().filename().string();
    EXPECT_TRUE(text.find("](" + name + ")") != std::string::npos || text.find("](" + name + "#") != std::string::npos)
        << name << " is not linked from README.md's documentation table: add a row for it";
  }
}

// Commands in a `sh` block are meant to be copied as they stand: a "$ " prompt belongs in a `console` block.
TEST_F(DocsLintTest, ShellBlocksHoldNoPrompts) {
  for (const MarkdownPage& page : pages_) {
    for (const testing::FencedBlock& block : page.blocks) {
      if (block.language != "sh") continue;
      for (const std::string& line : block.lines) {
        EXPECT_NE(line.rfind("$ ", 0), 0u) << fs::relative(page.path, source_).string() << ":" << block.line
                                           << ": a prompt in a `sh` block; show it as `console`";
      }
    }
  }
}

}  // namespace
}  // namespace sacfuse
