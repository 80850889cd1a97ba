#pragma once
// The LAS writer options every LAS a job writes (tiles, fused.las/laz/copc.laz, merge, union) is written with,
// and the file layout output.format chooses (LAS, LAZ or COPC: io/point_cloud_writer.h).
#include "config/job_config.h"
#include "io/las_writer.h"
#include "io/point_cloud_writer.h"
#include "tiles/tile_plan.h"

namespace sacfuse {

// LAS writer options of a config's output (version, scale, generating software; no offset, no CRS).
LasWriterOptions MakeLasOptions(const OutputOptions& output);
// The same plus the CRS records of config `crs` (io/las_crs.h).
LasWriterOptions MakeLasOptions(const JobConfig& config);
// COPC builds of a job: out of core within `memory_bytes`, work files beside the output (io/copc_writer.h).
CopcOptions MakeCopcOptions(uint64_t memory_bytes);
// An untiled run's fused cloud: MakeLasOptions(config), COPC for output.format copc, built within the budget
// (the fusion's memory is released before the COPC is built).
CloudFileOptions FusedCloudOptions(const JobConfig& config);
// A tiled run's: the merged cloud's (output.format) with the plan's shared offset (tiles/tile_manifest.h), and the
// tiles' (the same, always compressed: LAZ, a ninth of the disk of LAS for files read back by the merge; COPC for
// output.format copc, so that DIR/tiles.vpc streams in viewers; tiles/tile_marker.h). A tile's COPC build gets
// the share of the budget of one of the tiles running at once.
CloudFileOptions FusedCloudOptions(const JobConfig& config, const TilePlan& plan);
CloudFileOptions TileCloudOptions(const JobConfig& config, const TilePlan& plan);

}  // namespace sacfuse
