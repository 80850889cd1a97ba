#pragma once
// The block a job fuses: its input (jobs/open_input.h) with every view's pose corrected by co-registration
// (core/coregistration.h) when coregistration.enabled. A block-level stage before tiling, so a tiled run and an
// untiled one fuse the same poses, and every tile worker the poses its plan was made with.
//
// DIR/coregistration.json keeps the corrected poses with what they were made from: the digest of the views'
// identities as read (io/view_identity.h: depth map, image, camera) and the coregistration.* options. A later run,
// or a tile worker, reuses the file while both are unchanged and computes (then writes, atomically) otherwise, so
// the poses are never stale and a resumed run does not read every depth map again.
#include <memory>
#include <string>
#include <vector>

#include "config/job_config.h"
#include "core/coregistration.h"
#include "io/depth_block.h"
#include "io/reposed_block.h"

namespace sacfuse {

// What the stage did, for the log and run_report.json.
struct CoregistrationOutcome {
  bool enabled = false;
  bool reused = false;          // read from DIR/coregistration.json
  double seconds = 0.0;         // wall time of the stage (reading, decimating, solving; or reading the file)
  int decimation = 0;           // largest decimation factor over the views
  CoregistrationSummary summary;
};

// `input` as the job fuses it: unchanged when coregistration.enabled is false, else a ReposedBlock
// (io/reposed_block.h) with the poses of DIR/coregistration.json (reused or computed, above). Throws InputError
// naming a view whose depth map cannot be read.
std::unique_ptr<DepthBlock> WithCoregisteredPoses(const JobConfig& config, std::unique_ptr<DepthBlock> input,
                                                  CoregistrationOutcome* outcome = nullptr);

}  // namespace sacfuse
