#include "io/depth_block.h"

#include <algorithm>

#include "core/error.h"
#include "io/input_warnings.h"

namespace sacfuse {

ConsistencyGraph DepthBlock::ReadConsistencyGraph(const View& view) const {
  throw InputError(source(), "this input has no dense-matching consistency graphs (view \"" + view.name + "\")");
}

DepthMap WarnIfNoValidDepth(DepthMap depth, const View& view, const std::string& path) {
  if (std::none_of(depth.data.begin(), depth.data.end(), [](float d) { return IsValidDepth(d); })) {
    WarnAboutInput(path, "depth map of view " + std::to_string(view.index) + " (\"" + view.name +
                             "\") has no valid depth pixel (all 0, negative or not finite); the view adds no points");
  }
  return depth;
}

}  // namespace sacfuse
