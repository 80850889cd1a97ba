#!/usr/bin/env bash
# Re-runs the benchmarks of docs/benchmarks.md and prints their tables in Markdown, each headed by its command,
# the machine and the date, so the page can be brought up to date by pasting them in. It only drives the existing
# tools (timed_run.sh, sacfuse report, sacfuse_laz_bench, sacfuse bench, compare_colmap.sh, stage_ladder.sh,
# dortmund_scaling.sh); see each of them for what it measures.
#
#   tools/bench/benchmarks.sh WORKDIR [PART...]        (default part: quick)
#
# Parts, cheapest first:
#   quick     a few minutes: the simulated tiny and small blocks fused at the defaults (time, memory, points, F1),
#             the report of each (sacfuse report), and LAZ against LAS (sacfuse_laz_bench)
#   quality   ~20 min: sacfuse bench on our six blocks, every method, COLMAP's stereo_fusion when installed
#   aerial    an hour or more the first time: SAC on aerial-bench's six blocks beside its peers (sacfuse bench
#             --aerial-bench; needs ../shared/aerial-bench and its Python packages, see docs/install.md)
#   colmap    sacfuse against COLMAP's stereo_fusion on aerial-bench Montpellier at COLMAP's best setting on these
#             blocks, two runs (the block made by the aerial part, or AERIAL_BLOCK=DIR)
#   ladder    tools/bench/stage_ladder.sh on that block: what each part of a SAC run costs
#   dortmund  hours: tools/bench/dortmund_scaling.sh at DORTMUND_SCALES (default "0.125 0.25 0.5"; "1" is the
#             full 2.96-gigapixel block: ~1 h to simulate, ~20 min to fuse, ~20 GB of disk)
#
# WORKDIR holds every block and output (reused between calls: blocks are simulated once). Environment: SACFUSE
# (default build/bin/sacfuse of this checkout), LAZ_BENCH (default build/tools/laz_bench/sacfuse_laz_bench, target
# sacfuse_laz_bench), THREADS (default: all cores). Needs /usr/bin/time and jq (Debian: time, jq;
# tools/install_deps.sh installs both) and what the parts' tools need.
set -euo pipefail
usage() { sed -n '2,24p' "$0" >&2; exit 2; }
[ $# -ge 1 ] || usage
REPO=$(cd "$(dirname "$0")/../.." && pwd)
BENCH=$REPO/tools/bench
mkdir -p "$1"
WORK=$(cd "$1" && pwd)
shift
PARTS=("$@")
[ ${#PARTS[@]} -gt 0 ] || PARTS=(quick)
SACFUSE=${SACFUSE:-$REPO/build/bin/sacfuse}
THREADS=${THREADS:-$(nproc)}
[ -x "$SACFUSE" ] || { echo "$0: $SACFUSE not found: build it (tools/build.sh --target sacfuse) or set SACFUSE" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "$0: /usr/bin/time not found (Debian package: time)" >&2; exit 2; }
command -v jq >/dev/null || { echo "$0: jq not found (Debian package: jq)" >&2; exit 2; }
for part in "${PARTS[@]}"; do
  case "$part" in quick | quality | aerial | colmap | ladder | dortmund) ;; *) echo "$0: unknown part '$part'" >&2; usage ;; esac
done

machine() {
  local cpu mem os
  cpu=$(sed -n 's/^model name\s*:\s*//p' /proc/cpuinfo | head -n 1)
  mem=$(awk '/^MemTotal/ { printf "%.0f", $2 / 1048576 }' /proc/meminfo)
  os=$(. /etc/os-release && echo "$PRETTY_NAME")
  echo "$(nproc) cores ($cpu), $mem GiB, $os"
}

# A part's header: what ran, where and when.
header() {
  echo
  echo "### $1"
  echo
  echo "Command: \`$2\`  "
  echo "Machine: $(machine); $THREADS threads; load average before: $(cut -d' ' -f1-3 /proc/loadavg)  "
  echo "Date: $(date -u +%Y-%m-%d); sacfuse: $("$SACFUSE" version 2>/dev/null | head -n 1)"
  echo
}

# Simulates a preset once into WORK/blocks/NAME.
block() {
  local name=$1 preset=$2 seed=$3
  if [ ! -f "$WORK/blocks/$name/metadata.json" ]; then
    "$SACFUSE" simulate --preset "$preset" --seed "$seed" --out "$WORK/blocks/$name" > "$WORK/blocks/$name.log" 2>&1 ||
      { tail -n 20 "$WORK/blocks/$name.log" >&2; echo "$0: simulate $preset failed" >&2; exit 1; }
  fi
}

f1_percent() {  # eval.json, threshold index -> F1 in %
  printf '%.2f' "$(jq -r --argjson i "$2" '.scores[$i].f1 * 100' "$1")"
}

part_quick() {
  mkdir -p "$WORK/blocks" "$WORK/runs"
  header "Simulated blocks at the defaults" \
    "tools/bench/timed_run.sh SACFUSE BLOCK/sacfuse.yaml DIR $THREADS (blocks: sacfuse simulate --preset tiny --seed 3, --preset small --seed 7)"
  echo "| block | views | valid depth pixels | points | fusion wall s | fusion CPU s | fusion peak RSS MiB | process peak RSS MiB | F1 2× / 5× GSD % |"
  echo "|---|---:|---:|---:|---:|---:|---:|---:|---|"
  for spec in "tiny 3" "small 7"; do
    set -- $spec
    block "$1" "$1" "$2"
    "$BENCH/timed_run.sh" "$SACFUSE" "$WORK/blocks/$1/sacfuse.yaml" "$WORK/runs/$1" "$THREADS" >&2
    local r=$WORK/runs/$1/out/run_report.json e=$WORK/runs/$1/out/eval.json
    printf '| %s (seed %s) | %s | %s | %s | %.1f | %.1f | %.0f | %.0f | %s / %s |\n' "$1" "$2" \
      "$(jq '.views | length' "$r")" "$(jq '.input_points' "$r")" "$(jq '.output_points' "$r")" \
      "$(jq '.wall_seconds' "$r")" "$(jq '.cpu_seconds' "$r")" "$(jq '.peak_rss_mib' "$r")" \
      "$(awk 'END { print $1 / 1024 }' "$WORK/runs/$1/time.txt")" "$(f1_percent "$e" 0)" "$(f1_percent "$e" 1)"
  done

  header "The run report" "/usr/bin/time sacfuse report DIR/config.yaml (the runs above)"
  echo "| block | points | report wall s | report CPU s | peak RSS MiB |"
  echo "|---|---:|---:|---:|---:|"
  for name in tiny small; do
    /usr/bin/time -f '%e %U %S %M' -o "$WORK/runs/$name/report.time" "$SACFUSE" report "$WORK/runs/$name/config.yaml" \
      > "$WORK/runs/$name/report.log" 2>&1
    read -r wall user sys rss < "$WORK/runs/$name/report.time"
    printf '| %s | %s | %.1f | %.1f | %.0f |\n' "$name" "$(jq '.output_points' "$WORK/runs/$name/out/run_report.json")" \
      "$wall" "$(awk -v u="$user" -v s="$sys" 'BEGIN { print u + s }')" "$(awk -v k="$rss" 'BEGIN { print k / 1024 }')"
  done

  local laz_bench=${LAZ_BENCH:-$REPO/build/tools/laz_bench/sacfuse_laz_bench}
  if [ -x "$laz_bench" ]; then
    header "LAZ against LAS" "sacfuse_laz_bench --points 3000000; sacfuse_laz_bench --las small/out/fused.laz"
    "$laz_bench" --points 3000000 --dir "$WORK/laz"
    "$laz_bench" --las "$WORK/runs/small/out/fused.laz" --dir "$WORK/laz" | tail -n +3
  else
    echo >&2 "$0: $laz_bench not built (tools/build.sh --target sacfuse_laz_bench): LAZ table skipped"
  fi
}

part_quality() {
  header "Quality: sacfuse bench" "sacfuse bench --out DIR --aerial-bench off"
  "$SACFUSE" bench --out "$WORK/bench" --aerial-bench off > "$WORK/bench.log" 2>&1 ||
    echo >&2 "$0: sacfuse bench reported failed rows (see $WORK/bench.log)"
  cat "$WORK/bench/bench.md"
}

part_aerial() {
  header "aerial-bench" "sacfuse bench --out DIR --quick --methods sac --aerial-bench auto"
  "$SACFUSE" bench --out "$WORK/bench_aerial" --quick --methods sac --aerial-bench auto > "$WORK/bench_aerial.log" 2>&1 ||
    echo >&2 "$0: sacfuse bench reported failed rows (see $WORK/bench_aerial.log)"
  cat "$WORK/bench_aerial/bench.md"
}

# A folder whose sacfuse.yaml fuses the aerial-bench Montpellier block (compare_colmap.sh and stage_ladder.sh take
# a config; aerial-bench's blocks are bare COLMAP workspaces).
aerial_config() {
  local block=${AERIAL_BLOCK:-$WORK/bench_aerial/aerial/montpellier}
  [ -d "$block/stereo" ] || { echo "$0: no aerial-bench block at $block: run the aerial part or set AERIAL_BLOCK" >&2; exit 2; }
  mkdir -p "$WORK/montpellier"
  printf 'input: {format: colmap, path: %s}\noutput: {dir: out}\n' "$(cd "$block" && pwd)" > "$WORK/montpellier/sacfuse.yaml"
  echo "$WORK/montpellier"
}

part_colmap() {
  local dir
  dir=$(aerial_config)
  local args="--stereo-fusion max_normal_error=180 --stereo-fusion min_num_pixels=5 --stereo-fusion max_reproj_error=1"
  header "Against COLMAP's stereo_fusion" "COLMAP_ARGS=\"$args\" tools/bench/compare_colmap.sh BLOCK $THREADS (twice)"
  for run in 1 2; do
    COLMAP_ARGS=$args SACFUSE=$SACFUSE "$BENCH/compare_colmap.sh" "$dir" "$THREADS" "$WORK/compare_$run" | sed -n '/^| method/,$p'
    echo
  done
}

part_ladder() {
  local dir
  dir=$(aerial_config)
  header "What each part of a run costs" "tools/bench/stage_ladder.sh BLOCK/sacfuse.yaml $THREADS"
  STAGE_LADDER_DIR=$WORK/ladder SACFUSE=$SACFUSE "$BENCH/stage_ladder.sh" "$dir/sacfuse.yaml" "$THREADS"
}

part_dortmund() {
  local scales=${DORTMUND_SCALES:-0.125 0.25 0.5}
  header "Scale: the Dortmund-size block" "tools/bench/dortmund_scaling.sh DIR $scales"
  # shellcheck disable=SC2086
  SACFUSE=$SACFUSE "$BENCH/dortmund_scaling.sh" "$WORK/dortmund" $scales
}

echo "## Benchmarks ($(date -u +%Y-%m-%d), $(machine))"
for part in "${PARTS[@]}"; do "part_$part"; done
