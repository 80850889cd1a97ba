#include "jobs/las_options.h"

#include "config/version.h"
#include "io/las_crs.h"
#include "tiles/tile_manifest.h"

namespace sacfuse {

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

LasWriterOptions FusedCloudOptions(const JobConfig& config, const TilePlan& plan) {
  LasWriterOptions las = MakeLasOptions(config);
  las.offset = SharedTileOffset(plan);
  return las;
}

LasWriterOptions TileLasOptions(const JobConfig& config, const TilePlan& plan) {
  LasWriterOptions las = FusedCloudOptions(config, plan);
  las.compressed = true;
  return las;
}

}  // namespace sacfuse
