#pragma once
// How the true orthophoto colours a cell (docs/dsm-and-ortho.md): pure geometry, no file I/O.
//
// A cell with a DSM height z is the 3D point X = (centre x, centre y, z). A view SEES X when X lies in front of it,
// projects inside its image, and the ray from X to the view's centre never passes more than
// OrthoRule::occlusion_tolerance_m below the DSM (RayClearOfDsm). The cell's view (OrthoCellViews) is
//   1. the view SAC selected for the cell's surface (the source view of the point that made the cell's DSM height,
//      jobs/ortho_product.h), when it sees X and the cell is not at a wall (OrthoRule::wall_step_m);
//   2. else the most nadir view that sees X (smallest angle between the ray X -> centre and the vertical; ties to
//      the lower view index), which is also the rule for cells without points (the DSM's filled holes);
//   3. else none: the cell stays transparent.
// The cell's colour is the bilinear sample (SampleBilinear) of that view's ORIGINAL image at X's projection.
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/camera.h"
#include "core/cell_window.h"
#include "core/raster.h"
#include "core/rigid3.h"

namespace sacfuse {

struct OrthoRule {
  // The ray may pass this far below the DSM before it counts as blocked (the DSM's noise; 1 cell by default).
  double occlusion_tolerance_m = 0.25;
  // Cells within this distance of X (metres, horizontally) are not tested: the DSM around X is X's own surface.
  double self_distance_m = 0.375;
  // Rays are followed this far horizontally (a 100 m building seen 30 degrees off nadir hides 58 m of ground).
  double max_ray_m = 60.0;
  // Step along the ray, horizontally, metres (half a cell by default).
  double step_m = 0.125;
  // A cell with a neighbour (of its 8) higher by more than this is at the foot or on the face of a wall: its height
  // may be a façade point's, and the view SAC selected there is the oblique that saw the façade, whose image shows
  // the wall where a top view shows the roof's edge or the ground; such a cell takes the most nadir view that sees
  // it (2 cells by default: steeper than 63 degrees).
  double wall_step_m = 0.5;
};

// The rule for cells of `cell_m`: tolerance 1 cell, self distance 1.5 cells, step 0.5 cell, rays up to 60 m, wall
// step 2 cells.
OrthoRule OrthoRuleForCell(double cell_m);
// Cells of context around a block the occlusion test reads (max_ray_m in cells, rounded up).
int64_t OrthoHaloCells(const OrthoRule& rule, double cell_m);

struct OrthoView {
  uint32_t index = 0;         // view index (LAS point source ID - 1)
  PinholeCamera camera;       // at the resolution of the image that will be sampled
  Rigid3d cam_from_world;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // world
};
OrthoView OrthoViewOf(uint32_t index, const PinholeCamera& camera, const Rigid3d& cam_from_world);

// A window of the DSM: heights north-up over `window` (NaN = none), plus their maximum.
struct DsmPatch {
  CellWindow window;
  std::vector<float> z;
  float z_max = 0.0f;  // of the finite heights (lowest float when none)
};
DsmPatch MakeDsmPatch(const CellWindow& window, std::vector<float> z);

// X's projection into the view's image when X is in front and inside the image ([0, width) x [0, height)).
bool ProjectsInside(const OrthoView& view, const Eigen::Vector3d& x, Eigen::Vector2d* uv);
// Whether the ray X -> centre stays above the DSM (within the tolerance) as far as the patch and max_ray_m reach.
bool RayClearOfDsm(const Eigen::Vector3d& x, const Eigen::Vector3d& centre, const DsmPatch& dsm, const OrthoRule& rule);

// The view of every cell of `inner` (north-up; -1 = none) by the rule above. `selected` (north-up over `inner`)
// holds the SAC-selected view index per cell or -1; `dsm` must contain `inner` (grown by OrthoHaloCells for exact
// occlusion). `views` are indexed by view index (views[i].index == i). Rows run on the job's threads (TBB).
std::vector<int32_t> OrthoCellViews(const DsmPatch& dsm, const CellWindow& inner, const std::vector<int32_t>& selected,
                                    const std::vector<OrthoView>& views, const OrthoRule& rule);

// Bilinear sample of `image` (3 channels) at image coordinates (u, v) (pixel centres at +0.5; clamped at the
// border).
std::array<uint8_t, 3> SampleBilinear(const RgbImage& image, double u, double v);

// The colour of a cell of edge cell_m whose surface point is X: the mean of the bilinear samples of `image` (seen
// through `camera`, `cam_from_world`) at the projections of n x n points evenly spread over the cell at X's height,
// n = ceil(cell_m / the image's pixel size at X) within [kMinCellSamples, kMaxCellSamples]: the image averaged over
// the cell's area (at least one sample per image pixel), as a downsampling filter must, not point-sampled.
constexpr int kMinCellSamples = 2, kMaxCellSamples = 8;
std::array<uint8_t, 3> CellColour(const RgbImage& image, const PinholeCamera& camera, const Rigid3d& cam_from_world,
                                  const Eigen::Vector3d& x, double cell_m);

// The 3D point of cell (col, row) of height z: its centre at that height.
inline Eigen::Vector3d CellPoint(int64_t col, int64_t row, double cell_m, double z) {
  return {CellEdge(col, cell_m) + 0.5 * cell_m, CellEdge(row, cell_m) + 0.5 * cell_m, z};
}

}  // namespace sacfuse
