#include "io/crs_wkt.h"

#include "core/error.h"
#include "io/crs.h"
#include "io/crs_impl.h"

namespace sacfuse {

std::string ProjectCrsWkt(const std::string& crs_text, CrsWktDialect dialect) {
  Crs crs;
  try {
    crs = ParseProjectCrs(crs_text);
  } catch (const ConfigError&) {
    throw;
  } catch (const Error& e) {
    throw ConfigError(e.what());
  }
  return dialect == CrsWktDialect::kLas14 ? crs.impl().wkt1_las : crs.impl().wkt2;
}

}  // namespace sacfuse
