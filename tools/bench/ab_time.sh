#!/usr/bin/env bash
# Times two or more sacfuse binaries on one config, alternating them so that a drift of the machine hits all of
# them alike (a speed change is measured against its baseline in the same run, never against an old number).
#
#   tools/bench/ab_time.sh CONFIG REPEATS BINARY...
#
# CONFIG is a sacfuse YAML: every run writes into a fresh WORK/out (`--output-dir`, through timed_run.sh; WORK =
# $AB_TIME_DIR, default a temporary folder), so each starts cold (superpixels recomputed unless the config names
# fusion.superpixel_cache_dir). For each repeat and each binary it prints one
# line: wall and CPU seconds of the job (run_report.json), SAC's stage seconds, the process's peak RSS
# (/usr/bin/time), and whether the cloud is byte-identical to the first binary's cloud of the same repeat.
# At the end, the median wall and CPU time of each binary and their ratios to the first binary.
# Needs /usr/bin/time (Debian: time) and python3.
set -euo pipefail
if [[ $# -lt 3 ]]; then
  sed -n '2,12p' "$0"
  exit 2
fi
config=$(realpath "$1")
repeats=$2
shift 2
binaries=()
for b in "$@"; do binaries+=("$(realpath "$b")"); done
[[ -x /usr/bin/time ]] || { echo "$0: /usr/bin/time not found (Debian package: time)" >&2; exit 2; }
case "$repeats" in '' | *[!0-9]*) echo "$0: REPEATS must be a number, not '$repeats'" >&2; exit 2 ;; esac
work=${AB_TIME_DIR:-$(mktemp -d)}
mkdir -p "$work"
results=$work/results.tsv
: > "$results"
for ((rep = 1; rep <= repeats; ++rep)); do
  first_cloud=""
  for i in "${!binaries[@]}"; do
    b=${binaries[$i]}
    out=$work/out
    "$(dirname "$0")/timed_run.sh" "$b" "$config" "$work" config
    cloud=$(ls "$out"/fused.la[sz])
    same="-"
    if [[ $i -eq 0 ]]; then
      cp "$cloud" "$work/first_cloud"
      first_cloud=$work/first_cloud
    else
      cmp -s "$cloud" "$first_cloud" && same="identical" || same="differs"
    fi
    python3 - "$out/run_report.json" "$(tail -n 1 "$work/time.txt")" "$i" "$rep" "$same" "$b" "$results" <<'PY'
import json, sys
report, rss_kb, index, rep, same, binary, results = sys.argv[1:]
d = json.load(open(report))
stages = (d.get("sac") or {}).get("stage_seconds", {})
stage_text = " ".join(f"{k} {v:.2f}" for k, v in stages.items() if v >= 0.05)
print(f"repeat {rep} binary {index} wall {d['wall_seconds']:.2f} s cpu {d['cpu_seconds']:.2f} s "
      f"peak {int(rss_kb) / 1024:.0f} MiB cloud {same} | {stage_text} | {binary}")
with open(results, "a") as f:
    f.write(f"{index}\t{d['wall_seconds']}\t{d['cpu_seconds']}\n")
PY
  done
done
python3 - "$results" "${binaries[@]}" <<'PY'
import statistics, sys
rows = [line.split("\t") for line in open(sys.argv[1]).read().split("\n") if line]
binaries = sys.argv[2:]
median = {}
for i in range(len(binaries)):
    walls = [float(r[1]) for r in rows if int(r[0]) == i]
    cpus = [float(r[2]) for r in rows if int(r[0]) == i]
    median[i] = (statistics.median(walls), statistics.median(cpus))
for i, b in enumerate(binaries):
    w, c = median[i]
    print(f"binary {i}: median wall {w:.2f} s, cpu {c:.2f} s; ratio to binary 0: wall {w / median[0][0]:.2f}, "
          f"cpu {c / median[0][1]:.2f}  ({b})")
PY
