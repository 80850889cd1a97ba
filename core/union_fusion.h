#pragma once
// `fusion.method: union` over views held in memory (the whole block or a tile's windows): every valid depth pixel
// becomes a point (no fusion; the "before fusion" baseline), views in input order, rows in order.
#include <vector>

#include "core/fusion_stats.h"
#include "core/point.h"
#include "core/sac_view.h"

namespace sacfuse {

FusionStats RunUnionFusion(const std::vector<SacView>& views, PointSink& sink);

}  // namespace sacfuse
