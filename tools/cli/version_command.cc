#include <iostream>

#include <CLI/CLI.hpp>

#include "config/version.h"
#include "tools/cli/commands.h"

namespace sacfuse::cli {

void AddVersionCommand(CLI::App& app, int* exit_code) {
  auto* cmd = app.add_subcommand("version", "Print the sacfuse version (as sacfuse --version)");
  cmd->callback([exit_code] {
    std::cout << FullVersionString() << "\n";
    *exit_code = 0;
  });
}

}  // namespace sacfuse::cli
