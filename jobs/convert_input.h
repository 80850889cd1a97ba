#pragma once
// Writes a job's input (any format OpenInput reads) in another input format: how users bring a block into the
// form another tool wants, and how the tests check that every input path fuses to the same points.
#include <string>
#include <vector>

#include "config/job_config.h"
#include "io/depth_block.h"

namespace sacfuse {

// The formats ConvertInput can write (values of `sacfuse convert --to`).
std::vector<std::string> ConversionTargets();

// What some targets need besides the block.
struct ConvertContext {
  std::string crs;  // the input's project CRS (config `crs`); rasters-geodetic writes latitude/longitude in it
};

// Writes `input` as `target` into `out_dir` and returns the input options that read it back (format, path = out_dir,
// and any format-specific keys). Throws ConfigError for an unknown target.
InputOptions ConvertInput(const DepthBlock& input, const std::string& target, const std::string& out_dir,
                          const ConvertContext& context = {});

}  // namespace sacfuse
