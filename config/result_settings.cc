#include "config/result_settings.h"

#include <map>
#include <sstream>

#include "config/option_table.h"
#include "core/dsm_rule.h"
#include "io/file_checksum.h"

namespace sacfuse {
namespace {

std::map<std::string, std::string> ParseLines(const std::string& text) {
  std::map<std::string, std::string> values;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const auto colon = line.find(": ");
    if (colon == std::string::npos) continue;
    values[line.substr(0, colon)] = line.substr(colon + 2);
  }
  return values;
}

}  // namespace

std::string ResultSettingsText(const JobConfig& config) {
  std::string text;
  for (const OptionRow& row : JobOptionRows(config)) {
    if (row.spec.affects_results) text += row.key + ": " + row.value + "\n";
  }
  // A tile's DSM window (jobs/dsm_product.h) depends on whether the run writes a DSM, its cell (as configured: an
  // automatic cell follows from the inputs and the tile size, both checked already) and the cell rule; the rest of
  // the DSM's keys act only when the tiles are assembled. Absent without a DSM, so such runs keep their hash.
  if (DsmWanted(config)) {
    const DsmRule rule;
    text += "output.dsm: \"on\"\noutput.dsm_cell_m: " + OptionValueText(config.output.dsm_cell_m) +
            "\noutput.dsm_cell_rule: \"quantile " + OptionValueText(rule.quantile) + ", min_points " +
            std::to_string(rule.min_points) + "\"\n";
  }
  return text;
}

std::string ResultSettingsHash(const JobConfig& config) { return HexDigest(Fnv1a64(ResultSettingsText(config))); }

std::vector<std::string> ChangedResultSettings(const std::string& old_text, const std::string& new_text) {
  const auto old_values = ParseLines(old_text);
  const auto new_values = ParseLines(new_text);
  std::vector<std::string> changed;
  for (const auto& [key, value] : new_values) {
    const auto it = old_values.find(key);
    if (it == old_values.end()) {
      changed.push_back(key + " (new: " + value + ")");
    } else if (it->second != value) {
      changed.push_back(key + " " + it->second + " -> " + value);
    }
  }
  for (const auto& [key, value] : old_values) {
    if (!new_values.count(key)) changed.push_back(key + " (removed)");
  }
  return changed;
}

}  // namespace sacfuse
