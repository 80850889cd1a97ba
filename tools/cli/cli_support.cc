#include "tools/cli/cli_support.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <vector>

#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "core/error.h"

namespace sacfuse::cli {
namespace {

std::string g_console_level;  // SetConsoleLevel; "" = each command's own

// The progress line on a terminal: whether one is drawn and not yet ended (a log message must clear it first).
std::mutex g_console_mutex;
bool g_progress_line_open = false;

bool StderrIsTerminal() {
  static const bool tty = isatty(fileno(stderr)) != 0;
  return tty;
}

// Erases the open progress line so that what follows starts at column 0. The caller holds g_console_mutex.
void ClearProgressLineLocked() {
  if (!g_progress_line_open) return;
  std::fputs("\r\033[K", stderr);
  g_progress_line_open = false;
}

// The console sink: a log message first erases an open progress line (it is redrawn at the next update).
class ConsoleSink : public spdlog::sinks::stderr_color_sink_mt {
 public:
  void log(const spdlog::details::log_msg& msg) override {
    std::lock_guard<std::mutex> lock(g_console_mutex);
    ClearProgressLineLocked();
    spdlog::sinks::stderr_color_sink_mt::log(msg);
  }
};

spdlog::level::level_enum ConsoleLevel(const std::string& command_level) {
  return spdlog::level::from_str(g_console_level.empty() ? command_level : g_console_level);
}

}  // namespace

const std::vector<std::string>& LogLevelNames() {
  static const std::vector<std::string> names = {"trace", "debug", "info", "warn", "error", "critical", "off"};
  return names;
}

void SetConsoleLevel(const std::string& level) { g_console_level = level; }

void SetupLogging(const std::string& level, const std::string& log_file) {
  std::vector<spdlog::sink_ptr> sinks;
  auto console = std::make_shared<ConsoleSink>();
  console->set_pattern("[%H:%M:%S] %^%l%$ %v");
  console->set_level(ConsoleLevel(level));
  sinks.push_back(console);
  spdlog::level::level_enum logger_level = console->level();
  if (!log_file.empty()) {
    const auto parent = std::filesystem::path(log_file).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    auto file = std::make_shared<spdlog::sinks::basic_file_sink_mt>(log_file, /*truncate=*/false);
    file->set_pattern("[%Y-%m-%d %H:%M:%S.%e] [%l] %v");
    file->set_level(spdlog::level::from_str(level));
    logger_level = std::min(logger_level, file->level());
    sinks.push_back(file);
  }
  auto logger = std::make_shared<spdlog::logger>("sacfuse", sinks.begin(), sinks.end());
  logger->set_level(logger_level);
  logger->flush_on(spdlog::level::info);
  spdlog::set_default_logger(logger);
}

std::string WrapText(const std::string& text, size_t width) {
  std::string out, line, word;
  const auto end_word = [&] {
    if (word.empty()) return;
    if (!line.empty() && line.size() + 1 + word.size() > width) {
      out += line + "\n";
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
    word.clear();
  };
  for (size_t i = 0; i <= text.size(); ++i) {
    const char c = i < text.size() ? text[i] : '\n';
    if (c != ' ' && c != '\n') {
      word += c;
      continue;
    }
    end_word();
    if (c == '\n' && (i + 1 >= text.size() || text[i + 1] == '\n')) {  // a paragraph ends (or the text)
      if (!line.empty()) out += line + "\n";
      line.clear();
      if (i + 1 < text.size()) out += "\n";
      ++i;
    }
  }
  while (!out.empty() && out.back() == '\n') out.pop_back();
  return out;
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
  if (ConsoleLevel("info") > spdlog::level::info) return;
  std::lock_guard<std::mutex> lock(mutex_);
  const auto now = std::chrono::steady_clock::now();
  if (stage != stage_) {
    stage_ = stage;
    stage_start_ = now;
    last_print_ = now - std::chrono::seconds(10);
  }
  const bool finished = done >= total;
  const bool terminal = StderrIsTerminal();
  const auto interval = terminal ? std::chrono::milliseconds(250) : std::chrono::milliseconds(1000);
  if (!finished && now - last_print_ < interval) return;
  last_print_ = now;
  const double elapsed = std::chrono::duration<double>(now - stage_start_).count();
  const double fraction = total > 0 ? static_cast<double>(done) / total : 1.0;
  const double eta = fraction > 0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  char line[512];
  std::snprintf(line, sizeof(line), "  %s %zu/%zu (%.0f%%) %.1f s elapsed, ETA %.0f s", stage.c_str(), done, total,
                100.0 * fraction, elapsed, eta);
  std::lock_guard<std::mutex> console(g_console_mutex);
  if (terminal) {
    std::fprintf(stderr, "\r%s\033[K%s", line, finished ? "\n" : "");
    g_progress_line_open = !finished;
  } else {
    std::fprintf(stderr, "%s\n", line);
  }
  std::fflush(stderr);
}

}  // namespace sacfuse::cli
