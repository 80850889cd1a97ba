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

std::string Num(double v) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.15g", v);
  return text;
}

const char* kMetre = "UNIT[\"metre\",1,AUTHORITY[\"EPSG\",\"9001\"]]";

std::string GeogCs(const std::string& datum) {
  if (datum == "ETRS89") {
    return "GEOGCS[\"ETRS89\",DATUM[\"European_Terrestrial_Reference_System_1989\",SPHEROID[\"GRS 1980\",6378137,"
           "298.257222101,AUTHORITY[\"EPSG\",\"7019\"]],AUTHORITY[\"EPSG\",\"6258\"]],PRIMEM[\"Greenwich\",0,"
           "AUTHORITY[\"EPSG\",\"8901\"]],UNIT[\"degree\",0.0174532925199433,AUTHORITY[\"EPSG\",\"9122\"]],"
           "AUTHORITY[\"EPSG\",\"4258\"]]";
  }
  return "GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\",6378137,298.257223563,AUTHORITY[\"EPSG\",\"7030\"]],"
         "AUTHORITY[\"EPSG\",\"6326\"]],PRIMEM[\"Greenwich\",0,AUTHORITY[\"EPSG\",\"8901\"]],UNIT[\"degree\","
         "0.0174532925199433,AUTHORITY[\"EPSG\",\"9122\"]],AUTHORITY[\"EPSG\",\"4326\"]]";
}

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

std::string ProjectCrsWkt1(const ProjectCrs& crs) {
  switch (crs.kind) {
    case ProjectCrs::Kind::kNone: return "";
    case ProjectCrs::Kind::kLocalEnu:
      return "LOCAL_CS[\"sacfuse local ENU: origin lat " + Num(crs.origin_lat_deg) + ", lon " +
             Num(crs.origin_lon_deg) + ", h " + Num(crs.origin_h_m) +
             " m (WGS 84 ellipsoid); z = up, metres\",LOCAL_DATUM[\"east-north-up tangent plane\",32767]," +
             kMetre + ",AXIS[\"Easting\",EAST],AXIS[\"Northing\",NORTH]]";
    case ProjectCrs::Kind::kUtm: break;
  }
  const std::string name = crs.Name();
  const std::string projcs =
      "PROJCS[\"" + name + "\"," + GeogCs(crs.datum) +
      ",PROJECTION[\"Transverse_Mercator\"],PARAMETER[\"latitude_of_origin\",0],PARAMETER[\"central_meridian\"," +
      Num(6.0 * crs.utm_zone - 183.0) + "],PARAMETER[\"scale_factor\",0.9996],PARAMETER[\"false_easting\",500000]," +
      "PARAMETER[\"false_northing\"," + (crs.north ? "0" : "10000000") + "]," + kMetre +
      ",AXIS[\"Easting\",EAST],AXIS[\"Northing\",NORTH],AUTHORITY[\"EPSG\",\"" + std::to_string(crs.epsg) + "\"]]";
  return "COMPD_CS[\"" + name + " + ellipsoidal height\"," + projcs +
         ",VERT_CS[\"ellipsoidal height\",VERT_DATUM[\"Ellipsoid\",2002]," + kMetre + ",AXIS[\"Up\",UP]]]";
}

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
