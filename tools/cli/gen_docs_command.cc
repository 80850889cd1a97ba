// `sacfuse gen-docs configuration|cli|man [--out FILE]`: the generated reference pages, printed or written
// atomically to FILE: docs/configuration.md (config/option_docs.h), docs/cli.md and the man page
// (tools/cli/cli_docs.h). tools/gen_docs.sh regenerates the committed pages; the build writes the man page.
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "config/option_docs.h"
#include "io/atomic_file.h"
#include "tools/cli/cli_docs.h"
#include "tools/cli/cli_support.h"
#include "tools/cli/commands.h"

namespace sacfuse::cli {
namespace {

struct GenDocsArgs {
  std::string what;
  std::string out;  // "" = stdout
};

}  // namespace

void AddGenDocsCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<GenDocsArgs>();
  auto* cmd = app.add_subcommand("gen-docs", "Print a generated reference page: docs/configuration.md (from the "
                                             "option table), docs/cli.md or the man page (from every --help)");
  cmd->add_option("WHAT", args->what, "configuration | cli | man")
      ->required()
      ->check(CLI::IsMember({"configuration", "cli", "man"}));
  cmd->add_option("--out", args->out, "Write it to this file (atomically) instead of stdout");
  const CLI::App* root = &app;
  cmd->callback([args, root, exit_code] {
    SetupLogging("warn");
    *exit_code = RunGuarded([&] {
      const std::string text = args->what == "configuration" ? ConfigurationMarkdown()
                               : args->what == "cli"         ? CliMarkdown(*root)
                                                             : ManPage(*root);
      if (args->out.empty()) {
        std::cout << text;
      } else {
        WriteFileAtomically(args->out, text);
      }
      return kExitOk;
    });
  });
}

}  // namespace sacfuse::cli
