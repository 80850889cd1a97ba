#pragma once
// `fusion.collapse: best_view` — a collapse that really collapses (the paper: "each surface patch taken from as few,
// mutually consistent depth maps as possible"). After the Netlet coverage rule (core/collapse.h), a pixel of view v
// with point X is also dropped when a more precise view b holds the same surface at X and emits it there:
//   * same surface: b's depth at X's projection agrees with X's depth in b within the strict tolerance or within
//     `redundancy_tolerance_sigmas` sigma of the estimated noise of the two depths' difference;
//   * more precise: lower expected depth noise at X, sigma_b = k_b z_b^2 / f_b (stereo sigma_z = z^2 sigma_d / (f B),
//     k_b the per-view factor estimated from the data, core/view_noise.h); ties to the lower view index. It depends
//     on the place only, so the pixels of all views near X agree on which view is best. (With the quality unary's
//     incidence angle on each pixel's noisy superpixel normal, views dropped each other's pixels in cycles and left
//     holes: aerial-bench Montpellier F1 0.846 against 0.969.)
//   * emits it: b's pixel there keeps its own Netlet label (so the Netlet coverage rule does not drop it in turn) and
//     passes the outlier and free-space tests (core/point_verdicts.h). A chain of better views thus ends at a pixel
//     that is emitted: every consistently observed surface keeps a point, now from its best view only.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/consulted_views.h"
#include "core/point_verdicts.h"
#include "core/sac_labeling.h"
#include "core/sac_nodes.h"
#include "core/sac_options.h"
#include "core/sac_view.h"

namespace sacfuse {

// Whether a view of `judges` more precise than v holds and emits the surface at X = `point_in_world` (the pixel's
// own point at depth `depth_m`). `chosen_view`: the Netlet labels of `nodes`; `noise_factor` as core/view_noise.h
// (empty = 1 for every view).
bool BetterViewEmits(const std::vector<SacView>& views, uint32_t v, const Eigen::Vector3d& point_in_world,
                     double depth_m, const std::vector<uint32_t>& judges, const std::vector<double>& noise_factor,
                     const NodeTable& nodes, const NodeLabels& chosen_view, const PointVerdicts& verdicts,
                     const SacOptions& options);

// The order in which BetterViewEmits searches each list of `judges`: most precise first, by
// k_b zbar_b^2 / f_b (zbar_b the mean valid depth of view b, sampled), ties to the lower index. The answer is the
// same in any order (is there a better view that emits X?) and so is every verdict (each is its pixel's own), so
// the output does not change; but the most precise view is the one most likely to emit X, so the search usually
// stops at its first candidate and judges fewer pixels of other views (issue 13).
ConsultedViews RedundancySearchOrder(const std::vector<SacView>& views, const ConsultedViews& judges,
                                     const std::vector<double>& noise_factor);

}  // namespace sacfuse
