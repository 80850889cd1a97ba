#pragma once
// Test helper of the report tests: a DepthBlock held in memory (views with hand-made depth rasters), counting
// how many depth pixels the code under test reads.
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "core/error.h"
#include "io/depth_block.h"

namespace sacfuse::testing {

class MemoryDepthBlock : public DepthBlock {
 public:
  void Add(View view, DepthMap depth) {
    view.index = static_cast<uint32_t>(views_.size());
    views_.push_back(std::move(view));
    depths_.push_back(std::move(depth));
  }
  const std::string& source() const override { return source_; }
  const std::vector<View>& views() const override { return views_; }
  std::string DepthMapPath(const View& view) const override { return "memory:" + view.name; }
  std::string ImagePath(const View& /*view*/) const override { return ""; }
  DepthRasterSize DepthSize(const View& view) const override {
    return {depths_[view.index].width, depths_[view.index].height};
  }
  DepthMap ReadDepthMap(const View& view) const override {
    pixels_read += depths_[view.index].num_pixels();
    return depths_[view.index];
  }
  DepthMap ReadDepthWindow(const View& view, const PixelWindow& w) const override {
    const DepthMap& d = depths_[view.index];
    if (!w.FitsIn(d.width, d.height)) throw Error("window outside the raster: " + PixelWindowText(w));
    DepthMap out(w.width(), w.height());
    for (int r = 0; r < w.height(); ++r) {
      for (int c = 0; c < w.width(); ++c) out.at(r, c) = d.at(w.row_begin + r, w.col_begin + c);
    }
    pixels_read += w.num_pixels();
    return out;
  }
  RgbImage ReadImage(const View&) const override { return {}; }

  mutable uint64_t pixels_read = 0;

 private:
  std::string source_ = "memory";
  std::vector<View> views_;
  std::vector<DepthMap> depths_;
};

// A nadir camera (looking straight down, image x = world +x, image y = world -y) centred above (x, y) at height
// `height_m` over z = 0, width x height pixels of focal length f_px: ground sampling distance height_m / f_px.
inline View NadirView(const std::string& name, double x, double y, double height_m, int width, int height,
                      double f_px) {
  View v;
  v.name = name;
  v.camera = PinholeCamera::Centered(width, height, f_px);
  // cam_from_world: rotation of 180 degrees about x (camera z = world -z, camera y = world -y).
  v.cam_from_world.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()));
  v.cam_from_world.translation = -(v.cam_from_world.rotation * Eigen::Vector3d(x, y, height_m));
  return v;
}

}  // namespace sacfuse::testing
