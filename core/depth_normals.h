#pragma once
// Surface normals computed from a depth raster alone (for methods that compare normals, like fusibile's
// disparity-and-normal consistency, when the input's normal maps are not used): a least-squares plane through
// the back-projected pixels of a (2r+1) x (2r+1) window, pixels on another surface excluded.
#include "core/raster.h"
#include "core/sac_view.h"

namespace sacfuse {

// Unit normals in the WORLD frame, one per depth pixel (3 channels), facing the view's camera; (0, 0, 0) where
// the pixel is invalid or fewer than 5 window pixels lie on its surface. A window pixel counts when its depth is
// within 3 local GSDs per pixel of distance (Chebyshev, plus one) of the centre's depth, so depth edges do not
// tilt the normals of either side. The plane is the eigenvector of the smallest eigenvalue of the points'
// covariance (camera frame, relative to the centre pixel's point). Parallel over rows; deterministic.
NormalMap PlaneFitNormalsInWorld(const SacView& view, int radius_px);

}  // namespace sacfuse
