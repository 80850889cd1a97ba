#include "jobs/las_options.h"

#include <algorithm>

#include "config/version.h"
#include "io/las_crs.h"
#include "jobs/auto_tiling.h"
#include "tiles/memory_model.h"
#include "tiles/tile_manifest.h"

namespace sacfuse {
namespace {

// What the budget leaves for a COPC build once the process's own memory is set aside.
uint64_t CopcBudgetBytes(const JobConfig& config) {
  const uint64_t budget = MemoryBudgetBytes(config.resources.memory_gb);
  return budget > 2 * kProcessBaseBytes ? budget - kProcessBaseBytes : budget / 2;
}

}  // namespace

LasWriterOptions MakeLasOptions(const OutputOptions& output) {
  LasWriterOptions o;
  o.version_minor = output.las_version == "1.2" ? 2 : 4;
  o.scale_m = output.scale_m;
  o.compressed = output.format == "laz";
  o.generating_software = VersionString();
  return o;
}

LasWriterOptions MakeLasOptions(const JobConfig& config) {
  LasWriterOptions o = MakeLasOptions(config.output);
  AddCrsToLasOptions(ParseProjectCrs(config.crs), &o);
  return o;
}

CopcOptions MakeCopcOptions(uint64_t memory_bytes) {
  CopcOptions o;
  o.memory_bytes = memory_bytes;
  return o;
}

CloudFileOptions FusedCloudOptions(const JobConfig& config) {
  CloudFileOptions o{MakeLasOptions(config), std::nullopt};
  if (config.output.format == "copc") o.copc = MakeCopcOptions(CopcBudgetBytes(config));
  return o;
}

CloudFileOptions FusedCloudOptions(const JobConfig& config, const TilePlan& plan) {
  CloudFileOptions o = FusedCloudOptions(config);
  o.las.offset = SharedTileOffset(plan);
  return o;
}

CloudFileOptions TileCloudOptions(const JobConfig& config, const TilePlan& plan) {
  CloudFileOptions o = FusedCloudOptions(config, plan);
  o.las.compressed = true;
  if (o.copc) {
    const uint64_t threads = std::max<uint64_t>(1, EffectiveThreads(config));
    o.copc = MakeCopcOptions(TileMemoryPoolBytes(MemoryBudgetBytes(config.resources.memory_gb)) / threads);
  }
  return o;
}

}  // namespace sacfuse
