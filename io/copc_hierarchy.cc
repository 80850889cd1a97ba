#include "io/copc_hierarchy.h"

#include <algorithm>
#include <map>
#include <set>

#include "core/error.h"

namespace sacfuse::copc {
namespace {

bool ByLevelThenKey(const Entry& a, const Entry& b) { return a.key < b.key; }

}  // namespace

std::vector<uint8_t> EncodeHierarchy(const std::vector<Entry>& given, uint64_t payload_offset,
                                     const PageLayout& layout, uint64_t* root_page_bytes, size_t* page_count) {
  std::vector<Entry> nodes = given;
  std::sort(nodes.begin(), nodes.end(), ByLevelThenKey);  // parents before children
  if (nodes.empty() || nodes[0].key.level != 0) throw Error("COPC hierarchy without a root node");
  std::map<VoxelKey, size_t> index;
  for (size_t i = 0; i < nodes.size(); ++i) {
    if (!index.emplace(nodes[i].key, i).second) {
      throw Error("COPC hierarchy: node " + nodes[i].key.ToString() + " twice");
    }
  }
  std::vector<size_t> parent(nodes.size(), 0);
  for (size_t i = 1; i < nodes.size(); ++i) {
    const auto p = index.find(nodes[i].key.Parent());
    if (p == index.end()) throw Error("COPC hierarchy: node " + nodes[i].key.ToString() + " has no parent node");
    parent[i] = p->second;
  }
  std::vector<size_t> subtree(nodes.size(), 1);
  for (size_t i = nodes.size() - 1; i > 0; --i) subtree[parent[i]] += subtree[i];

  // Each node's page: its own when it roots one, else its parent's.
  const int levels = std::max(1, layout.page_levels);
  std::vector<size_t> page_of(nodes.size(), 0);
  std::vector<bool> roots_page(nodes.size(), false);
  roots_page[0] = true;
  for (size_t i = 1; i < nodes.size(); ++i) {
    roots_page[i] = nodes[i].key.level % levels == 0 && subtree[i] >= layout.min_page_entries;
    page_of[i] = roots_page[i] ? i : page_of[parent[i]];
  }
  struct Page {
    std::vector<size_t> entries;      // nodes listed in it
    std::vector<size_t> child_pages;  // page roots referenced from it
    uint64_t offset = 0;
  };
  std::map<size_t, Page> pages;  // by page root (node index)
  for (size_t i = 0; i < nodes.size(); ++i) {
    pages[page_of[i]].entries.push_back(i);
    if (i > 0 && roots_page[i]) pages[page_of[parent[i]]].child_pages.push_back(i);
  }
  // Depth-first order from the root page; entries of a page sorted by key (both lists already are).
  std::vector<size_t> order;
  std::vector<size_t> stack = {0};
  while (!stack.empty()) {
    const size_t p = stack.back();
    stack.pop_back();
    order.push_back(p);
    const std::vector<size_t>& kids = pages[p].child_pages;
    for (auto it = kids.rbegin(); it != kids.rend(); ++it) stack.push_back(*it);
  }
  const auto page_bytes = [&](const Page& page) {
    return kEntrySize * (page.entries.size() + page.child_pages.size());
  };
  uint64_t at = payload_offset;
  for (size_t p : order) {
    pages[p].offset = at;
    at += page_bytes(pages[p]);
  }
  std::vector<uint8_t> payload;
  payload.reserve(static_cast<size_t>(at - payload_offset));
  for (size_t p : order) {
    const Page& page = pages[p];
    std::vector<Entry> listed;
    for (size_t i : page.entries) listed.push_back(nodes[i]);
    for (size_t child : page.child_pages) {
      const Page& c = pages[child];
      listed.push_back({nodes[child].key, c.offset, static_cast<int32_t>(page_bytes(c)), -1});
    }
    // A page root's own entry is in its own page; its -1 reference in the parent's page: keys never repeat.
    std::sort(listed.begin(), listed.end(), ByLevelThenKey);
    for (const Entry& e : listed) AppendEntry(e, &payload);
  }
  *root_page_bytes = page_bytes(pages[0]);
  *page_count = pages.size();
  return payload;
}

HierarchyWalk WalkHierarchy(const ReadBytes& read, uint64_t root_offset, uint64_t root_size, uint64_t first,
                            uint64_t end) {
  HierarchyWalk walk;
  std::set<uint64_t> seen_pages;
  std::set<VoxelKey> seen_keys;
  struct Pending {
    uint64_t offset, size;
    std::string from;
  };
  std::vector<Pending> todo = {{root_offset, root_size, "info VLR"}};
  std::vector<uint8_t> bytes;
  while (!todo.empty()) {
    const Pending page = todo.back();
    todo.pop_back();
    const std::string where = "page at " + std::to_string(page.offset) + " (" + std::to_string(page.size) +
                              " bytes, from " + page.from + ")";
    if (page.size == 0 || page.size % kEntrySize != 0) {
      walk.problems.push_back(where + ": size is not a positive multiple of " + std::to_string(kEntrySize));
      continue;
    }
    if (page.offset < first || page.offset + page.size > end) {
      walk.problems.push_back(where + ": outside the hierarchy EVLR [" + std::to_string(first) + ", " +
                              std::to_string(end) + ")");
      continue;
    }
    if (!seen_pages.insert(page.offset).second) {
      walk.problems.push_back(where + ": referenced twice");
      continue;
    }
    if (!read(page.offset, static_cast<size_t>(page.size), &bytes)) {
      walk.problems.push_back(where + ": cannot be read");
      continue;
    }
    ++walk.pages;
    for (size_t at = 0; at + kEntrySize <= bytes.size(); at += kEntrySize) {
      const Entry e = DecodeEntry(&bytes[at]);
      const std::string name = "entry " + e.key.ToString() + " in " + where;
      if (!e.key.Valid()) {
        walk.problems.push_back(name + ": invalid key");
        continue;
      }
      if (e.point_count == -1) {
        todo.push_back({e.offset, static_cast<uint64_t>(std::max(e.byte_size, 0)), "entry " + e.key.ToString()});
        continue;
      }
      if (e.point_count < -1) {
        walk.problems.push_back(name + ": point count " + std::to_string(e.point_count));
        continue;
      }
      if (!seen_keys.insert(e.key).second) {
        walk.problems.push_back(name + ": node listed twice");
        continue;
      }
      walk.nodes.push_back(e);
    }
  }
  return walk;
}

}  // namespace sacfuse::copc
