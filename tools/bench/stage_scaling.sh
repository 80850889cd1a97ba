#!/usr/bin/env bash
# How every stage of a run scales with threads (issue 48): runs one config with 1, 2, 4, ... threads (up to the
# machine's cores, or the counts given), each from an empty output folder (so co-registration and superpixels are
# computed every time), and prints one Markdown table: per stage its wall and CPU seconds at each thread count, the
# speed-up of its wall time over one thread and its CPU seconds against one thread's. Optionally also COLMAP's
# stereo_fusion on the same workspace and its speed against sacfuse's.
#
#   tools/bench/stage_scaling.sh CONFIG [THREADS...]
#
# Stages and their times come from each run's run_report.json ("stages": wall and CPU seconds of every stage,
# io/stage_clock.h); "to fused cloud" is the job up to the cloud written (run_report.json wall_seconds, what
# compare_colmap.sh compares), "whole run" every stage with scoring and report; peak RSS is the process's
# (/usr/bin/time). A stage shorter than MIN_STAGE_S (default 0.5 s) on one thread gets no speed-up: too short to
# time. REPEATS (default 1) runs every thread count that many times, alternating, and takes each stage's median.
# Every run line records the load average before it: wall-clock ratios mean little on a loaded machine.
#
# STAGE_SCALING_PERF=1 also runs every sacfuse under `perf record -e cpu-clock` (Debian: linux-perf) and adds, per
# stage and thread count above the first, two figures that do not depend on the machine's load, since a thread is
# only sampled while it runs: "balance" = the stage's CPU samples / those of its busiest thread (the most any
# number of free cores could speed the stage up with that thread count's split of the work; 1.00 = serial), and
# "bound" = the first thread count's CPU seconds / the busiest thread's CPU seconds (the stage's speed-up over the
# first thread count on an otherwise idle machine if the threads never wait for each other; an upper bound).
# Stages are placed on the samples' timeline from their wall times, aligned at the last sample. With perf it also
# prints, per stage, the serial CPU seconds inferred from the largest thread count's split and the speed-up that
# Amdahl's law then gives on 4 ... 64 free cores (an inference, not a measurement: uneven work counts as serial).
#
# Environment: SACFUSE (default build/bin/sacfuse of this checkout), STAGE_SCALING_DIR (work folder, default a
# temporary one), COLMAP_WALL_S (COLMAP's stereo_fusion wall time on this block, measured elsewhere: prints the
# ratio), STAGE_SCALING_COLMAP=1 (runs `sacfuse colmap-fusion` at each thread count, after sacfuse, with
# COLMAP_ARGS, default its best setting on the aerial-bench blocks: max_normal_error=180, min_num_pixels=5,
# max_reproj_error=1). Needs /usr/bin/time (Debian: time) and python3 with PyYAML (python3-yaml); the COLMAP runs
# need colmap (tools/install_deps.sh installs all three).
set -euo pipefail
[[ $# -ge 1 ]] || { sed -n '2,33p' "$0" >&2; exit 2; }
config=$(realpath "$1")
shift
threads=("$@")
if [[ ${#threads[@]} -eq 0 ]]; then
  cores=$(nproc)
  for ((t = 1; t <= cores; t *= 2)); do threads+=("$t"); done
  [[ ${threads[-1]} -eq $cores ]] || threads+=("$cores")
fi
for t in "${threads[@]}"; do
  case "$t" in '' | *[!0-9]* | 0) echo "$0: thread counts must be positive numbers, not '$t'" >&2; exit 2 ;; esac
done
repo=$(cd "$(dirname "$0")/../.." && pwd)
sacfuse=$(realpath "${SACFUSE:-$repo/build/bin/sacfuse}")
[[ -x $sacfuse ]] || { echo "$0: sacfuse binary not found ($sacfuse); build it or set SACFUSE" >&2; exit 2; }
[[ -x /usr/bin/time ]] || { echo "$0: /usr/bin/time not found (Debian package: time)" >&2; exit 2; }
repeats=${REPEATS:-1}
case "$repeats" in '' | *[!0-9]* | 0) echo "$0: REPEATS must be a positive number" >&2; exit 2 ;; esac
work=${STAGE_SCALING_DIR:-$(mktemp -d)}
mkdir -p "$work"
work=$(realpath "$work")
perf=${STAGE_SCALING_PERF:-0}
run_bin=$sacfuse
if [[ $perf == 1 ]]; then
  command -v perf > /dev/null || { echo "$0: STAGE_SCALING_PERF=1 needs perf (Debian: linux-perf)" >&2; exit 2; }
  run_bin=$work/perf_sacfuse.sh  # timed_run.sh runs this one: sacfuse under perf, data to $STAGE_SCALING_PERF_DATA
  # shellcheck disable=SC2016  # $STAGE_SCALING_PERF_DATA and $@ are for the wrapper to expand
  printf '#!/bin/sh\nexec perf record -q -e cpu-clock -F 499 -o "$STAGE_SCALING_PERF_DATA" -- %q "$@"\n' \
    "$sacfuse" > "$run_bin"
  chmod +x "$run_bin"
fi
colmap_args=${COLMAP_ARGS:-"--stereo-fusion max_normal_error=180 --stereo-fusion min_num_pixels=5 --stereo-fusion max_reproj_error=1"}

echo "config $config; threads ${threads[*]} on $(nproc) cores ($(lscpu 2>/dev/null | sed -n 's/^Model name: *//p'));" \
  "$(awk '/MemTotal/ { printf "%.0f GiB", $2 / 1048576 }' /proc/meminfo) memory; $(date -u '+%Y-%m-%d %H:%M UTC')"
echo "sacfuse: $("$sacfuse" version); work $work"
runs=$work/runs.tsv
: > "$runs"
for ((rep = 1; rep <= repeats; ++rep)); do
  for t in "${threads[@]}"; do
    dir=$work/t${t}_r$rep
    load=$(cut -d' ' -f1-3 /proc/loadavg)
    perf_data=-
    [[ $perf == 1 ]] && perf_data=$dir/perf.data
    STAGE_SCALING_PERF_DATA=$perf_data "$(dirname "$0")/timed_run.sh" "$run_bin" "$config" "$dir" "$t" || { echo "$0: the run on $t threads failed" >&2; exit 1; }
    colmap_json=-
    if [[ ${STAGE_SCALING_COLMAP:-0} == 1 ]]; then
      # shellcheck disable=SC2086  # COLMAP_ARGS is a list of words
      "$sacfuse" colmap-fusion "$config" --out "$dir/colmap" --threads "$t" $colmap_args \
        > "$dir/colmap.log" 2>&1 || { tail -n 20 "$dir/colmap.log" >&2; echo "$0: colmap-fusion failed" >&2; exit 1; }
      colmap_json=$dir/colmap/colmap_fusion.json
    fi
    printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$t" "$dir/out/run_report.json" "$(tail -n 1 "$dir/time.txt")" "$load" \
      "$colmap_json" "$perf_data" >> "$runs"
    echo "run: $t threads, repeat $rep, load average before it $load" >&2
  done
done

python3 - "$runs" "${MIN_STAGE_S:-0.5}" "${COLMAP_WALL_S:-}" <<'PY'
import collections
import json
import statistics
import subprocess
import sys

runs_path, min_stage_s, colmap_wall = sys.argv[1], float(sys.argv[2]), sys.argv[3]


def thread_samples(perf_data, report):
    """Per stage name: (CPU samples of every thread, those of the busiest thread), from perf's samples."""
    out = subprocess.run(["perf", "script", "-i", perf_data, "-F", "tid,time"], capture_output=True, text=True,
                         check=True).stdout
    samples = []  # (seconds, thread id)
    for line in out.splitlines():
        fields = line.split()
        if len(fields) == 2:
            samples.append((float(fields[1].rstrip(":")), int(fields[0])))
    stages = report["stages"]["list"]
    start = samples[-1][0] - sum(s["wall_s"] for s in stages)  # the last stage ends at the last sample
    result = {}
    for s in stages:
        end = start + s["wall_s"]
        per_thread = collections.Counter(tid for time, tid in samples if start <= time < end)
        start = end
        if per_thread:
            result[s["name"]] = (sum(per_thread.values()), per_thread.most_common(1)[0][1])
    return result


by_threads = {}  # threads -> list of (report, rss_kb, load, colmap json or None, thread samples or None)
for line in open(runs_path):
    t, report, rss_kb, load, colmap, perf_data = line.rstrip("\n").split("\t")
    report = json.load(open(report))
    by_threads.setdefault(int(t), []).append(
        (report, int(rss_kb), load, None if colmap == "-" else json.load(open(colmap)),
         None if perf_data == "-" else thread_samples(perf_data, report)))
threads = sorted(by_threads)
names = []  # stage names in the order they ran
for t in threads:
    for report, *_ in by_threads[t]:
        for s in report["stages"]["list"]:
            if s["name"] not in names:
                names.append(s["name"])


def median(values):
    return statistics.median(values) if values else None


def stage(t, name, key):
    return median([s[key] for report, *_ in by_threads[t] for s in report["stages"]["list"] if s["name"] == name])


def busiest_share(t, name):
    """Median over the runs on t threads of the stage's busiest thread's share of its CPU samples."""
    return median([samples[name][1] / samples[name][0] for *_, samples in by_threads[t]
                   if samples and name in samples])


rows = [(name, lambda t, n=name: stage(t, n, "wall_s"), lambda t, n=name: stage(t, n, "cpu_s")) for name in names]
rows.append(("**to fused cloud**", lambda t: median([r["wall_seconds"] for r, *_ in by_threads[t]]),
             lambda t: median([r["cpu_seconds"] for r, *_ in by_threads[t]])))
rows.append(("**whole run**", lambda t: median([r["stages"]["total_wall_s"] for r, *_ in by_threads[t]]),
             lambda t: median([r["stages"]["total_cpu_s"] for r, *_ in by_threads[t]])))
base = threads[0]
head = "| stage |" + "".join(f" {t} thr wall s | {t} thr CPU s |" for t in threads)
rule = "|---|" + "---|---|" * len(threads)
with_perf = any(samples for t in threads for *_, samples in by_threads[t])
for t in threads[1:]:
    head += f" speed-up {t}/{base} | CPU {t}/{base} |" + (f" balance {t} | bound {t}/{base} |" if with_perf else "")
    rule += "---|---|" + ("---|---|" if with_perf else "")
print(head)
print(rule)
for label, wall, cpu in rows:
    line = f"| {label} |"
    for t in threads:
        w, c = wall(t), cpu(t)
        line += f" {w:.2f} | {c:.2f} |" if w is not None else " – | – |"
    for t in threads[1:]:
        w0, c0, w, c = wall(base), cpu(base), wall(t), cpu(t)
        if None in (w0, c0, w, c):
            line += " – | – |"
        elif w0 < min_stage_s:
            line += f" (< {min_stage_s:g} s) | {c / c0:.2f} |" if c0 > 0 else f" (< {min_stage_s:g} s) | – |"
        else:
            line += f" {w0 / w:.2f}x | {c / c0:.2f} |" if c0 > 0 else f" {w0 / w:.2f}x | – |"
        if with_perf:
            share = busiest_share(t, label) if label in names else None
            if share is None or c is None or c0 is None or c0 < min_stage_s:
                line += " – | – |"
            else:
                line += f" {1 / share:.2f} | {c0 / (share * c):.2f}x |"
    print(line)
if with_perf and threads[-1] > 1:
    # Amdahl from the largest thread count's split: its busiest thread ran B = S + P / T of the stage's CPU
    # C = S + P, so the serial part is S = (T B - C) / (T - 1) (uneven work counts as serial: an upper bound), and
    # on N free cores the stage would take S + P / N, against the first thread count's CPU seconds.
    top = threads[-1]
    counts = [n for n in (4, 8, 16, 32, 64) if n > top]
    print(f"\nInferred from the {top}-thread split (Amdahl: serial part S = (T B - C) / (T - 1), wall on N free "
          f"cores S + (C - S) / N), speed-up over {base} thread{'s' if base > 1 else ''}:\n")
    print("| stage | CPU s | serial s |" + "".join(f" {n} cores |" for n in counts))
    print("|---|---|---|" + "---|" * len(counts))
    total_c0 = total_s = total_c = 0.0
    for name in names:
        share, c, c0 = busiest_share(top, name), stage(top, name, "cpu_s"), stage(base, name, "cpu_s")
        if share is None or c is None or c0 is None or c0 < min_stage_s:
            continue
        serial = max(0.0, (top * share * c - c) / (top - 1))
        total_c0, total_s, total_c = total_c0 + c0, total_s + serial, total_c + c
        print(f"| {name} | {c:.2f} | {serial:.2f} |" + "".join(f" {c0 / (serial + (c - serial) / n):.2f}x |"
                                                          for n in counts))
    if total_c > 0:
        print(f"| **these stages** | {total_c:.2f} | {total_s:.2f} |"
              + "".join(f" {total_c0 / (total_s + (total_c - total_s) / n):.2f}x |" for n in counts))
rss = {t: median([rss_kb / 1024 for _, rss_kb, *_ in by_threads[t]]) for t in threads}
print("\npeak RSS MiB (whole process" + (", perf's included" if with_perf else "") + "): " + ", ".join(f"{t} threads {rss[t]:.0f}" for t in threads))
print("load average before each run: " + "; ".join(f"{t} threads {', '.join(l for _, _, l, *_ in by_threads[t])}"
                                                    for t in threads))
points = {r["output_points"] for t in threads for r, *_ in by_threads[t]}
print(f"points: {', '.join(f'{p:,}' for p in sorted(points))}"
      + (" (the same for every thread count)" if len(points) == 1 else " (DIFFERENT between thread counts)"))
colmap = {t: [c for _, _, _, c, _ in by_threads[t] if c is not None] for t in threads}
for t in threads:
    fused = median([r["wall_seconds"] for r, *_ in by_threads[t]])
    fused_rss = median([r["peak_rss_mib"] for r, *_ in by_threads[t]])
    if colmap[t]:
        c_wall = median([c["wall_s"] for c in colmap[t]])
        c_rss = median([c["peak_rss_mib"] for c in colmap[t]])
        print(f"COLMAP stereo_fusion on {t} threads: {c_wall:.2f} s, {c_rss:.0f} MiB; sacfuse to fused cloud "
              f"{fused:.2f} s, {fused_rss:.0f} MiB: {c_wall / fused:.2f}x COLMAP's speed at {fused_rss / c_rss:.2f}x "
              f"its memory")
    elif colmap_wall:
        print(f"COLMAP_WALL_S {float(colmap_wall):.2f} s: sacfuse to fused cloud on {t} threads {fused:.2f} s, "
              f"{float(colmap_wall) / fused:.2f}x COLMAP's speed")
PY
