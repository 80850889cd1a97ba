#pragma once
// The LAS writer options every LAS a job writes (tiles, fused.las/laz, merge, union) is written with.
#include "config/job_config.h"
#include "io/las_writer.h"
#include "tiles/tile_plan.h"

namespace sacfuse {

// LAS writer options of a config's output (version, scale, generating software; no offset, no CRS).
LasWriterOptions MakeLasOptions(const OutputOptions& output);
// The same plus the CRS records of config `crs` (io/las_crs.h).
LasWriterOptions MakeLasOptions(const JobConfig& config);
// A tiled run's: the merged cloud's (output.format) with the plan's shared offset (tiles/tile_manifest.h), and the
// tiles' (the same, always LAZ: a ninth of the disk of LAS for intermediate files, tiles/tile_marker.h).
LasWriterOptions FusedCloudOptions(const JobConfig& config, const TilePlan& plan);
LasWriterOptions TileLasOptions(const JobConfig& config, const TilePlan& plan);

}  // namespace sacfuse
