#!/usr/bin/env bash
# sacfuse on the independent aerial-bench (../shared/aerial-bench: a simulator over real LiDAR, its peers and its
# scorer, written apart from sacfuse), beside the peers' rows, in one table.
#
#   tools/bench/aerial_bench.sh WORK [BLOCK...]
#
# BLOCK: montpellier, montpellier_e25, zurich, zurich_e25 (default: all four; e25 = every error x2.5). Blocks are
# made once in WORK/<block> by make_block.py (Montpellier: the six IGN tiles at GSD 0.25 m; Zurich: zurich.las at
# GSD 0.125 m with 0.25 m DSM cells, the settings its README names as ranking methods), then for each block:
# `sacfuse run` (defaults, output.format las) scored by score.py, and peers.py's tsdf, union and oracle rows (once;
# AB_COLMAP=1 adds colmap_best over the grid max_normal_error=180 x min_num_pixels=2,5 x max_reproj_error=1,2).
# Environment: SACFUSE (binary, default build/bin/sacfuse), SACFUSE_SHARED (default ../shared next to the checkout),
# AB_PY (/usr/bin/python3 with Debian's python3-numpy, -scipy, -opencv, -open3d: tools/install_deps.sh installs
# them as optional benchmark packages). Prints one line per block; the JSON of every score is kept in WORK.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
work="${1:?usage: tools/bench/aerial_bench.sh WORK [BLOCK...]}"
shift
blocks=("$@")
[ ${#blocks[@]} -gt 0 ] || blocks=(montpellier montpellier_e25 zurich zurich_e25)
shared="${SACFUSE_SHARED:-$root/../shared}"
ab="$shared/aerial-bench"
lidar="$shared/research-data/lidar"
sacfuse="${SACFUSE:-$root/build/bin/sacfuse}"
py="${AB_PY:-/usr/bin/python3}"
if [ ! -f "$ab/make_block.py" ] || [ ! -d "$lidar" ]; then
  echo "aerial_bench: $ab or $lidar not found; skipped (set SACFUSE_SHARED)"; exit 0
fi
mkdir -p "$work"
work="$(cd "$work" && pwd)"

make_args() {  # block name -> make_block.py arguments
  case "$1" in
    montpellier) echo "$lidar/ign_montpellier/test_data_*.las --gsd 0.25" ;;
    montpellier_e25) echo "$lidar/ign_montpellier/test_data_*.las --gsd 0.25 --error-scale 2.5" ;;
    zurich) echo "$lidar/lastools/zurich.las --gsd 0.125 --cell 0.25" ;;
    zurich_e25) echo "$lidar/lastools/zurich.las --gsd 0.125 --cell 0.25 --error-scale 2.5" ;;
    *) echo "aerial_bench: unknown block $1" >&2; exit 2 ;;
  esac
}

for b in "${blocks[@]}"; do
  blk="$work/$b"
  if [ ! -f "$blk/meta.json" ]; then
    # shellcheck disable=SC2046  # the glob of the LiDAR tiles must expand
    (cd "$ab" && "$py" make_block.py $(make_args "$b") --out "$blk" --force) > "$work/$b.make.log" 2>&1
  fi
  printf 'input: {format: colmap, path: %s}\noutput: {dir: %s, format: las}\n' "$blk" "$work/$b.sacfuse" \
    > "$work/$b.sacfuse.yaml"
  "$sacfuse" run "$work/$b.sacfuse.yaml" > "$work/$b.sacfuse.log" 2>&1
  "$py" "$ab/score.py" "$work/$b.sacfuse/fused.las" --block "$blk" --json-only > "$work/$b.sacfuse.score.json"
  methods="tsdf,union,oracle"
  [ "${AB_COLMAP:-0}" = 1 ] && methods="$methods,colmap_best"
  if [ ! -f "$blk/peers.json" ]; then
    (cd "$ab" && "$py" peers.py --block "$blk" --methods "$methods" --grid max_normal_error=180 \
      --grid min_num_pixels=2,5 --grid max_reproj_error=1,2) > "$work/$b.peers.log" 2>&1
  fi
  "$py" - "$b" "$work/$b.sacfuse.score.json" "$blk/peers.json" "$work/$b.sacfuse/run_report.json" <<'PY'
import json, sys
name, score, peers, report = sys.argv[1:5]
s = json.loads(open(score).readline())
rows = {p["method"]: p for p in json.load(open(peers)).get("peers", [])}
r = json.load(open(report))
def f1(x): return "/".join(f"{t['f1']:.4f}" for t in x["scores"])
line = (f"{name}: sacfuse F1 {f1(s)} points in mask {s['points_in_mask']} "
        f"({s['density_per_m2']:.1f}/m2) above top {100 * s['diagnostics_v2']['above_top']:.2f} % "
        f"fusion {r['wall_seconds']:.1f} s")
for m in ("colmap_best", "tsdf", "union", "oracle"):
    p = rows.get(m)
    if p and p.get("score"):
        ps = p["score"]
        line += (f" | {m} {f1(ps)} {ps['density_per_m2']:.1f}/m2"
                 f" above {100 * ps.get('diagnostics_v2', {}).get('above_top', 0):.2f} %")
print(line)
PY
done
