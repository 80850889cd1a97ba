// sacfuse: the command-line entry point. Each subcommand is registered by its own file (see commands.h).
#include <iostream>

#include <CLI/CLI.hpp>

#include "tools/cli/commands.h"

int main(int argc, char** argv) { return sacfuse::cli::Main(argc, argv); }
