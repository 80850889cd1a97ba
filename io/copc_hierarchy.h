#pragma once
// The COPC hierarchy EVLR: pages of 32-byte entries (io/copc_format.h), written by io/copc_writer.h and walked by
// io/copc_validate.h. Private to io/.
//
// Pages as written: the root page holds the nodes of levels 0 .. page_levels - 1; a node of level
// n x page_levels (n >= 1) whose subtree has at least min_page_entries nodes gets a page of its own (its own entry
// and its subtree's down to the next such page), referenced from the page of its parent by an entry with point
// count -1; smaller subtrees stay in their parent's page. Entries within a page are sorted by key; pages follow
// the root page depth first, so a reader fetches the top of the tree with one small read.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "io/copc_format.h"

namespace sacfuse::copc {

struct PageLayout {
  int page_levels = 4;
  size_t min_page_entries = 64;
};

// The EVLR payload for `nodes` (every node with points and every 0-point node with descendants; each node's
// ancestors must be among them), whose first byte will be at absolute file offset `payload_offset`;
// *root_page_bytes gets the size of the root page (the payload's first bytes), *pages the number of pages.
std::vector<uint8_t> EncodeHierarchy(const std::vector<Entry>& nodes, uint64_t payload_offset,
                                     const PageLayout& layout, uint64_t* root_page_bytes, size_t* pages);

// Reads `bytes` bytes at absolute `offset` into `out`; false when they are not in the file.
using ReadBytes = std::function<bool(uint64_t offset, size_t bytes, std::vector<uint8_t>* out)>;

struct HierarchyWalk {
  std::vector<Entry> nodes;  // every non-page entry, in the order found
  size_t pages = 0;
  std::vector<std::string> problems;  // pages that cannot be read, repeated pages or keys, invalid entries
};
// Walks the pages from the root page (offset and size from the info VLR); each page must lie within
// [first, end) (the hierarchy EVLR's payload) and be a whole number of entries.
HierarchyWalk WalkHierarchy(const ReadBytes& read, uint64_t root_offset, uint64_t root_size, uint64_t first,
                            uint64_t end);

}  // namespace sacfuse::copc
