#include "io/depth_block.h"

#include <algorithm>

#include "core/backproject.h"
#include "core/error.h"
#include "io/input_warnings.h"

namespace sacfuse {

ConsistencyGraph DepthBlock::ReadConsistencyGraph(const View& view) const {
  throw InputError(source(), "this input has no dense-matching consistency graphs (view \"" + view.name + "\")");
}

DepthMap DepthBlock::ReadDepthRows(const View& view, const std::vector<int>& rows) const {
  const DepthMap full = ReadDepthMap(view);
  DepthMap out = DepthMap::Uninitialized(full.width, static_cast<int>(rows.size()), full.channels);
  const size_t row_values = static_cast<size_t>(full.width) * full.channels;
  for (size_t i = 0; i < rows.size(); ++i) {
    if (rows[i] < 0 || rows[i] >= full.height) {
      throw Error(DepthMapPath(view) + ": row " + std::to_string(rows[i]) + " is outside the depth map's " +
                  std::to_string(full.height) + " rows");
    }
    std::copy_n(full.data.data() + static_cast<size_t>(rows[i]) * row_values, row_values,
                out.data.data() + i * row_values);
  }
  return out;
}

std::vector<double> SampleDepthMapHeights(const DepthBlock& input) {
  constexpr int kRows = 16, kColumns = 64;
  std::vector<double> z;
  for (const View& view : input.views()) {
    const DepthRasterSize size = input.DepthSize(view);
    const PinholeCamera depth_camera = view.camera.Scaled(size.width, size.height);
    const Rigid3d world_from_cam = view.cam_from_world.Inverse();
    const int rows = std::min(kRows, size.height), cols = std::min(kColumns, size.width);
    for (int k = 0; k < rows; ++k) {
      const int row = static_cast<int>((k + 0.5) * size.height / rows);
      const DepthMap line = input.ReadDepthWindow(view, PixelWindow{row, row + 1, 0, size.width});
      for (int j = 0; j < cols; ++j) {
        const int col = static_cast<int>((j + 0.5) * size.width / cols);
        const float d = line.at(0, col);
        if (IsValidDepth(d)) z.push_back(DepthPixelToWorld(depth_camera, world_from_cam, col, row, d).z());
      }
    }
  }
  return z;
}

DepthMap WarnIfNoValidDepth(DepthMap depth, const View& view, const std::string& path) {
  if (std::none_of(depth.data.begin(), depth.data.end(), [](float d) { return IsValidDepth(d); })) {
    WarnAboutInput(path, "depth map of view " + std::to_string(view.index) + " (\"" + view.name +
                             "\") has no valid depth pixel (all 0, negative or not finite); the view adds no points");
  }
  return depth;
}

}  // namespace sacfuse
