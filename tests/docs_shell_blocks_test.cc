// Docs that cannot rot: every page of README.md and docs/ whose first line is `<!-- docs-test: run -->` is run as
// one bash script in a fresh temporary folder, with the built sacfuse first on PATH, so a renamed subcommand, flag
// or YAML key fails here instead of for a reader. In such a page a ```sh block is executed, a ```yaml block whose
// first line is `# file: NAME` is written to NAME first, and every other block is shown only (docs/development.md,
// "Docs that cannot rot"). `<!-- docs-test: run, needs: parallel -->` names tools the page needs: without them it
// is skipped, except under CI=true, where tools/install_deps.sh installs them.
// The pages start from the same simulated block: `sacfuse simulate` runs once per set of arguments (without
// --out) in this process and is copied for the pages after (the block is seeded, so the copy is the same block).
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/markdown.h"
#include "tests/support/test_support.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;
using testing::MarkdownPage;

constexpr const char* kMarker = "<!-- docs-test: run";

// The pages that declare themselves runnable, as paths relative to the source folder.
std::vector<std::string> RunnablePages() {
  std::vector<std::string> pages;
  const fs::path source = testing::SourceDir();
  if (source.empty()) return pages;
  for (const fs::path& page : testing::DocPages(source)) {
    std::ifstream in(page);
    std::string first;
    std::getline(in, first);
    if (first.rfind(kMarker, 0) == 0) pages.push_back(fs::relative(page, source).string());
  }
  return pages;
}

// The tools a page's marker names after "needs:".
std::vector<std::string> NeededTools(const std::string& marker_line) {
  std::vector<std::string> tools;
  const size_t at = marker_line.find("needs:");
  if (at == std::string::npos) return tools;
  std::istringstream words(marker_line.substr(at + 6));
  for (std::string word; words >> word;) {
    if (word == "-->") break;
    if (word.back() == ',') word.pop_back();
    tools.push_back(word);
  }
  return tools;
}

bool HaveTool(const std::string& tool) {
  return std::system(("command -v " + testing::ShellQuote(tool) + " >/dev/null 2>&1").c_str()) == 0;
}

// The page as one bash script: before each executed block, its location is written to `where_file`, so that a
// failure names the block.
std::string ScriptOf(const MarkdownPage& page, const std::string& name, const fs::path& where_file) {
  static const std::regex file_line(R"(#\s*file:\s*([A-Za-z0-9_./-]+)\s*)");
  std::ostringstream script;
  script << "set -euo pipefail\n";
  for (const testing::FencedBlock& block : page.blocks) {
    const std::string where = name + ":" + std::to_string(block.line);
    std::smatch m;
    if (block.language == "yaml" && !block.lines.empty() && std::regex_match(block.lines[0], m, file_line)) {
      script << "printf '%s\\n' " << testing::ShellQuote(where) << " > " << testing::ShellQuote(where_file) << "\n"
             << "cat > " << testing::ShellQuote(m[1].str()) << " <<'SACFUSE_DOCS_EOF'\n";
      for (size_t i = 1; i < block.lines.size(); ++i) script << block.lines[i] << "\n";
      script << "SACFUSE_DOCS_EOF\n";
    } else if (block.language == "sh") {
      script << "printf '%s\\n' " << testing::ShellQuote(where) << " > " << testing::ShellQuote(where_file) << "\n";
      for (const std::string& line : block.lines) script << line << "\n";
    }
  }
  return script.str();
}

