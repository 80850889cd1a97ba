#pragma once

namespace sacfuse::cli {
int Main(int argc, char** argv);
}  // namespace sacfuse::cli
