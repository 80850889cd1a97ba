#pragma once
#include <string>

namespace sacfuse {
// "sacfuse 0.1.0"; written into LAS headers, run reports and logs.
std::string VersionString();
}  // namespace sacfuse
