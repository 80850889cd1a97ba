#include "io/colmap_patch_match_config.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>

#include "core/error.h"
#include "io/input_file.h"
#include "io/trimmed.h"

namespace sacfuse {
namespace {

std::string Quoted(const std::string& s) { return "\"" + s + "\""; }

std::vector<std::string> SplitCommas(const std::string& line) {
  std::vector<std::string> parts;
  size_t begin = 0;
  while (true) {
    const size_t comma = line.find(',', begin);
    parts.push_back(Trimmed(line.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin)));
    if (comma == std::string::npos) return parts;
    begin = comma + 1;
  }
}

}  // namespace

std::vector<PatchMatchEntry> ReadPatchMatchConfig(const std::string& path) {
  std::ifstream in = OpenInputStream(path, "patch-match.cfg");
  std::vector<std::pair<std::string, int>> lines;  // non-empty lines, trimmed, with their numbers
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    std::string trimmed = Trimmed(line);
    if (!trimmed.empty()) lines.emplace_back(std::move(trimmed), number);
  }
  std::vector<PatchMatchEntry> entries;
  std::set<std::string> seen;
  for (size_t k = 0; k < lines.size(); k += 2) {
    PatchMatchEntry entry;
    entry.image = lines[k].first;
    entry.line = lines[k].second;
    const std::string at = "line " + std::to_string(entry.line) + ": image " + Quoted(entry.image);
    if (k + 1 == lines.size()) {
      throw InputError(path, at + " has no sources line (the file alternates an image name line and a line of its "
                                  "sources: names separated by commas, __all__ or __auto__, N)");
    }
    if (!seen.insert(entry.image).second) throw InputError(path, at + " is listed twice");
    const std::string& sources = lines[k + 1].first;
    const std::string source_at = "line " + std::to_string(lines[k + 1].second) + " (sources of " +
                                  Quoted(entry.image) + ")";
    const std::vector<std::string> parts = SplitCommas(sources);
    if (parts[0] == "__all__" && parts.size() == 1) {
      entry.automatic = true;
    } else if (parts[0] == "__auto__") {
      char* end = nullptr;
      const long count = parts.size() == 2 ? std::strtol(parts[1].c_str(), &end, 10) : 0;
      if (parts.size() != 2 || parts[1].empty() || *end != '\0' || count <= 0) {
        throw InputError(path, source_at + ": " + Quoted(sources) + " is not \"__auto__, N\" with N a positive "
                                                                      "integer");
      }
      entry.automatic = true;
    } else {
      for (const std::string& name : parts) {
        if (name.empty()) throw InputError(path, source_at + ": an empty image name in " + Quoted(sources));
        if (name == entry.image) throw InputError(path, source_at + ": the image is listed among its own sources");
        entry.sources.push_back(name);
      }
    }
    entries.push_back(std::move(entry));
  }
  return entries;
}

std::vector<std::vector<uint32_t>> MatchingPartners(const std::vector<PatchMatchEntry>& entries,
                                                    const std::vector<View>& views) {
  std::vector<std::set<uint32_t>> partners(views.size());
  std::map<std::string, uint32_t> by_name;
  for (uint32_t i = 0; i < views.size(); ++i) by_name.emplace(views[i].name, i);
  for (const PatchMatchEntry& entry : entries) {
    const auto a = by_name.find(entry.image);
    if (entry.automatic) {
      if (a != by_name.end()) return std::vector<std::vector<uint32_t>>(views.size());
      continue;  // an image left out of the fusion
    }
    if (a == by_name.end()) continue;
    for (const std::string& name : entry.sources) {
      const auto b = by_name.find(name);
      if (b == by_name.end()) continue;
      partners[a->second].insert(b->second);
      partners[b->second].insert(a->second);
    }
  }
  std::vector<std::vector<uint32_t>> out(views.size());
  for (size_t i = 0; i < views.size(); ++i) out[i].assign(partners[i].begin(), partners[i].end());
  return out;
}

}  // namespace sacfuse
