#pragma once
// The Markdown pages of the repository as the docs tests read them (tests/docs_shell_blocks_test.cc,
// tests/docs_lint_test.cc): lines, fenced code blocks, headings and their GitHub anchors. Only ``` fences are
// recognised (indented up to any depth, e.g. inside a list item); the block's lines lose the fence's indentation.
#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace sacfuse::testing {

struct FencedBlock {
  std::string language;  // the first word of the info string ("sh", "yaml", "console", "" when none)
  size_t line = 0;       // 1-based line of the opening fence
  std::vector<std::string> lines;
};

struct MarkdownPage {
  std::filesystem::path path;
  std::vector<std::string> lines;
  std::vector<bool> in_code;  // per line: inside a fenced block, or a fence itself
  std::vector<FencedBlock> blocks;
};

// Reads and splits a page (an unterminated fence runs to the end of the file).
MarkdownPage ReadMarkdownPage(const std::filesystem::path& path);

// The documentation pages under `source_dir`: README.md, CHANGELOG.md and every docs/**/*.md, sorted.
std::vector<std::filesystem::path> DocPages(const std::filesystem::path& source_dir);

// The anchors GitHub gives the headings of a page (`## Tiles and halos` -> "tiles-and-halos"; repeated headings
// get -1, -2, ...).
std::set<std::string> HeadingAnchors(const MarkdownPage& page);

}  // namespace sacfuse::testing
