#include "config/version.h"

namespace sacfuse {
std::string VersionString() { return "sacfuse 0.1.0"; }
}  // namespace sacfuse
