#pragma once
// A DepthBlock whose views have other poses than its input's; rasters, images, files and consistency graphs are
// the input's. Two uses: the workspace origin (input.origin_m: a workspace in a local frame shifted from the
// project CRS) and co-registration (jobs/coregistered_block.h: corrected poses).
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/rigid3.h"
#include "io/depth_block.h"

namespace sacfuse {

class ReposedBlock : public DepthBlock {
 public:
  // View i gets cam_from_world[i]; SceneHeights are the input's + scene_height_shift_m. Throws Error when the
  // counts differ.
  ReposedBlock(std::unique_ptr<DepthBlock> inner, const std::vector<Rigid3d>& cam_from_world,
               double scene_height_shift_m = 0.0);

  const std::string& source() const override { return inner_->source(); }
  const std::vector<View>& views() const override { return views_; }
  std::string DepthMapPath(const View& view) const override { return inner_->DepthMapPath(Inner(view)); }
  std::string ImagePath(const View& view) const override { return inner_->ImagePath(Inner(view)); }
  DepthRasterSize DepthSize(const View& view) const override { return inner_->DepthSize(Inner(view)); }
  DepthMap ReadDepthMap(const View& view) const override { return inner_->ReadDepthMap(Inner(view)); }
  DepthMap ReadDepthWindow(const View& view, const PixelWindow& window) const override {
    return inner_->ReadDepthWindow(Inner(view), window);
  }
  DepthMap ReadDepthRows(const View& view, const std::vector<int>& rows) const override {
    return inner_->ReadDepthRows(Inner(view), rows);
  }
  RgbImage ReadImage(const View& view) const override { return inner_->ReadImage(Inner(view)); }
  std::vector<double> SceneHeights() const override;
  std::string SceneHeightsSource() const override { return inner_->SceneHeightsSource(); }
  bool HasConsistencyGraph(const View& view) const override { return inner_->HasConsistencyGraph(Inner(view)); }
  ConsistencyGraph ReadConsistencyGraph(const View& view) const override {
    return inner_->ReadConsistencyGraph(Inner(view));
  }

 private:
  const View& Inner(const View& view) const { return inner_->views().at(view.index); }
  std::unique_ptr<DepthBlock> inner_;
  std::vector<View> views_;
  double scene_height_shift_m_;
};

// `input` with its world frame moved by `origin_m`: world = input world + origin_m, for every pose and scene
// height (camera centres move by exactly origin_m, up to the last bit of the doubles); `input` itself when the
// origin is zero.
std::unique_ptr<DepthBlock> WithWorldOrigin(std::unique_ptr<DepthBlock> input, const Eigen::Vector3d& origin_m);

}  // namespace sacfuse
