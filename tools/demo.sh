#!/usr/bin/env bash
# One command for a fresh Debian machine: install the build dependencies, build the sacfuse binary (only: the tests
# are built by tools/test.sh, into the same build/), simulate the demo block, fuse it, score it.
# Outputs go to build/demo/: block/ (the simulated COLMAP workspace), out/fused.laz, out/eval.json.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install_deps.sh --build
tools/build.sh --target sacfuse
bin=build/bin/sacfuse
demo=build/demo
if [ ! -f "$demo/block/metadata.json" ]; then
  "$bin" simulate --preset small --seed 7 --out "$demo/block"
fi
"$bin" run tools/demo/demo.yaml
echo
echo "demo: fused cloud at $demo/out/fused.laz; scores in $demo/out/eval.json"
