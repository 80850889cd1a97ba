#pragma once
// `fusion.method: union` over views held in memory (a tile's windows): every valid depth pixel becomes a point
// (no fusion; the "before fusion" baseline), views in input order, rows in order. The untiled job streams one
// view at a time with BackprojectDepthMap (core/backproject.h) instead; both give the same points.
#include <vector>

#include "core/method_stats.h"
#include "core/point.h"
#include "core/sac_view.h"

namespace sacfuse {

MethodStats RunUnionFusion(const std::vector<SacView>& views, PointSink& sink);

}  // namespace sacfuse
