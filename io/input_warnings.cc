#include "io/input_warnings.h"

#include <mutex>
#include <set>

#include <spdlog/spdlog.h>

namespace sacfuse {

namespace {

struct Given {
  std::mutex mutex;
  std::set<std::string> said;  // file + '\n' + message
  std::vector<std::string> in_order;
};

Given& TheWarnings() {
  static Given given;
  return given;
}

}  // namespace

void WarnAboutInput(const std::string& file, const std::string& message) {
  Given& g = TheWarnings();
  {
    std::lock_guard<std::mutex> lock(g.mutex);
    if (!g.said.insert(file + '\n' + message).second) return;
    g.in_order.push_back(file + ": " + message);
  }
  spdlog::warn("{}: {}", file, message);
}

std::vector<std::string> InputWarningsGiven() {
  Given& g = TheWarnings();
  std::lock_guard<std::mutex> lock(g.mutex);
  return g.in_order;
}

}  // namespace sacfuse
