#include "tools/bench/colmap_fusion.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <fstream>

#include <spdlog/spdlog.h>

#include "core/error.h"
#include "tools/bench/ply_to_las.h"

namespace sacfuse {
namespace {

namespace fs = std::filesystem;

std::string Number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%g", v);
  return buf;
}

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The last `n` lines of a text file, indented, for error messages.
std::string LogTail(const std::string& path, size_t n) {
  std::ifstream in(path);
  std::deque<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    lines.push_back(line);
    if (lines.size() > n) lines.pop_front();
  }
  std::string tail;
  for (const std::string& line : lines) tail += "\n  | " + line;
  return tail;
}

// "COLMAP 3.8 (Commit Unknown on Unknown without CUDA)" from the first lines of `colmap -h` ("COLMAP 3.8 --
// Structure-from-Motion and Multi-View Stereo", then the build in parentheses).
std::string ColmapVersion(const std::string& colmap, const fs::path& out_dir) {
  const fs::path help = out_dir / ".colmap_help.txt";
  fs::remove(help);
  try {
    RunChildProcess({colmap, "-h"}, help.string());
  } catch (const Error&) {
    return "unknown";
  }
  std::ifstream in(help);
  std::vector<std::string> lines;
  for (std::string line; lines.size() < 2 && std::getline(in, line);) {
    const size_t begin = line.find_first_not_of(" \t\r");
    if (begin == std::string::npos) continue;
    const size_t end = line.find_last_not_of(" \t\r");
    lines.push_back(line.substr(begin, end - begin + 1));
  }
  in.close();
  fs::remove(help);
  if (lines.empty()) return "unknown";
  std::string version = lines[0].substr(0, lines[0].find(" -- "));
  if (lines.size() > 1 && lines[1].front() == '(') version += " " + lines[1];
  return version;
}

}  // namespace

std::string RequireColmapBinary(const std::string& colmap) {
  const std::string path = FindExecutable(colmap);
  if (path.empty()) {
    throw ConfigError("COLMAP not found: \"" + colmap + "\" is " +
                      (colmap.find('/') == std::string::npos ? "not on PATH" : "not an executable file") +
                      ". Install it (Debian: apt-get install colmap; tools/install_deps.sh installs it when the "
                      "package is available) or pass --colmap PATH");
  }
  return path;
}

std::pair<std::string, std::string> ParseStereoFusionOption(const std::string& text) {
  const size_t eq = text.find('=');
  const std::string name = eq == std::string::npos ? "" : text.substr(0, eq);
  const std::string value = eq == std::string::npos ? "" : text.substr(eq + 1);
  const bool plain = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  });
  if (!plain || value.empty()) {
    throw ConfigError("StereoFusion option \"" + text + "\": expected NAME=VALUE with NAME an option of `colmap "
                      "stereo_fusion -h` without its \"StereoFusion.\" prefix, e.g. max_normal_error=180");
  }
  return {name, value};
}

std::vector<std::string> StereoFusionCommand(const ColmapFusionRequest& request, const std::string& colmap_path,
                                             const std::string& workspace, const std::string& ply_path) {
  std::vector<std::pair<std::string, std::string>> options = {
      {"num_threads", std::to_string(request.threads > 0 ? request.threads : -1)},
      {"cache_size", Number(request.memory_gb)},
      {"use_cache", request.use_cache ? "1" : "0"}};
  for (const auto& [name, value] : request.stereo_fusion_options) {
    auto same = std::find_if(options.begin(), options.end(), [&](const auto& o) { return o.first == name; });
    if (same != options.end()) {
      same->second = value;
    } else {
      options.emplace_back(name, value);
    }
  }
  std::vector<std::string> argv = {colmap_path,       "stereo_fusion",   "--workspace_path", workspace,
                                   "--workspace_format", "COLMAP",       "--input_type",     request.input_type,
                                   "--output_path",    ply_path};
  for (const auto& [name, value] : options) {
    argv.push_back("--StereoFusion." + name);
    argv.push_back(value);
  }
  argv.push_back("--log_to_stderr");  // glog messages into our log instead of files in /tmp
  argv.push_back("1");
  return argv;
}

ColmapFusionResult RunColmapFusion(const ColmapFusionRequest& request) {
  ColmapFusionResult result;
  result.colmap_path = RequireColmapBinary(request.colmap);
  if (request.input_type != "geometric" && request.input_type != "photometric") {
    throw ConfigError("input type must be geometric or photometric, not \"" + request.input_type + "\"");
  }
  const fs::path out = fs::absolute(request.out_dir).lexically_normal();
  fs::create_directories(out);
  result.colmap_version = ColmapVersion(result.colmap_path, out);

  auto start = std::chrono::steady_clock::now();
  result.workspace = PrepareShiftedWorkspace(request.workspace, (out / "workspace").string());
  result.prepare_s = SecondsSince(start);
  spdlog::info("shifted workspace {} ({} images, {} sparse points): world = local + ({:.0f}, {:.0f}, {:.0f})",
               result.workspace.path, result.workspace.images, result.workspace.points3D,
               result.workspace.offset.x(), result.workspace.offset.y(), result.workspace.offset.z());

  result.ply_path = (fs::path(result.workspace.path) / "fused.ply").string();
  result.log_path = (out / "colmap.log").string();
  result.las_path = (out / "fused.las").string();
  fs::remove(result.ply_path);
  fs::remove(result.ply_path + ".vis");
  result.command = StereoFusionCommand(request, result.colmap_path, result.workspace.path, result.ply_path);
  std::string command_line;
  for (const std::string& a : result.command) command_line += (command_line.empty() ? "" : " ") + a;
  {
    std::ofstream log(result.log_path, std::ios::trunc);
    log << "# sacfuse colmap-fusion: " << result.colmap_version << "\n# " << command_line << "\n";
    if (!log) throw InputError(result.log_path, "cannot write the log file");
  }
  spdlog::info("running {} (output: {})", command_line, result.log_path);
  result.run = RunChildProcess(result.command, result.log_path);
  spdlog::info("COLMAP stereo_fusion: exit code {}, {:.1f} s wall, {:.0f} MiB peak RSS (this process had {:.0f} MiB "
               "at fork), {:.1f} s CPU",
               result.run.exit_code, result.run.wall_s, result.run.peak_rss_mib, result.run.parent_rss_at_fork_mib,
               result.run.user_s + result.run.system_s);
  if (result.run.exit_code != 0) {
    throw Error("COLMAP stereo_fusion failed with exit code " + std::to_string(result.run.exit_code) +
                (result.run.term_signal ? " (signal " + std::to_string(result.run.term_signal) + ")" : "") +
                "; the end of " + result.log_path + ":" + LogTail(result.log_path, 15));
  }
  if (!fs::exists(result.ply_path)) {
    throw Error("COLMAP stereo_fusion exited 0 but wrote no " + result.ply_path + "; the end of " +
                result.log_path + ":" + LogTail(result.log_path, 15));
  }

  start = std::chrono::steady_clock::now();
  LasWriterOptions las = request.las;
  las.system_identifier = "sacfuse colmap-fusion";
  las.generating_software = "COLMAP stereo_fusion";
  result.points =
      ConvertPlyToLas(result.ply_path, result.las_path, result.workspace.offset + request.origin_m, las);
  result.convert_s = SecondsSince(start);
  spdlog::info("wrote {} points to {} in {:.1f} s", result.points, result.las_path, result.convert_s);
  return result;
}

}  // namespace sacfuse
