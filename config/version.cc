#include "config/version.h"

#include "sacfuse_build_version.h"  // generated: SACFUSE_RELEASE_VERSION, SACFUSE_GIT_DESCRIBE

namespace sacfuse {

std::string ReleaseVersion() { return SACFUSE_RELEASE_VERSION; }

std::string GitDescription() { return SACFUSE_GIT_DESCRIBE; }

std::string VersionString() { return "sacfuse " + ReleaseVersion(); }

std::string FullVersionString() {
  const std::string git = GitDescription();
  return git.empty() ? VersionString() : VersionString() + " (git " + git + ")";
}

}  // namespace sacfuse
