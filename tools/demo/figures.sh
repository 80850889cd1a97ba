#!/usr/bin/env bash
# Remakes the pictures of the docs from a run of the demo block (`sacfuse simulate --preset small --seed 7`, fused
# at the defaults, as tools/demo.sh does):
#   tools/demo/report_screenshot.png         the top of the run report (README.md, docs/report.md)
#   docs/figures/cross_section_before.png    the report's cross-section before fusion (docs/concepts.md)
#   docs/figures/cross_section_after.png     ... and after fusion
#
#   tools/demo/figures.sh WORKDIR
#
# The block and the run go to WORKDIR (simulated once, reused). The report's header names the run's output folder,
# which the screenshot shows: choose a WORKDIR whose path may appear in the docs. The second call reuses the
# block's caches, so its run time is the one of a rerun. Needs chromium (headless; tools/install_deps.sh --test
# installs it); with ImageMagick (Debian: imagemagick) the screenshot is reduced to 256 colours, a third of the
# bytes. SACFUSE: the binary (default build/bin/sacfuse of this checkout).
set -euo pipefail
[ $# -eq 1 ] || { sed -n '2,16p' "$0" >&2; exit 2; }
repo=$(cd "$(dirname "$0")/../.." && pwd)
sacfuse=${SACFUSE:-$repo/build/bin/sacfuse}
[ -x "$sacfuse" ] || { echo "$0: $sacfuse not found: build it or set SACFUSE" >&2; exit 2; }
command -v chromium >/dev/null || { echo "$0: chromium not found (tools/install_deps.sh --test)" >&2; exit 2; }
mkdir -p "$1"
work=$(cd "$1" && pwd)
if [ ! -f "$work/block/metadata.json" ]; then
  "$sacfuse" simulate --preset small --seed 7 --out "$work/block"
fi
"$sacfuse" run "$work/block/sacfuse.yaml"
report=$work/block/out/report
timeout 120 chromium --headless --no-sandbox --disable-gpu --hide-scrollbars \
  --screenshot="$repo/tools/demo/report_screenshot.png" --window-size=944,1240 "file://$report/index.html" \
  > /dev/null 2>&1
if convert -version 2>/dev/null | grep -q '^Version: ImageMagick'; then
  convert "$repo/tools/demo/report_screenshot.png" -colors 256 "PNG8:$repo/tools/demo/report_screenshot.png"
fi
mkdir -p "$repo/docs/figures"
cp "$report/profile_before.png" "$repo/docs/figures/cross_section_before.png"
cp "$report/profile_after.png" "$repo/docs/figures/cross_section_after.png"
echo "written: tools/demo/report_screenshot.png, docs/figures/cross_section_before.png, docs/figures/cross_section_after.png"
