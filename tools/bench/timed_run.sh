#!/usr/bin/env bash
# Runs `sacfuse run` once on a copy of a config and records its peak RSS: the one way the benchmark scripts that
# time runs (ab_time.sh, stage_ladder.sh) run a config.
#
#   tools/bench/timed_run.sh SACFUSE CONFIG DIR THREADS [SECTION.KEY=VALUE...]
#
# Writes DIR/config.yaml (config_with_output.sh: CONFIG's paths made absolute, output.dir = DIR/out, the given
# options set), removes DIR/out, runs SACFUSE under /usr/bin/time with its log in DIR/run.log and its peak RSS in
# KB in DIR/time.txt (last line). THREADS: a number for --threads, or "config" for the config's own
# resources.threads. Exits 1 (with the log's tail) when the run fails, 2 when the config cannot be rewritten.
set -euo pipefail
[[ $# -ge 4 ]] || { sed -n '2,10p' "$0" >&2; exit 2; }
sacfuse=$1 config=$2 dir=$3 threads=$4
shift 4
thread_args=()
case "$threads" in
  config) ;;
  '' | *[!0-9]*) echo "$0: THREADS must be a number or 'config', not '$threads'" >&2; exit 2 ;;
  *) thread_args=(--threads "$threads") ;;
esac
mkdir -p "$dir"
rm -rf "$dir/out"
"$(dirname "$0")/config_with_output.sh" "$config" "$dir/out" "$@" > "$dir/config.yaml" ||
  { echo "$0: cannot rewrite $config (see above)" >&2; exit 2; }
if ! /usr/bin/time -f "%M" -o "$dir/time.txt" "$sacfuse" run "$dir/config.yaml" ${thread_args[@]+"${thread_args[@]}"} \
    > "$dir/run.log" 2>&1; then
  tail -n 20 "$dir/run.log" >&2
  echo "$0: $sacfuse run $dir/config.yaml failed" >&2
  exit 1
fi
