// `sacfuse validate FILE.las...`: checks LAS files against the rules lasvalidate checks (io/las_validate.h) and
// prints each file's findings, or "ok" with its version, format, point count and CRS. Exit 1 when any file has a
// finding. --json prints the same as one JSON object (the schema in the command's help).
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "config/version.h"
#include "io/copc_validate.h"
#include "io/las_crs.h"
#include "io/las_reader.h"
#include "io/las_validate.h"
#include "tools/cli/cli_support.h"
#include "tools/cli/commands.h"

namespace sacfuse::cli {
namespace {

// One file's result: its findings and what its header says (or why the reader refuses it).
struct FileCheck {
  std::string path;
  std::vector<std::string> findings;
  bool readable = false;
  std::string error;  // not readable: why
  std::string las_version;
  int point_format = -1;
  uint64_t point_count = 0;
  std::string crs;  // the CRS description, or "unreadable: ..."
  std::string copc;  // a COPC file's octree summary; empty for plain LAS/LAZ

  // "LAS 1.4, point format 7, 1234 points, CRS EPSG:25832 (...)", or why the reader refuses the file.
  std::string Summary() const {
    if (!readable) return "not readable by sacfuse: " + error;
    return "LAS " + las_version + ", point format " + std::to_string(point_format) + ", " +
           std::to_string(point_count) + " points, CRS " + crs + (copc.empty() ? "" : ", " + copc);
  }
};

FileCheck CheckFile(const std::string& path) {
  FileCheck f;
  f.path = path;
  f.findings = ValidateLasFile(path);
  try {
    LasReader reader(path);
    const LasHeader& h = reader.header();
    f.readable = true;
    f.las_version = std::to_string(h.version_major) + "." + std::to_string(h.version_minor);
    f.point_format = h.point_format;
    f.point_count = h.point_count;
    try {
      f.crs = ReadLasCrs(h).description;
    } catch (const std::exception& e) {
      f.crs = std::string("unreadable: ") + e.what();
    }
    f.copc = DescribeCopc(path);
  } catch (const std::exception& e) {
    f.error = e.what();
  }
  return f;
}

nlohmann::json FileJson(const FileCheck& f) {
  nlohmann::json j = {{"path", f.path}, {"ok", f.findings.empty()}, {"findings", f.findings},
                      {"readable", f.readable}};
  if (f.readable) {
    j["las_version"] = f.las_version;
    j["point_format"] = f.point_format;
    j["point_count"] = f.point_count;
    j["crs"] = f.crs;
    if (!f.copc.empty()) j["copc"] = f.copc;
  } else {
    j["error"] = f.error;
  }
  return j;
}

int ValidateCommand(const std::vector<std::string>& paths, bool json) {
  std::vector<FileCheck> checks;
  size_t bad_files = 0;
  for (const std::string& path : paths) {
    checks.push_back(CheckFile(path));
    bad_files += !checks.back().findings.empty();
  }
  if (json) {
    nlohmann::json files = nlohmann::json::array();
    for (const FileCheck& f : checks) files.push_back(FileJson(f));
    const nlohmann::json j = {{"version", FullVersionString()},
                              {"files", files},
                              {"passed", paths.size() - bad_files},
                              {"total", paths.size()}};
    // Paths are bytes: replace what is not UTF-8 rather than fail.
    std::cout << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
    return bad_files == 0 ? kExitOk : kExitFailure;
  }
  for (const FileCheck& f : checks) {
    if (f.findings.empty()) {
      std::cout << f.path << ": ok (" << f.Summary() << ")\n";
      continue;
    }
    std::cout << f.path << ": " << f.findings.size() << (f.findings.size() == 1 ? " finding" : " findings") << " ("
              << f.Summary() << ")\n";
    for (const std::string& finding : f.findings) std::cout << "  " << finding << "\n";
  }
  if (paths.size() > 1) {
    std::cout << paths.size() - bad_files << " of " << paths.size() << " files passed\n";
  }
  return bad_files == 0 ? kExitOk : kExitFailure;
}

}  // namespace

void AddValidateCommand(CLI::App& app, int* exit_code) {
  auto paths = std::make_shared<std::vector<std::string>>();
  auto json = std::make_shared<bool>(false);
  auto* cmd = app.add_subcommand(
      "validate",
      "Check LAS files as lasvalidate does (header size, offsets, record length, counts, points by return, bounds, "
      "return numbers, global encoding, scale/offset, CRS records), and COPC files' octree (hierarchy pages, every "
      "node's chunk within the file, counts, points inside their nodes); exit 1 when any file has a finding");
  cmd->add_option("FILE", *paths, "LAS files")->required();
  cmd->add_flag("--json", *json, "Print one JSON object (the schema below) instead of text");
  cmd->footer(
      "--json prints an object with version (this sacfuse), files: a list of {path, ok (no finding), findings (a "
      "list of texts), readable (by sacfuse's reader), and when readable las_version (\"1.4\"), point_format, "
      "point_count, crs (its description), else error}, passed and total (numbers of files).");
  cmd->callback([paths, json, exit_code] {
    SetupLogging(*json ? "warn" : "info");
    *exit_code = RunGuarded([&] { return ValidateCommand(*paths, *json); });
  });
}

}  // namespace sacfuse::cli
