#!/usr/bin/env bash
# Installs what the tests need if missing (tools/install_deps.sh --test: Chromium, Node.js/npm, GNU parallel, the
# npm LAS reader; only checks when all are present), builds sacfuse and every test, and runs the whole suite (unit,
# end-to-end, fault injection) with CTest. After tools/demo.sh it reuses the demo's build (same build/, same flags).
# Tests that need ../shared research data skip with a message when it is absent (override: SACFUSE_SHARED=DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install_deps.sh --test
tools/build.sh
jobs=$(nproc 2>/dev/null || echo 2)
ctest --test-dir build --output-on-failure -j"$jobs" --timeout 900
