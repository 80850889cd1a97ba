#!/usr/bin/env bash
# The DSM's cell rule measured on an aerial-bench block (docs/dsm-and-ortho.md, "How a cell gets its height"):
# sacfuse's fused cloud and the peers' clouds (peers.py's colmap_best and tsdf, in the block's local frame) gridded
# with `sacfuse dsm` at 1 and 2 x the block's GSD, at each quantile, without and with hole filling, every DSM scored
# by the block's independent scorer (score_dsm.py: NMAD and completeness over the evaluation mask).
#
#   tools/bench/dsm_rules.sh BLOCK FUSED.las [OUT]     # prints a Markdown table; DSMs go to OUT (default: a temp dir)
#
# Environment: SACFUSE_BIN (default build/bin/sacfuse), AERIAL_BENCH (default ../shared/aerial-bench),
# QUANTILES (default "1 0.9 0.75 0.5"), CELLS_GSD (default "1 2"), HOLES_M (default "0 2").
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
block=${1:?usage: dsm_rules.sh BLOCK FUSED.las [OUT]}
fused=${2:?usage: dsm_rules.sh BLOCK FUSED.las [OUT]}
out=${3:-$(mktemp -d)}
bin=${SACFUSE_BIN:-$root/build/bin/sacfuse}
ab=${AERIAL_BENCH:-$root/../shared/aerial-bench}
py=/usr/bin/python3
mkdir -p "$out"
read -r gsd ox oy oz < <($py -c 'import json,sys; m=json.load(open(sys.argv[1])); o=m["origin"]; print(m["gsd"], *o)' \
  "$block/meta.json")
echo "| block | cloud | cell m | quantile | max hole m | NMAD m | completeness % | median m | RMSE m |"
echo "|---|---|---|---|---|---|---|---|---|"
for cloud in sacfuse colmap_best tsdf; do
  case $cloud in
    sacfuse) file=$fused; offset=() ;;
    *) file=$block/peers/$cloud.ply; offset=(--offset "$ox,$oy,$oz") ;;
  esac
  [ -f "$file" ] || { echo "| $(basename "$block") | $cloud | missing: $file | | | | | | |"; continue; }
  for k in ${CELLS_GSD:-1 2}; do
    cell=$($py -c "print($k * $gsd)")
    for q in ${QUANTILES:-1 0.9 0.75 0.5}; do
      for hole in ${HOLES_M:-0 2}; do
        dsm=$out/${cloud}_c${k}_q${q}_h${hole}.tif
        "$bin" dsm "$file" ${offset[@]+"${offset[@]}"} --cell "$cell" --quantile "$q" --max-hole "$hole" \
          --out "$dsm" > "$dsm.log" 2>&1
        $py "$ab/score_dsm.py" "$dsm" --block "$block" --json-only | tail -1 | $py -c '
import json, sys
s = json.load(sys.stdin)["all"]
nmad, comp, med, rmse = s["nmad_m"], 100 * s["completeness"], s["median_m"], s["rmse_m"]
b, c, cell, q, h = sys.argv[1:6]
print(f"| {b} | {c} | {cell} | {q} | {h} | {nmad:.3f} | {comp:.2f} | {med:+.3f} | {rmse:.3f} |")' \
          "$(basename "$block")" "$cloud" "$cell" "$q" "$hole"
      done
    done
  done
done
