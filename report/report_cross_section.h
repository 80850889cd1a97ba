#pragma once
// The cross-section figure of the run report, end to end: pick the strip on the top grid, size it to 2 GSD, gather
// the before / after / reference points in it (report/report_profile_sources.h), render the two panels.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "io/depth_block.h"
#include "report/report_colours.h"
#include "report/report_figures.h"
#include "report/report_top_grid.h"

namespace sacfuse {

struct CrossSectionInputs {
  const TopGrid* grid = nullptr;              // of the fused cloud
  // The LAS files holding the fused points of a strip box (fused.las, or the tiles that meet it), and how to
  // name them on the page.
  std::function<std::vector<std::string>(const Box2d& strip_box, std::string* source)> after_files;
  std::string reference_las;                  // "" = none; when set, the strip is picked inside its bounds
  const DepthBlock* input = nullptr;          // nullptr = no "before" panel
  std::vector<Rgb> colours;                   // by view index
  double fallback_gsd_m = 0.1;                // when no view sees the strip
  size_t max_points = 60000;                  // per series
  int max_width_px = 470, min_width_px = 300;  // each panel (before and after stand side by side)
  int min_height_px = 170, max_height_px = 460;
};

// Smallest ground sampling distance of the views at `point_in_world`: its depth in each view that sees it over the
// view's focal length at depth-raster resolution. 0 when no view sees it.
double GsdAtPoint(const DepthBlock& input, const Eigen::Vector3d& point_in_world);

// Makes the figure and writes profile_before.png / profile_after.png into report_dir. When no strip can be
// picked the figure is absent with a reason; an unreadable depth map leaves out the "before" panel (with the
// reason). Throws when a LAS file cannot be read.
ProfileFigure MakeCrossSection(const CrossSectionInputs& in, const std::string& report_dir);

}  // namespace sacfuse
