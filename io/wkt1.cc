#include "io/wkt1.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/error.h"

namespace sacfuse {
namespace {

constexpr int kMaxDepth = 64;

class Parser {
 public:
  explicit Parser(const std::string& text) : s_(text) {}

  WktNode Document() {
    WktNode node = Node(0);
    SkipBlanks();
    if (pos_ != s_.size()) Fail("unexpected text after the closing bracket");
    return node;
  }

 private:
  [[noreturn]] void Fail(const std::string& what) const {
    throw Error("WKT: " + what + " at character " + std::to_string(pos_));
  }
  void SkipBlanks() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  std::string Word() {
    const size_t start = pos_;
    while (pos_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '_')) ++pos_;
    return s_.substr(start, pos_ - start);
  }
  std::string Quoted() {
    std::string out;
    ++pos_;  // opening quote
    while (true) {
      if (pos_ >= s_.size()) Fail("unterminated quoted string");
      const char c = s_[pos_++];
      if (c != '"') {
        out += c;
      } else if (pos_ < s_.size() && s_[pos_] == '"') {
        out += '"';
        ++pos_;
      } else {
        return out;
      }
    }
  }
  WktNode Node(int depth) {
    if (depth > kMaxDepth) Fail("nested too deeply");
    SkipBlanks();
    WktNode node;
    node.keyword = Word();
    if (node.keyword.empty()) Fail("expected a keyword");
    SkipBlanks();
    if (pos_ >= s_.size() || (s_[pos_] != '[' && s_[pos_] != '(')) Fail("expected [ after " + node.keyword);
    const char close = s_[pos_] == '[' ? ']' : ')';
    ++pos_;
    while (true) {
      SkipBlanks();
      if (pos_ >= s_.size()) Fail("missing " + std::string(1, close) + " of " + node.keyword);
      if (s_[pos_] == '"') {
        node.values.push_back(Quoted());
      } else {
        const size_t start = pos_;
        std::string word = Word();
        SkipBlanks();
        if (!word.empty() && pos_ < s_.size() && (s_[pos_] == '[' || s_[pos_] == '(')) {
          pos_ = start;
          node.children.push_back(Node(depth + 1));
        } else {
          pos_ = start;
          while (pos_ < s_.size() && s_[pos_] != ',' && s_[pos_] != close && s_[pos_] != '[' && s_[pos_] != ']' &&
                 s_[pos_] != '(' && s_[pos_] != ')') {
            ++pos_;
          }
          std::string token = s_.substr(start, pos_ - start);
          while (!token.empty() && std::isspace(static_cast<unsigned char>(token.back()))) token.pop_back();
          if (token.empty()) Fail("empty value in " + node.keyword);
          node.values.push_back(token);
        }
      }
      SkipBlanks();
      if (pos_ < s_.size() && s_[pos_] == ',') {
        ++pos_;
        continue;
      }
      if (pos_ < s_.size() && s_[pos_] == close) {
        ++pos_;
        return node;
      }
      Fail("expected , or " + std::string(1, close) + " in " + node.keyword);
    }
  }

  const std::string& s_;
  size_t pos_ = 0;
};

}  // namespace

const WktNode* WktNode::Child(const std::string& name) const {
  for (const WktNode& c : children) {
    if (c.keyword == name) return &c;
  }
  return nullptr;
}

int WktNode::EpsgAuthority() const {
  const WktNode* a = Child("AUTHORITY");
  if (a == nullptr || a->values.size() < 2 || a->values[0] != "EPSG") return 0;
  char* end = nullptr;
  const long code = std::strtol(a->values[1].c_str(), &end, 10);
  return (end != a->values[1].c_str() && *end == '\0' && code > 0 && code < 1000000) ? static_cast<int>(code) : 0;
}

WktNode ParseWkt1(const std::string& text) { return Parser(text).Document(); }

int WktHorizontalEpsg(const WktNode& root) {
  const WktNode* node = &root;
  if (node->keyword == "COMPD_CS") {
    const WktNode* h = node->Child("PROJCS");
    if (h == nullptr) h = node->Child("GEOGCS");
    if (h == nullptr) return 0;
    node = h;
  }
  if (node->keyword == "PROJCS" || node->keyword == "GEOGCS") return node->EpsgAuthority();
  return 0;
}

}  // namespace sacfuse
