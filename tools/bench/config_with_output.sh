#!/usr/bin/env bash
# Prints a block-style sacfuse YAML config with every relative path made absolute (relative to the config's own
# folder, as sacfuse reads them) and output.dir replaced by OUT_DIR, so the copy can live anywhere. Used by the
# benchmarks that run one config into their own output folders (compare_colmap.sh, ab_time.sh).
#
#   tools/bench/config_with_output.sh CONFIG OUT_DIR > COPY.yaml
#
# Handles the block-style YAML `sacfuse simulate` writes (two-space keys under top-level sections); exits 3 on a
# flow-style section ({...}) or when the config has no output.dir key.
set -euo pipefail
[[ $# -eq 2 ]] || { sed -n '2,9p' "$0" >&2; exit 2; }
config=$1
base=$(cd "$(dirname "$config")" && pwd)
awk -v block="$base" -v outdir="$2" '
  function unquote(v) { gsub(/^[ \t]+|[ \t]+$/, "", v); if (v ~ /^".*"$/ || v ~ /^'"'"'.*'"'"'$/) v = substr(v, 2, length(v) - 2); return v }
  function absolute(v) { if (v == "" || v ~ /^\//) return v; if (v == ".") return block; sub(/^\.\//, "", v); return block "/" v }
  /^[A-Za-z_]+:[ \t]*\{/ { print "flow-style section not supported: " $0 > "/dev/stderr"; bad = 1 }
  /^[A-Za-z_]+:/ { section = $1; sub(/:.*/, "", section) }
  {
    line = $0
    if (match(line, /^  [A-Za-z_]+:/)) {
      key = substr(line, 3, RLENGTH - 3); value = substr(line, RLENGTH + 1); sub(/[ \t]+#.*$/, "", value)
      full = section "." key
      if (full == "output.dir") { line = "  dir: \"" outdir "\""; dir_set = 1 }
      else if (full == "input.path" || full == "evaluation.reference" || full == "evaluation.mask" ||
               full == "fusion.superpixel_cache_dir") line = "  " key ": \"" absolute(unquote(value)) "\""
    }
    print line
  }
  END { if (bad) exit 3; if (!dir_set) { print "no output.dir key found" > "/dev/stderr"; exit 3 } }
' "$config"
