#include "report/report_cross_section.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include <tbb/task_group.h>

#include "io/las_reader.h"
#include "report/report_png.h"
#include "report/report_profile_figure.h"
#include "report/report_profile_sources.h"
#include "report/report_text.h"
#include "tiling/footprint.h"

namespace sacfuse {

double GsdAtPoint(const DepthBlock& input, const Eigen::Vector3d& point_in_world) {
  double best = std::numeric_limits<double>::infinity();
  for (const View& view : input.views()) {
    if (!ViewSeesPoint(view, point_in_world)) continue;
    const DepthRasterSize size = input.DepthSize(view);
    const PinholeCamera camera = view.camera.Scaled(size.width, size.height);
    const double depth = (view.cam_from_world * point_in_world).z();
    if (depth > 0 && camera.fx > 0) best = std::min(best, depth / camera.fx);
  }
  return std::isfinite(best) ? best : 0.0;
}

ProfileFigure MakeCrossSection(const CrossSectionInputs& in, const std::string& report_dir) {
  ProfileFigure fig;
  StripPickOptions pick;
  if (!in.reference_las.empty()) {
    const LasHeader h = LasReader(in.reference_las).header();
    pick.within.Extend(Eigen::Vector2d(h.min.x(), h.min.y()));
    pick.within.Extend(Eigen::Vector2d(h.max.x(), h.max.y()));
  }
  const std::optional<ProfileStrip> picked = in.grid ? PickProfileStrip(*in.grid, pick) : std::nullopt;
  if (!picked) {
    fig.reason = "the fused cloud has no points to pick a strip from";
    return fig;
  }
  ProfileStrip strip = *picked;
  // Width: 2 GSD of the finest view at the strip's peak cell, halfway up its height range.
  const Eigen::Vector3d peak(strip.peak_xy.x(), strip.peak_xy.y(), 0.5 * (strip.z_min_m + strip.z_max_m));
  double gsd = 0.0;
  bool has_before = in.input != nullptr;
  if (has_before) {
    try {
      gsd = GsdAtPoint(*in.input, peak);
    } catch (const std::exception& e) {  // an unreadable depth map costs the "before" panel, not the report
      has_before = false;
      fig.before_reason = e.what();
    }
  }
  fig.gsd_source = "views' depth and focal length at the strip";
  if (gsd <= 0.0) {
    gsd = in.fallback_gsd_m;
    fig.gsd_source = "fused cloud's mean point spacing";
  }
  strip.half_width_m = gsd;
  fig.gsd_m = gsd;
  fig.strip = strip;

  // The three series are gathered at once (each sample its own, with its own seed): the fused points, the
  // reference and the depth windows are read side by side.
  ProfileSample after(in.max_points, 11), reference(in.max_points, 12), before(in.max_points, 13);
  const std::vector<std::string> after_files = in.after_files(strip.Box(), &fig.after_source);
  tbb::task_group series;
  series.run([&] { SampleLasInStrip(after_files, strip, &after); });
  if (!in.reference_las.empty()) {
    series.run([&] { SampleLasInStrip({in.reference_las}, strip, &reference, /*keep_source_id=*/false); });
    fig.has_reference = true;
  }
  if (has_before) {
    series.run([&] {
      try {
        const DepthStripStats st = SampleDepthInStrip(*in.input, strip, &before);
        fig.before_views = st.views_read;
        fig.before_window_pixels = st.window_pixels;
      } catch (const std::exception& e) {
        has_before = false;
        fig.before_reason = e.what();
      }
    });
  }
  series.wait();
  fig.after_in_strip = after.seen();
  fig.after_drawn = after.points().size();
  fig.reference_in_strip = reference.seen();
  fig.reference_drawn = reference.points().size();
  fig.before_in_strip = before.seen();
  fig.before_drawn = before.points().size();

  double lo = strip.z_min_m, hi = strip.z_max_m;
  if (!after.points().empty() || !reference.points().empty()) {
    RobustHeightRange({&after.points(), &reference.points()}, &lo, &hi);
  } else if (!before.points().empty()) {
    RobustHeightRange({&before.points()}, &lo, &hi);
  }
  fig.frame = MakePlotFrame(strip.Length(), lo, hi, in.max_width_px, in.min_width_px, in.min_height_px,
                            in.max_height_px);
  const std::vector<double> grid_z = NiceTicks(fig.frame.z_min, fig.frame.z_max, 5);
  const std::filesystem::path dir(report_dir);
  fig.after_file = "profile_after.png";
  if (has_before) fig.before_file = "profile_before.png";
  tbb::task_group panels;  // the two panels drawn and encoded side by side
  panels.run([&] {
    WritePng((dir / fig.after_file).string(),
             RenderProfilePanel(after.points(), reference.points(), in.colours, fig.frame, grid_z));
  });
  if (has_before) {
    panels.run([&] {
      ProfileStyle dense;
      dense.alpha = 0.35;  // many overlapping views
      WritePng((dir / fig.before_file).string(),
               RenderProfilePanel(before.points(), reference.points(), in.colours, fig.frame, grid_z, dense));
    });
  }
  panels.wait();
  fig.present = true;
  return fig;
}

}  // namespace sacfuse