// A folder with a `sacfuse` that runs the built binary, except that a `simulate` whose arguments (without
// --out) ran before is a copy of that earlier block.
class SimulateOnce {
 public:
  SimulateOnce() {
    const fs::path wrapper = dir_ / "bin" / "sacfuse";
    fs::create_directories(wrapper.parent_path());
    fs::create_directories(dir_ / "blocks");
    std::ofstream(wrapper)
        << "#!/usr/bin/env bash\n"
        << "real=" << testing::ShellQuote(testing::SacfuseBinary()) << "\n"
        << "blocks=" << testing::ShellQuote(dir_ / "blocks") << "\n"
        << "[ \"${1:-}\" = simulate ] || exec \"$real\" \"$@\"\n"
        << "args=(\"$@\"); out=''; key=''\n"
        << "for ((i = 1; i < ${#args[@]}; i++)); do\n"
        << "  if [ \"${args[i]}\" = --out ]; then out=${args[i + 1]:-}; i=$((i + 1)); else key+=\"${args[i]} \"; fi\n"
        << "done\n"
        << "key=$(printf '%s' \"$key\" | md5sum | cut -c1-16)\n"
        << "if [ -n \"$out\" ] && [ ! -e \"$out\" ] && [ -d \"$blocks/$key\" ]; then exec cp -a \"$blocks/$key\" \"$out\"; fi\n"
        << "\"$real\" \"$@\" || exit $?\n"
        << "if [ -n \"$out\" ] && [ ! -e \"$blocks/$key\" ]; then cp -a \"$out\" \"$blocks/$key\"; fi\n";
    fs::permissions(wrapper, fs::perms::owner_all, fs::perm_options::add);
  }
  fs::path BinDir() const { return dir_ / "bin"; }

 private:
  testing::TempDir dir_;
};

class DocsShellBlocksTest : public ::testing::TestWithParam<std::string> {
 protected:
  static void SetUpTestSuite() { simulate_once_ = new SimulateOnce(); }
  static void TearDownTestSuite() {
    delete simulate_once_;
    simulate_once_ = nullptr;
  }
  static inline SimulateOnce* simulate_once_ = nullptr;
};

TEST_P(DocsShellBlocksTest, RunAsWritten) {
  const fs::path source = testing::SourceDir();
  const MarkdownPage page = testing::ReadMarkdownPage(source / GetParam());
  ASSERT_FALSE(page.lines.empty()) << GetParam();
  for (const std::string& tool : NeededTools(page.lines[0])) {
    if (HaveTool(tool)) continue;
    const char* ci = std::getenv("CI");
    if (ci != nullptr && std::string(ci) == "true") FAIL() << GetParam() << " needs " << tool << " (CI=true)";
    GTEST_SKIP() << GetParam() << " needs " << tool << ", which is not installed (tools/install_deps.sh installs it)";
  }

  testing::TempDir work;     // the reader's folder: the page's commands run here
  testing::TempDir scratch;  // the script and the location of the running block
  const fs::path where_file = scratch / "block";
  std::ofstream(scratch / "page.sh") << ScriptOf(page, GetParam(), where_file);

  const fs::path bin_dir = simulate_once_->BinDir();
  const std::string command = "cd " + testing::ShellQuote(work.path()) + " && PATH=" + testing::ShellQuote(bin_dir) +
                              ":\"$PATH\" bash " + testing::ShellQuote(scratch / "page.sh");
  std::string output;
  const int code = testing::RunCommand(command, &output);
  if (code != 0) {
    std::string where = testing::ReadFileBytes(where_file);
    if (!where.empty() && where.back() == '\n') where.pop_back();
    constexpr size_t kTail = 6000;
    FAIL() << "the block at " << (where.empty() ? GetParam() : where) << " failed (exit " << code
           << "); the script's output" << (output.size() > kTail ? " (last part)" : "") << ":\n"
           << (output.size() > kTail ? output.substr(output.size() - kTail) : output);
  }
}

std::string PageTestName(const ::testing::TestParamInfo<std::string>& info) {
  std::string name;
  for (char c : info.param) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Pages, DocsShellBlocksTest, ::testing::ValuesIn(RunnablePages()), PageTestName);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(DocsShellBlocksTest);

// The pages the docs promise to run are found (an empty list would let every page rot unseen).
TEST(DocsShellBlocksPagesTest, TheRunnablePagesAreFound) {
  ASSERT_FALSE(testing::SourceDir().empty()) << "SACFUSE_SOURCE_DIR is not set (run the tests via ctest)";
  const std::vector<std::string> pages = RunnablePages();
  for (const char* page : {"README.md", "docs/tutorial.md"}) {
    EXPECT_NE(std::find(pages.begin(), pages.end(), page), pages.end()) << page << " must be runnable";
  }
}

}  // namespace
}  // namespace sacfuse
