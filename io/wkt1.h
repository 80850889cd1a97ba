#pragma once
// OGC WKT1 (CT 1.0, the dialect of LAS 1.4's LASF_Projection/2112 record): a small parser so `sacfuse validate`,
// readers and tests can look inside any WKT1 string without PROJ (what sacfuse writes comes from PROJ: io/crs.h).
#include <optional>
#include <string>
#include <vector>

namespace sacfuse {

// One WKT1 node: KEYWORD["quoted", 1.5, CHILD[...], ENUM].
struct WktNode {
  std::string keyword;                 // e.g. "PROJCS"
  std::vector<std::string> values;     // quoted strings (unquoted), numbers and bare words, in order
  std::vector<WktNode> children;

  const WktNode* Child(const std::string& keyword) const;  // first child with that keyword, or nullptr
  // EPSG code of this node's AUTHORITY["EPSG","code"] child, or 0.
  int EpsgAuthority() const;
};

// Parses one WKT1 node (keyword, brackets [] or (), quoted strings with "" escapes). Throws sacfuse::Error with
// the character position on malformed text or trailing garbage.
WktNode ParseWkt1(const std::string& text);

// Horizontal EPSG code of a WKT1 CRS: the AUTHORITY of PROJCS or GEOGCS (also inside COMPD_CS), or 0.
int WktHorizontalEpsg(const WktNode& root);

}  // namespace sacfuse
