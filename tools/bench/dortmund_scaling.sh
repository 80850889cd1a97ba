#!/usr/bin/env bash
# Scaling benchmark of the tiled job system: the `dortmund` preset (16 nadir + 43 oblique views, 1 km2, Table II
# of the paper) simulated at several image scales (--pixel-scale s: images s x 6132 x 8176, GSD 10 cm / s, the same
# flight), each fused with `sacfuse run` under the default memory budget (4 GiB) on all cores, superpixels
# included. Prints a Markdown table: wall time (fusion, and the whole process with scoring), stage times, peak RSS,
# input Mpx/s, points and F1.
#
#   tools/bench/dortmund_scaling.sh WORKDIR [SCALE ...]     (default scales: 0.25 0.5 1)
#
# Blocks are simulated once into WORKDIR/dortmund_<scale> (no normal maps: sacfuse does not read them) and
# reused; every run starts from an empty output folder, so superpixels are recomputed. Needs /usr/bin/time and
# python3. Disk: about 8 GB per 185 Mpx of depth (depth, superpixel and colour caches, tiles, fused.las).
set -euo pipefail
if [[ $# -lt 1 ]]; then
  sed -n '2,13p' "$0"
  exit 2
fi
work=$(realpath -m "$1")
shift
scales=("$@")
[[ ${#scales[@]} -gt 0 ]] || scales=(0.25 0.5 1)
here=$(cd "$(dirname "$0")/../.." && pwd)
sacfuse=${SACFUSE:-$here/build/bin/sacfuse}
mkdir -p "$work"
rows=()
for s in "${scales[@]}"; do
  block="$work/dortmund_$s"
  if [[ ! -f "$block/sacfuse.yaml" ]]; then
    echo "== simulating dortmund at pixel scale $s into $block" >&2
    "$sacfuse" simulate --preset dortmund --seed 1 --pixel-scale "$s" --no-normal-maps --out "$block" >&2
  fi
  out="$block/out_bench"
  rm -rf "$out"
  # Today's defaults for everything but the paths (the block's own sacfuse.yaml pins the defaults of its day).
  gsd=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['gsd_m'])" "$block/metadata.json")
  cat > "$block/bench.yaml" <<YAML
input: {path: "$block"}
output: {dir: "$out"}
evaluation: {reference: "$block/reference.las", mask: "$block/eval_mask.png", gsd_m: $gsd}
YAML
  echo "== fusing $block" >&2
  /usr/bin/time -v "$sacfuse" run "$block/bench.yaml" > "$block/bench.log" 2> "$block/bench.time"
  rows+=("$(python3 - "$block" <<'PY'
import json, re, sys
block = sys.argv[1]
report = json.load(open(f"{block}/out_bench/run_report.json"))
ev = json.load(open(f"{block}/out_bench/eval.json"))
meta = json.load(open(f"{block}/metadata.json"))
timing = open(f"{block}/bench.time").read()
rss_kib = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", timing).group(1))
wall = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): ([\d:.]+)", timing).group(1).split(":")
wall_s = sum(float(x) * 60 ** i for i, x in enumerate(reversed(wall)))
views = report["views"]
# Depth pixels of the block (valid or not) from the simulator's metadata.
mpx = sum(v["depth_camera"]["width"] * v["depth_camera"]["height"] for v in meta["views"]) / 1e6
st = report["stage_wall_seconds"]
f1 = [s["f1"] * 100 for s in ev["scores"]]
print(f"| {meta['gsd_m']:.2f} | {len(views)} | {mpx:.0f} | "
      f"{report['tiling_decision']['tile_size_m']:.0f} | {report['wall_seconds']:.0f} | {st['superpixels']:.0f} | "
      f"{st['tiles']:.0f} | {st['merge']:.0f} | {wall_s:.0f} | {report['peak_rss_mib']:.0f} | {rss_kib / 1024:.0f} | "
      f"{mpx / report['wall_seconds']:.2f} | {report['output_points']:,} | {f1[0]:.2f} / {f1[-1]:.2f} |")
PY
)")
done
echo "| GSD m | views | depth Mpx | tile m | fusion wall s | superpixels s | tiles s | merge s | process wall s (with scoring) | fusion peak RSS MiB | process peak RSS MiB | Mpx/s | points | F1 2x / 5x GSD % |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
printf '%s\n' "${rows[@]}"
