#pragma once
// The one interface every fusion method implements (SAC and the comparison methods): what it needs of the views
// besides depth and colour, and Fuse(views, scope, sink) -> FusionStats. The job (jobs/fuse_views.h) loads the
// views — a whole block or a tile's windows — and calls Fuse the same way for every method.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/fusion_stats.h"
#include "core/method_views.h"
#include "core/owned_region.h"
#include "core/point.h"
#include "core/sac_view.h"

namespace sacfuse {

// What a method reads besides each view's depth and colours.
struct FusionNeeds {
  bool superpixels = false;         // SacView::superpixels (SAC's nodes)
  bool consistency_graphs = false;  // SacView::consistency (SAC with fusion.correspondence: dense)
  bool block_geometry = false;      // FusionScope::plan and gsd_m (the comparison methods)
  // true: the method applies FusionScope::owns to each pixel's own point itself (SAC, whose averaging moves a
  // point along its ray differently in each tile); false: the job keeps the emitted points the scope owns.
  bool owns_pixels = false;
  // true: the method reads a view's colours only while it emits that view's points, one view after another (SAC).
  // The job then loads no colours with the views (SacView::image stays null) and hands each view's colours out
  // when asked (FusionScope::colours), so a run holds one view's colours instead of every view's (issue 13: 3 B
  // per depth pixel, a sixth of an untiled run's heap).
  bool colours_one_view_at_a_time = false;
};

// Colours loaded when a method asks for them (FusionNeeds::colours_one_view_at_a_time).
class ViewColours {
 public:
  virtual ~ViewColours() = default;
  // The colours of views[i] on its depth raster or window, what SacView::image would point to; empty = grey
  // points. Throws InputError for an unreadable image.
  virtual RgbImage Load(size_t i) const = 0;
};

// Where one run sits in the block.
struct FusionScope {
  const ViewPlan* plan = nullptr;           // neighbours and order, positions in the views (needs.block_geometry)
  double gsd_m = 0.0;                       // the block's GSD, metres (needs.block_geometry)
  const Box2d* region_xy = nullptr;  // the XY box the views were cut to (a tile's halo); null = unbounded
  OwnedRegion owns;                  // which pixels (or points) the run emits: a tile's core (default: all)
  const ViewColours* colours = nullptr;  // set by the job when the method needs colours one view at a time
};

class FusionMethod {
 public:
  virtual ~FusionMethod() = default;
  virtual std::string name() const = 0;
  virtual FusionNeeds needs() const = 0;
  // Streams the fused points of `views` to `sink`. input_per_view / input_pixels are filled by the caller
  // (jobs/fuse_views.h), the same way for every method.
  virtual FusionStats Fuse(const std::vector<SacView>& views, const FusionScope& scope, PointSink& sink) const = 0;
};

}  // namespace sacfuse
