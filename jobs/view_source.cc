#include "jobs/view_source.h"

#include "tiling/tile_windows.h"

namespace sacfuse {

void LoadedViews::AddView(uint32_t view_id, const View& view, const DepthRasterSize& raster,
                          const PixelWindow& window, const FusionNeeds& needs, size_t i) {
  SacView sv = MakeSacView(view, &depths[i], needs.superpixels ? &superpixels[i] : nullptr,
                           colours[i].empty() ? nullptr : &colours[i],
                           needs.consistency_graphs ? &graphs[i] : nullptr);
  sv.depth_camera = WindowCamera(view.camera.Scaled(raster.width, raster.height), window);
  views.push_back(sv);
  view_ids.push_back(view_id);
}

}  // namespace sacfuse
