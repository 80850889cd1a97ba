// `sacfuse validate FILE.las...`: checks LAS files against the rules lasvalidate checks (io/las_validate.h) and
// prints each file's findings, or "ok" with its version, format, point count and CRS. Exit 1 when any file has a
// finding.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "io/las_crs.h"
#include "io/las_reader.h"
#include "io/las_validate.h"
#include "tools/cli/cli_support.h"
#include "tools/cli/commands.h"

namespace sacfuse::cli {
namespace {

// "LAS 1.4, point format 7, 1234 points, CRS EPSG:25832 (...)", or why the reader refuses the file.
std::string Summary(const std::string& path) {
  try {
    LasReader reader(path);
    const LasHeader& h = reader.header();
    std::string crs;
    try {
      crs = ReadLasCrs(h).description;
    } catch (const std::exception& e) {
      crs = std::string("unreadable: ") + e.what();
    }
    return "LAS " + std::to_string(h.version_major) + "." + std::to_string(h.version_minor) + ", point format " +
           std::to_string(h.point_format) + ", " + std::to_string(h.point_count) + " points, CRS " + crs;
  } catch (const std::exception& e) {
    return std::string("not readable by sacfuse: ") + e.what();
  }
}

int ValidateCommand(const std::vector<std::string>& paths) {
  size_t bad_files = 0;
  for (const std::string& path : paths) {
    const std::vector<std::string> findings = ValidateLasFile(path);
    if (findings.empty()) {
      std::cout << path << ": ok (" << Summary(path) << ")\n";
      continue;
    }
    ++bad_files;
    std::cout << path << ": " << findings.size() << (findings.size() == 1 ? " finding" : " findings") << " ("
              << Summary(path) << ")\n";
    for (const std::string& f : findings) std::cout << "  " << f << "\n";
  }
  if (paths.size() > 1) {
    std::cout << paths.size() - bad_files << " of " << paths.size() << " files passed\n";
  }
  return bad_files == 0 ? kExitOk : kExitFailure;
}

}  // namespace

void AddValidateCommand(CLI::App& app, int* exit_code) {
  auto paths = std::make_shared<std::vector<std::string>>();
  auto* cmd = app.add_subcommand(
      "validate",
      "Check LAS files as lasvalidate does (header size, offsets, record length, counts, points by return, bounds, "
      "return numbers, global encoding, scale/offset, CRS records); exit 1 when any file has a finding");
  cmd->add_option("FILE", *paths, "LAS files")->required();
  cmd->callback([paths, exit_code] {
    SetupLogging("info");
    *exit_code = RunGuarded([&] { return ValidateCommand(*paths); });
  });
}

}  // namespace sacfuse::cli
