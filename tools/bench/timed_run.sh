#!/usr/bin/env bash
# Runs `sacfuse run` once on a config into DIR/out and records its peak RSS: the one way the benchmark scripts that
# time runs (ab_time.sh, stage_ladder.sh) run a config.
#
#   tools/bench/timed_run.sh SACFUSE CONFIG DIR THREADS [SECTION.KEY=VALUE...]
#
# Removes DIR/out, then runs `SACFUSE run CONFIG --output-dir DIR/out --set SECTION.KEY=VALUE ...` under
# /usr/bin/time with its log in DIR/run.log and its peak RSS in KB in DIR/time.txt (last line); the options set
# are recorded in DIR/out/sacfuse.effective.yaml. THREADS: a number for --threads, or "config" for the config's
# own resources.threads. Exits 1 (with the log's tail) when the run fails (a bad SECTION.KEY=VALUE included).
set -euo pipefail
[[ $# -ge 4 ]] || { sed -n '2,10p' "$0" >&2; exit 2; }
sacfuse=$1 config=$2 dir=$3 threads=$4
shift 4
run_args=(--output-dir "$dir/out")
for kv in "$@"; do run_args+=(--set "$kv"); done
case "$threads" in
  config) ;;
  '' | *[!0-9]*) echo "$0: THREADS must be a number or 'config', not '$threads'" >&2; exit 2 ;;
  *) run_args+=(--threads "$threads") ;;
esac
mkdir -p "$dir"
rm -rf "$dir/out"
if ! /usr/bin/time -f "%M" -o "$dir/time.txt" "$sacfuse" run "$config" "${run_args[@]}" > "$dir/run.log" 2>&1; then
  tail -n 20 "$dir/run.log" >&2
  echo "$0: $sacfuse run $config ${run_args[*]} failed" >&2
  exit 1
fi
