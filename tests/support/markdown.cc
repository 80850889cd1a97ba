#include "tests/support/markdown.h"

#include <algorithm>
#include <fstream>
#include <map>

namespace sacfuse::testing {
namespace {

namespace fs = std::filesystem;

size_t IndentOf(const std::string& line) {
  const size_t first = line.find_first_not_of(' ');
  return first == std::string::npos ? line.size() : first;
}

bool IsFence(const std::string& line, size_t* indent) {
  *indent = IndentOf(line);
  return line.compare(*indent, 3, "```") == 0;
}

// The next UTF-8 code point of `s` at `*i` (advancing `*i`); malformed bytes are returned one by one.
uint32_t NextCodePoint(const std::string& s, size_t* i) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char b = byte(*i);
  int extra = b >= 0xF0 ? 3 : b >= 0xE0 ? 2 : b >= 0xC0 ? 1 : 0;
  if (*i + extra >= s.size()) extra = 0;  // a sequence cut short: its first byte alone
  uint32_t cp = extra == 0 ? b : b & (0x3F >> extra);
  for (int k = 1; k <= extra; ++k) cp = (cp << 6) | (byte(*i + k) & 0x3F);
  *i += 1 + extra;
  return cp;
}

void AppendUtf8(uint32_t cp, std::string* out) {
  if (cp < 0x80) {
    *out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    *out += static_cast<char>(0xC0 | (cp >> 6));
    *out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    *out += static_cast<char>(0xE0 | (cp >> 12));
    *out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    *out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    *out += static_cast<char>(0xF0 | (cp >> 18));
    *out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    *out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    *out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

// GitHub's heading anchor: lower case; letters, digits, '-' and '_' kept; spaces become '-'; everything else
// (punctuation, symbols such as × or ≤, backticks) dropped. Letters outside ASCII are recognised for the Latin and
// Greek blocks, which is what these pages use.
std::string Slug(const std::string& heading) {
  std::string out;
  for (size_t i = 0; i < heading.size();) {
    uint32_t cp = NextCodePoint(heading, &i);
    if (cp < 0x80) {
      const char c = static_cast<char>(cp);
      if (c >= 'A' && c <= 'Z') out += static_cast<char>(c - 'A' + 'a');
      else if ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_') out += c;
      else if (c == ' ') out += '-';
      continue;
    }
    const bool latin = cp >= 0xC0 && cp <= 0x24F && cp != 0xD7 && cp != 0xF7;
    const bool greek = cp >= 0x391 && cp <= 0x3C9;
    if (!latin && !greek) continue;
    if ((cp >= 0xC0 && cp <= 0xDE) || (cp >= 0x391 && cp <= 0x3A9)) cp += 0x20;
    AppendUtf8(cp, &out);
  }
  return out;
}

}  // namespace

MarkdownPage ReadMarkdownPage(const fs::path& path) {
  MarkdownPage page;
  page.path = path;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) page.lines.push_back(line);
  page.in_code.assign(page.lines.size(), false);
  FencedBlock* open = nullptr;
  size_t open_indent = 0;
  for (size_t i = 0; i < page.lines.size(); ++i) {
    const std::string& line = page.lines[i];
    size_t indent = 0;
    const bool fence = IsFence(line, &indent);
    if (open == nullptr) {
      if (!fence) continue;
      page.in_code[i] = true;
      std::string info = line.substr(indent + 3);
      info = info.substr(0, info.find_first_of(" \t{"));
      page.blocks.push_back(FencedBlock{info, i + 1, {}});
      open = &page.blocks.back();
      open_indent = indent;
      continue;
    }
    page.in_code[i] = true;
    if (fence && line.find_first_not_of('`', indent) == std::string::npos) {
      open = nullptr;
      continue;
    }
    open->lines.push_back(line.substr(std::min(open_indent, IndentOf(line))));
  }
  return page;
}

std::vector<fs::path> DocPages(const fs::path& source_dir) {
  std::vector<fs::path> pages;
  for (const char* top : {"README.md", "CHANGELOG.md"}) {
    if (fs::is_regular_file(source_dir / top)) pages.push_back(source_dir / top);
  }
  std::error_code ec;
  for (fs::recursive_directory_iterator it(source_dir / "docs", ec), end; !ec && it != end; it.increment(ec)) {
    if (it->is_regular_file() && it->path().extension() == ".md") pages.push_back(it->path());
  }
  std::sort(pages.begin(), pages.end());
  return pages;
}

std::set<std::string> HeadingAnchors(const MarkdownPage& page) {
  std::set<std::string> anchors;
  std::map<std::string, int> seen;
  for (size_t i = 0; i < page.lines.size(); ++i) {
    const std::string& line = page.lines[i];
    if (page.in_code[i]) continue;
    const size_t hashes = line.find_first_not_of('#');
    if (hashes == 0 || hashes > 6 || hashes == std::string::npos || line[hashes] != ' ') continue;
    std::string text = line.substr(hashes + 1);
    while (!text.empty() && (text.back() == '#' || text.back() == ' ')) text.pop_back();
    const std::string slug = Slug(text);
    const int n = seen[slug]++;
    anchors.insert(n == 0 ? slug : slug + "-" + std::to_string(n));
  }
  return anchors;
}

}  // namespace sacfuse::testing
