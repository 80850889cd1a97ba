#include "tools/cli/commands.h"

#include <iostream>

#include <CLI/CLI.hpp>

#include "jobs/version.h"

namespace sacfuse::cli {

int Main(int argc, char** argv) {
  CLI::App app{"sacfuse: Select-and-Combine depth-map fusion for aerial blocks"};
  app.require_subcommand(1);
  auto* version = app.add_subcommand("version", "Print the version");
  version->callback([] { std::cout << VersionString() << "\n"; });
  CLI11_PARSE(app, argc, argv);
  return 0;
}

}  // namespace sacfuse::cli
