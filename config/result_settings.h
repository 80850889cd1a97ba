#pragma once
// The part of a config that affects a run's results: the keys whose row in config/option_table.cc says so (every
// input.*, fusion.*, superpixels.*, consistency.*, disparity_normal.*, tsdf.*, multiray.* and tiling.* key, crs,
// output.scale_m and output.las_version; not output.dir, output.format, fusion.superpixel_cache_dir (where files
// go, not what they hold), tiling.claim_timeout_s, resources.*, evaluation.*, log.*), and, when the run writes a
// DSM (DsmWanted), what each tile's DSM window depends on: output.dsm, output.dsm_cell_m and the cell rule. Tiled
// runs fingerprint it so that tiles computed under another config are never reused.
#include <string>
#include <vector>

#include "config/job_config.h"

namespace sacfuse {

// One "key: value" line per result-affecting key, in schema order (a flat YAML mapping).
std::string ResultSettingsText(const JobConfig& config);
// FNV-1a 64 of ResultSettingsText, as 16 hex digits.
std::string ResultSettingsHash(const JobConfig& config);
// Keys whose value differs between two ResultSettingsText texts (added or removed keys count as changed),
// as "key (old -> new)".
std::vector<std::string> ChangedResultSettings(const std::string& old_text, const std::string& new_text);

}  // namespace sacfuse
