#!/usr/bin/env bash
# What each part of a SAC run costs, and how far the rest is from a speed target (issue 13): runs one block's
# config again and again, each step switching one more part off, and prints wall time, CPU time, peak RSS and
# points per step. The last steps are the paper's SAC alone and the read-and-write floor (every valid depth pixel
# read once and written as a point, `fusion.method: union`).
#
#   tools/bench/stage_ladder.sh CONFIG [THREADS]
#
# Steps (each keeps the switches of the steps before it):
#   defaults        the config as it is
#   no coreg        coregistration.enabled=false
#   select          fusion.combine=select (an emitted pixel keeps its own depth: no averaging over other views)
#   no point tests  fusion.free_space_min_views=0, min_consistent_views=1, outlier_expected_factor=0
#   paper SAC       fusion.collapse=netlet, fusion.unary=paper (Netlets, MRF and collapse of the paper only)
#   union           fusion.method=union (no superpixels, no selection)
# Every step writes into a fresh WORK/<step>/out (WORK = $STAGE_LADDER_DIR, default a temporary folder), so each
# computes its superpixels unless the config names fusion.superpixel_cache_dir. Columns: the job's wall and CPU
# seconds and its co-registration and superpixel stages (run_report.json), the process's peak RSS (/usr/bin/time),
# points written. With COLMAP_WALL_S (COLMAP's stereo_fusion wall time on the same block, e.g. from
# compare_colmap.sh) also each step's speed ratio to COLMAP and the issue's budget (a fifth of COLMAP's time). The
# first line gives the RSS of the binary doing nothing (`sacfuse version`): its libraries, the memory floor.
# Each step's switches are `sacfuse run --set` options (tools/bench/timed_run.sh). Needs /usr/bin/time (Debian:
# time) and python3.
# SACFUSE: the binary (default build/bin/sacfuse of this checkout).
set -euo pipefail
[[ $# -ge 1 && $# -le 2 ]] || { sed -n '2,23p' "$0" >&2; exit 2; }
config=$(realpath "$1")
threads=${2:-$(nproc)}
case "$threads" in '' | *[!0-9]*) echo "$0: THREADS must be a number, not '$threads'" >&2; exit 2 ;; esac
repo=$(cd "$(dirname "$0")/../.." && pwd)
sacfuse=$(realpath "${SACFUSE:-$repo/build/bin/sacfuse}")
[[ -x $sacfuse ]] || { echo "$0: sacfuse binary not found ($sacfuse); build it or set SACFUSE" >&2; exit 2; }
[[ -x /usr/bin/time ]] || { echo "$0: /usr/bin/time not found (Debian package: time)" >&2; exit 2; }
work=${STAGE_LADDER_DIR:-$(mktemp -d)}
mkdir -p "$work"
work=$(realpath "$work")

steps=("defaults" "no coreg" "select" "no point tests" "paper SAC" "union")
switches=(""
          "coregistration.enabled=false"
          "fusion.combine=select"
          "fusion.free_space_min_views=0 fusion.min_consistent_views=1 fusion.outlier_expected_factor=0"
          "fusion.collapse=netlet fusion.unary=paper"
          "fusion.method=union")
/usr/bin/time -f "%M" -o "$work/version_rss.txt" "$sacfuse" version > /dev/null
echo "block config $config, $threads threads ($(nproc) cores), work $work"
echo "binary alone (sacfuse version): peak RSS $(( $(tail -n 1 "$work/version_rss.txt") / 1024 )) MiB"
results=$work/ladder.tsv
: > "$results"
active=()
for i in "${!steps[@]}"; do
  # shellcheck disable=SC2206  # the switches are words without spaces
  active+=(${switches[$i]})
  dir=$work/step$i
  "$(dirname "$0")/timed_run.sh" "$sacfuse" "$config" "$dir" "$threads" ${active[@]+"${active[@]}"} ||
    { echo "$0: step '${steps[$i]}' failed" >&2; exit 1; }
  printf '%s\t%s\t%s\n' "${steps[$i]}" "$dir/out/run_report.json" "$(tail -n 1 "$dir/time.txt")" >> "$results"
done
python3 - "$results" "${COLMAP_WALL_S:-}" <<'PY'
import json
import sys

rows = [line.rstrip("\n").split("\t") for line in open(sys.argv[1])]
colmap_s = float(sys.argv[2]) if sys.argv[2] else None
head = "| step | wall s | CPU s | co-registration s | superpixels s | peak RSS MiB | points |"
rule = "|---|---|---|---|---|---|---|"
if colmap_s:
    head += " COLMAP / step |"
    rule += "---|"
print(head)
print(rule)
for step, report_path, rss_kb in rows:
    report = json.load(open(report_path))
    stages = report["stage_wall_seconds"]
    line = (f"| {step} | {report['wall_seconds']:.2f} | {report['cpu_seconds']:.2f} | "
            f"{stages.get('coregistration', 0.0):.2f} | {stages.get('superpixels', 0.0):.2f} | "
            f"{int(rss_kb) / 1024:.0f} | {report['output_points']:,} |")
    if colmap_s:
        line += f" {colmap_s / report['wall_seconds']:.2f}x |"
    print(line)
if colmap_s:
    print(f"\nCOLMAP's stereo_fusion {colmap_s:.2f} s: 5x its speed is a wall time of {colmap_s / 5:.2f} s.")
PY
