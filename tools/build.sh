#!/usr/bin/env bash
# Configures (Release) and builds into ./build (or $SACFUSE_BUILD_DIR). Usage: tools/build.sh [--target NAME]...
# [extra cmake args]
#   no --target: everything, sacfuse and every test (what tools/test.sh runs);
#   --target sacfuse: only the binary and the libraries it links (what tools/demo.sh runs). The configuration is the
#   same either way (SACFUSE_TESTS stays ON), so a later full build reuses every object the target build made.
# ccache is used when installed (CMAKE_CXX_COMPILER_LAUNCHER; CCACHE_BASEDIR defaults to the repository root so
# clones at other paths share hits); it pays off on rebuilds in new build folders or clones, not on a first build.
set -euo pipefail
cd "$(dirname "$0")/.."
targets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --target) targets+=(--target "${2:?--target needs a target name}"); shift 2 ;;
    --target=*) targets+=(--target "${1#--target=}"); shift ;;
    *) break ;;
  esac
done
launcher=()
if command -v ccache >/dev/null 2>&1; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"
else
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=)   # clears a launcher cached while ccache was installed
fi
jobs=$(nproc 2>/dev/null || echo 2)
build=${SACFUSE_BUILD_DIR:-build}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" "$@" >/dev/null
cmake --build "$build" -j"$jobs" ${targets[@]+"${targets[@]}"}
