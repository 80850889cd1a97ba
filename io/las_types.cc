#include "io/las_types.h"

#include "io/las_format.h"

namespace sacfuse {

std::string LasHeader::Wkt() const {
  for (const LasVlr& vlr : vlrs) {
    if (vlr.user_id != las_format::kProjectionUserId || vlr.record_id != las_format::kWktRecordId) continue;
    std::string wkt(vlr.data.begin(), vlr.data.end());
    while (!wkt.empty() && wkt.back() == '\0') wkt.pop_back();
    return wkt;
  }
  return "";
}

}  // namespace sacfuse
