#pragma once
// docs/cli.md and the man page sacfuse.1, generated from the --help text of the program and of every command
// (exactly what `sacfuse --help` and `sacfuse <command> --help` print), so the reference cannot drift from the
// binary. `sacfuse gen-docs cli|man` prints them; the build writes the man page (tools/cli/CMakeLists.txt) and
// tests/generated_docs_test.cc fails when the committed cli.md differs.
#include <string>

namespace CLI {
class App;
}

namespace sacfuse::cli {

std::string CliMarkdown(const CLI::App& app);
// roff for man(1): NAME, SYNOPSIS, DESCRIPTION (the program's help), COMMANDS (each command's help), SEE ALSO.
std::string ManPage(const CLI::App& app);

}  // namespace sacfuse::cli
