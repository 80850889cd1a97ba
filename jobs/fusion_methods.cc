#include "jobs/fusion_methods.h"

#include "core/consistency_fusion.h"
#include "core/disparity_normal_fusion.h"
#include "core/error.h"
#include "core/multiray_fusion.h"
#include "core/tsdf_fusion.h"
#include "core/union_fusion.h"

namespace sacfuse {

bool MethodUsesSuperpixels(const std::string& method) { return method == "sac"; }

MethodStats RunFusionMethod(const FusionOptions& fusion, const std::vector<SacView>& views, const ViewPlan& plan,
                            double gsd_m, PointSink& sink, const FootprintBox* region_xy) {
  const std::string& m = fusion.method;
  if (m == "union") return RunUnionFusion(views, sink);
  if (m == "consistency") return RunConsistencyFusion(views, fusion.consistency, sink, &plan);
  if (m == "disparity_normal") return RunDisparityNormalFusion(views, fusion.disparity_normal, sink, &plan);
  if (m == "multiray") return RunMultirayFusion(views, fusion.multiray, sink, &plan);
  if (m == "tsdf") return RunTsdfFusion(views, fusion.tsdf, sink, gsd_m, region_xy);
  throw ConfigError("fusion.method = " + m + ": not a comparison method (sac runs through jobs/sac_block.h)");
}

}  // namespace sacfuse
