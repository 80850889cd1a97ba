#!/usr/bin/env bash
# Builds sacfuse and runs the whole test suite (unit, end-to-end, fault injection) with CTest.
# Tests that need ../shared research data skip with a message when it is absent (override: SACFUSE_SHARED=DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/build.sh
jobs=$(nproc 2>/dev/null || echo 2)
ctest --test-dir build --output-on-failure -j"$jobs" --timeout 900
