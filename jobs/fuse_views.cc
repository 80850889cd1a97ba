#include "jobs/fuse_views.h"

#include "core/error.h"
#include "core/owned_region.h"
#include "jobs/point_sinks.h"

namespace sacfuse {
namespace {

// Valid depth pixels per view whose own point the scope owns.
void CountInput(const std::vector<SacView>& views, const OwnedRegion& owns, FusionStats* stats) {
  stats->input_pixels = 0;
  stats->input_per_view.assign(views.size(), 0);
  for (size_t i = 0; i < views.size(); ++i) {
    const uint64_t n = CountOwnedPixels(views[i], owns);
    stats->input_per_view[i] = n;
    stats->input_pixels += n;
  }
}

// A source's colours, for a method that reads them one view at a time.
class SourceColours : public ViewColours {
 public:
  SourceColours(const ViewSource& source, const LoadedViews& loaded) : source_(source), loaded_(loaded) {}
  RgbImage Load(size_t i) const override { return source_.LoadColours(loaded_, i); }

 private:
  const ViewSource& source_;
  const LoadedViews& loaded_;
};

}  // namespace

FusedViews FuseViews(const FusionMethod& method, const ViewSource& source, const MethodGeometry* geometry,
                     FusionScope scope, PointSink& sink, const std::function<void()>& on_loaded) {
  const FusionNeeds needs = method.needs();
  const std::unique_ptr<LoadedViews> loaded = source.Load(needs);
  if (on_loaded) on_loaded();
  FusedViews out;
  out.view_ids = loaded->view_ids;
  out.superpixels_computed = loaded->superpixels_computed;
  out.load_seconds = loaded->load_seconds;
  ViewPlan plan;
  if (needs.block_geometry) {
    if (geometry == nullptr) throw Error("fusion method " + method.name() + " needs the block geometry");
    plan = SubsetViewPlan(geometry->plan, loaded->view_ids);
    scope.plan = &plan;
    scope.gsd_m = geometry->gsd_m;
  }
  const SourceColours colours(source, *loaded);
  if (needs.colours_one_view_at_a_time) scope.colours = &colours;
  CountingSink written(sink);
  OwnedPointsSink owned(scope.owns, written);
  const bool filter_here = !scope.owns.OwnsEverything() && !needs.owns_pixels;
  out.stats = method.Fuse(loaded->views, scope, filter_here ? static_cast<PointSink&>(owned) : written);
  CountInput(loaded->views, scope.owns, &out.stats);
  out.points_written = written.count();
  out.points_per_view = written.per_view();
  out.points_not_owned = needs.owns_pixels ? out.stats.counter("pixels_not_owned") : owned.rejected();
  return out;
}

}  // namespace sacfuse
