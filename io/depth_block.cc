#include "io/depth_block.h"

#include "core/error.h"

namespace sacfuse {

ConsistencyGraph DepthBlock::ReadConsistencyGraph(const View& view) const {
  throw InputError(source(), "this input has no dense-matching consistency graphs (view \"" + view.name + "\")");
}

}  // namespace sacfuse
