#include "io/input_warnings.h"

#include <mutex>
#include <set>

#include <spdlog/spdlog.h>

namespace sacfuse {

void WarnAboutInput(const std::string& file, const std::string& message) {
  static std::mutex mutex;
  static std::set<std::string> said;
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (!said.insert(file + '\n' + message).second) return;
  }
  spdlog::warn("{}: {}", file, message);
}

}  // namespace sacfuse
