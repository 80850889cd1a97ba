#include "io/test_pause.h"

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

namespace sacfuse {

void PauseAtTestPoint(const char* point) {
  const char* spec = std::getenv("SACFUSE_TEST_PAUSE");
  if (spec == nullptr) return;
  const std::string all = std::string(spec) + ",";
  const std::string prefix = std::string(point) + "=";
  for (size_t begin = 0, end; (end = all.find(',', begin)) != std::string::npos; begin = end + 1) {
    const std::string item = all.substr(begin, end - begin);
    if (item.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string file = item.substr(prefix.size());
    { std::ofstream(file + ".tmp") << ::getpid() << "\n"; }
    std::filesystem::rename(file + ".tmp", file);  // appears whole
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (std::filesystem::exists(file) && std::chrono::steady_clock::now() < give_up) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return;
  }
}

}  // namespace sacfuse
