#include "tools/cli/cli_support.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <vector>

#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "core/error.h"

namespace sacfuse::cli {

void SetupLogging(const std::string& level, const std::string& log_file) {
  std::vector<spdlog::sink_ptr> sinks;
  auto console = std::make_shared<spdlog::sinks::stderr_color_sink_mt>();
  console->set_pattern("[%H:%M:%S] %^%l%$ %v");
  sinks.push_back(console);
  if (!log_file.empty()) {
    const auto parent = std::filesystem::path(log_file).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    auto file = std::make_shared<spdlog::sinks::basic_file_sink_mt>(log_file, /*truncate=*/false);
    file->set_pattern("[%Y-%m-%d %H:%M:%S.%e] [%l] %v");
    sinks.push_back(file);
  }
  auto logger = std::make_shared<spdlog::logger>("sacfuse", sinks.begin(), sinks.end());
  logger->set_level(spdlog::level::from_str(level));
  logger->flush_on(spdlog::level::info);
  spdlog::set_default_logger(logger);
}

int RunGuarded(const std::function<int()>& body) {
  try {
    return body();
  } catch (const ConfigError& e) {
    spdlog::error("{}", e.what());
    return kExitConfigError;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return kExitFailure;
  }
}

void ProgressPrinter::operator()(const std::string& stage, size_t done, size_t total) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto now = std::chrono::steady_clock::now();
  if (stage != stage_) {
    stage_ = stage;
    stage_start_ = now;
    last_print_ = now - std::chrono::seconds(10);
  }
  const bool finished = done >= total;
  if (!finished && now - last_print_ < std::chrono::seconds(1)) return;
  last_print_ = now;
  const double elapsed = std::chrono::duration<double>(now - stage_start_).count();
  const double fraction = total > 0 ? static_cast<double>(done) / total : 1.0;
  const double eta = fraction > 0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  std::fprintf(stderr, "  %s %zu/%zu (%.0f%%) %.1f s elapsed, ETA %.0f s\n", stage.c_str(), done, total,
               100.0 * fraction, elapsed, eta);
}

}  // namespace sacfuse::cli
