#!/usr/bin/env bash
# COPC output at scale (docs/copc.md, "Measured"): the `dortmund` preset (16 nadir + 43 oblique views, 1 km2)
# simulated at one pixel scale, fused with output.format copc untiled (the COPC built when the fusion is done) and
# in tiles of TILE_M metres (default 250; tiles
# written as COPC, DIR/fused.copc.laz built from them, DIR/tiles.vpc), then `sacfuse merge` alone into a fresh
# fused.copc.laz under each memory budget
# (resources.memory_gb: the smaller the budget, the more octree buckets the build sorts the points into), and once
# with output.format laz for comparison. Each command is timed with /usr/bin/time (wall, user + system CPU, peak
# RSS) and each COPC checked with `sacfuse validate`. Last, a COPC merge killed with SIGKILL half-way and run again
# must give the bytes of the uninterrupted merge with the same budget (all but the header's creation date).
#
#   tools/bench/copc_bench.sh WORKDIR [SCALE] [MEMORY_GB ...]     (defaults: 0.25; 4 1 0.5)
#   PRESET=tiny TILE_M=20 tools/bench/copc_bench.sh WORKDIR 1 1 0.05   (a check of the script in a minute or two)
#
# The block (PRESET, default dortmund) is simulated once into WORKDIR/<preset>_<scale> (as
# tools/bench/dortmund_scaling.sh names the dortmund blocks, so the two share them) and reused; the run goes to
# WORKDIR/<preset>_<scale>/copc_run (removed first). Prints a Markdown table. Needs /usr/bin/time and python3 with
# PyYAML (tools/install_deps.sh).
set -euo pipefail
if [[ $# -lt 1 ]]; then
  sed -n '2,16p' "$0"
  exit 2
fi
work=$(realpath -m "$1")
scale=${2:-0.25}
shift $(( $# >= 2 ? 2 : 1 ))
budgets=("$@")
[[ ${#budgets[@]} -gt 0 ]] || budgets=(4 1 0.5)
tile_m=${TILE_M:-250}
preset=${PRESET:-dortmund}
here=$(cd "$(dirname "$0")/../.." && pwd)
sacfuse=${SACFUSE:-$here/build/bin/sacfuse}
block="$work/${preset}_$scale"
run="$block/copc_run"
mkdir -p "$work"
if [[ ! -f "$block/sacfuse.yaml" ]]; then
  echo "== simulating $preset at pixel scale $scale into $block" >&2
  "$sacfuse" simulate --preset "$preset" --seed 1 --pixel-scale "$scale" --no-normal-maps --out "$block" >&2
fi

# config FILE OUT SECTION.KEY=VALUE...: the block's config into FILE with output.dir OUT and the options given.
config() {
  local file=$1 out=$2
  shift 2
  "$here/tools/bench/config_with_output.sh" "$block/sacfuse.yaml" "$out" evaluation.reference='""' "$@" > "$file"
}
# timed NAME COMMAND...: runs it under /usr/bin/time; prints "wall user+sys peak_MiB".
timed() {
  local name=$1
  shift
  /usr/bin/time -f "%e %U %S %M" -o "$run/$name.time" "$@" > "$run/$name.log" 2>&1 ||
    { tail -n 20 "$run/$name.log" >&2; echo "$0: $name failed" >&2; exit 1; }
  awk '{printf "%.1f %.1f %.0f\n", $1, $2 + $3, $4 / 1024}' "$run/$name.time"
}
row() {  # row WHAT MEMORY_GB "wall cpu rss" POINTS NOTE
  local t=($3)
  printf '| %s | %s | %s | %s | %s | %s | %s |\n' "$1" "$2" "${t[0]}" "${t[1]}" "${t[2]}" "$4" "$5"
}
points() {  # points FILE: the header's count
  python3 -c "import struct,sys; f=open(sys.argv[1],'rb'); f.seek(247); print(struct.unpack('<Q', f.read(8))[0])" "$1"
}
built() {  # built LOG: the fused COPC's build time, nodes, levels and buckets from its log lines
  local n
  n=$(grep -o "sorted into [0-9]* octree buckets" "$1" | tail -n 1 | awk '{print $3}')
  grep "fused.copc.laz: COPC of" "$1" | tail -n 1 |
    sed -E 's/.* built in ([0-9.]+) s: ([0-9]+) nodes in ([0-9]+) levels.*/octree built in \1 s, \2 nodes, \3 levels/' |
    tr -d '\n'
  echo ", ${n:-1} bucket(s)"
}
validate() {
  "$sacfuse" validate "$1" | head -n 1 | grep -q ": ok (" || { "$sacfuse" validate "$1" >&2; echo "$0: $1 invalid" >&2; exit 1; }
}
digest() {  # the file's SHA-256 with the header's creation day and year (bytes 90-93) zeroed
  python3 - "$1" <<'PY'
import hashlib, sys
data = bytearray(open(sys.argv[1], "rb").read())
data[90:94] = b"\0\0\0\0"
print(hashlib.sha256(data).hexdigest())
PY
}

rm -rf "$run"
mkdir -p "$run"
rows=()
config "$run/untiled.yaml" "$run/untiled" output.format=copc tiling.tile_size_m=0
echo "== fusing $block with output.format copc, untiled" >&2
t=$(timed untiled "$sacfuse" run "$run/untiled.yaml")
rows+=("$(row "sacfuse run, untiled" default "$t" "$(points "$run/untiled/fused.copc.laz")" "$(built "$run/untiled.log")")")
validate "$run/untiled/fused.copc.laz"
rm -rf "$run/untiled"
# Every config of the tiled run names its tile size: `sacfuse merge` must see the plan the run made.
tiled=(tiling.tile_size_m="$tile_m")
config "$run/run.yaml" "$run/out" output.format=copc "${tiled[@]}"
echo "== fusing $block with output.format copc, $tile_m m tiles" >&2
t=$(timed run "$sacfuse" run "$run/run.yaml")
stages=$(python3 -c "import json,sys; s=json.load(open(sys.argv[1]))['stage_wall_seconds']; \
print(f\"tiles {s['tiles']:.0f} s, merge {s['merge']:.0f} s\")" "$run/out/run_report.json")
rows+=("$(row "sacfuse run, $tile_m m tiles (tiles + merge)" default "$t" "$(points "$run/out/fused.copc.laz")" \
  "$stages; $(built "$run/run.log")")")
validate "$run/out/fused.copc.laz"
ls "$run"/out/tiles/*.copc.laz > /dev/null
cp "$run/out/fused.copc.laz" "$run/fused_from_run.copc.laz"
for gb in "${budgets[@]}"; do
  echo "== sacfuse merge, output.format copc, resources.memory_gb $gb" >&2
  config "$run/merge_$gb.yaml" "$run/out" output.format=copc resources.memory_gb="$gb" "${tiled[@]}"
  rm -f "$run/out/fused.copc.laz"
  t=$(timed "merge_$gb" "$sacfuse" merge "$run/merge_$gb.yaml")
  rows+=("$(row "sacfuse merge (COPC)" "$gb" "$t" "$(points "$run/out/fused.copc.laz")" \
    "$(built "$run/merge_$gb.log"); $(du -m "$run/out/fused.copc.laz" | cut -f1) MB")")
  validate "$run/out/fused.copc.laz"
  cp "$run/out/fused.copc.laz" "$run/fused_$gb.copc.laz"
done
echo "== sacfuse merge, output.format laz" >&2
config "$run/merge_laz.yaml" "$run/out" output.format=laz "${tiled[@]}"
t=$(timed merge_laz "$sacfuse" merge "$run/merge_laz.yaml")
rows+=("$(row "sacfuse merge (LAZ, from the COPC tiles)" default "$t" "$(points "$run/out/fused.laz")" \
  "$(du -m "$run/out/fused.laz" | cut -f1) MB")")

# Killed half-way, then again: the same bytes as the uninterrupted merge with that budget.
gb=${budgets[0]}
after=$(awk '{printf "%.2f", $1 / 2}' "$run/merge_$gb.time")
rm -f "$run/out/fused.copc.laz"
"$sacfuse" merge "$run/merge_$gb.yaml" > "$run/killed.log" 2>&1 &
pid=$!
sleep "$after"
killed=yes
kill -9 "$pid" 2> /dev/null || killed="no (the merge had ended)"
wait "$pid" 2> /dev/null || true
left=$(find "$run/out" -maxdepth 1 -name "fused.copc.laz.tmp-*" | wc -l)
"$sacfuse" merge "$run/merge_$gb.yaml" > "$run/resumed.log" 2>&1
left_after=$(find "$run/out" -maxdepth 1 -name "fused.copc.laz.tmp-*" | wc -l)
same=no
[[ "$(digest "$run/out/fused.copc.laz")" == "$(digest "$run/fused_$gb.copc.laz")" ]] && same=yes
echo "| scale $scale | budget GiB | wall s | CPU s | peak RSS MiB | points | notes |"
echo "|---|---:|---:|---:|---:|---:|---|"
printf '%s\n' "${rows[@]}"
echo
echo "merge killed after $after s: $killed ($left work files or folders left; $left_after after the next merge); run" \
     "again: identical to the uninterrupted merge but for the creation date: $same"
[[ $same == yes ]]
