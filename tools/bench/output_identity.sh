#!/usr/bin/env bash
# Guard for refactors that must not change results: runs every fusion method, untiled and tiled, on 1 and 2
# threads, on the tiny and small simulated blocks, and records a checksum of each fused.las with the header's
# creation date zeroed (bytes 90-93: day of year, year) — everything else, header and points, must be identical.
#
#   tools/bench/output_identity.sh record WORK BASELINE.txt   # with the binary before the change
#   tools/bench/output_identity.sh check  WORK BASELINE.txt   # with the binary after it: exit 1 on any difference
#                                                             # (the runs made now against their baseline lines)
#
# WORK is a scratch folder (blocks are simulated there once and reused). Environment: SACFUSE_BIN (default
# build/bin/sacfuse), METHODS (default: all six), BLOCKS (default "tiny small"), TILE_M (tile size of the tiled
# runs, default 20 m: several tiles on both blocks), CRS (the runs' `crs` key, default none; e.g. EPSG:25832
# makes them write their DSM and true ortho too, whose reading of the tiles must leave the clouds alone, and then
# DIR/dsm.tif and DIR/ortho.tif are compared byte for byte as well). Not a test of the default suite (it takes minutes); run it
# before each commit of a refactor.
set -euo pipefail
mode=${1:?usage: output_identity.sh record|check WORK BASELINE.txt}
work=${2:?usage: output_identity.sh record|check WORK BASELINE.txt}
baseline=${3:?usage: output_identity.sh record|check WORK BASELINE.txt}
case "$mode" in record|check) ;; *) echo "mode must be record or check, not '$mode'" >&2; exit 2 ;; esac
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=${SACFUSE_BIN:-$root/build/bin/sacfuse}
methods=${METHODS:-"sac union consistency disparity_normal tsdf multiray"}
blocks=${BLOCKS:-"tiny small"}
tile_m=${TILE_M:-20}
crs_line=""
[ -n "${CRS:-}" ] && crs_line="crs: \"$CRS\""
mkdir -p "$work"
work=$(cd "$work" && pwd)
# Binaries that know output.format (las | laz) are asked for LAS; older ones write only fused.las.
format_key=""
defaults=$("$bin" run --print-defaults 2>/dev/null || true)  # not piped into grep -q: SIGPIPE under pipefail
if grep -qE "^  format: \"(las|laz)\"" <<<"$defaults"; then format_key=", format: las"; fi

# Checksum of a LAS file with its creation day and year (header bytes 90..93) zeroed.
las_digest() {
  python3 - "$1" <<'EOF'
import hashlib, sys
data = bytearray(open(sys.argv[1], "rb").read())
data[90:94] = b"\0\0\0\0"
print(hashlib.sha256(data).hexdigest(), len(data))
EOF
}

results=$(mktemp)
trap 'rm -f "$results"' EXIT
for block in $blocks; do
  dir=$work/block_$block
  if [ ! -f "$dir/metadata.json" ]; then
    "$bin" simulate --preset "$block" --seed 7 --out "$dir" >/dev/null
  fi
  for method in $methods; do
    for tiled in untiled tiled; do
      for threads in 1 2; do
        name=$block.$method.$tiled.t$threads
        out=$work/runs/$name
        rm -rf "$out"
        tile_size=0
        [ "$tiled" = tiled ] && tile_size=$tile_m
        cfg=$work/runs/$name.yaml
        mkdir -p "$work/runs"
        cat >"$cfg" <<EOF
$crs_line
input: {format: colmap, path: $dir}
output: {dir: $out$format_key}
fusion: {method: $method}
tiling: {tile_size_m: $tile_size}
resources: {threads: $threads}
EOF
        start=$(date +%s.%N)
        if ! "$bin" run "$cfg" >"$work/runs/$name.log" 2>&1; then
          echo "$name: run failed (see $work/runs/$name.log)" >&2
          echo "$name FAILED" >>"$results"
          continue
        fi
        secs=$(python3 -c "import time; print(f'{time.time() - $start:.1f}')")
        echo "$name $(las_digest "$out/fused.las")" >>"$results"
        for raster in dsm.tif ortho.tif; do  # with CRS: the raster products, byte for byte
          if [ -f "$out/$raster" ]; then
            echo "$name.$raster $(sha256sum <"$out/$raster" | cut -d' ' -f1) $(stat -c %s "$out/$raster")" >>"$results"
          fi
        done
        echo "$name: ${secs} s" >&2
      done
    done
  done
done

if [ "$mode" = record ]; then
  cp "$results" "$baseline"
  echo "recorded $(wc -l <"$baseline") outputs in $baseline"
  exit 0
fi
# Compare the runs made now (METHODS x BLOCKS) with their baseline lines; a run without one is a difference.
expected=$(mktemp)
trap 'rm -f "$results" "$expected"' EXIT
while read -r name _; do
  grep "^$name " "$baseline" >>"$expected" || echo "$name (no baseline)" >>"$expected"
done <"$results"
if diff <(sort "$expected") <(sort "$results"); then
  echo "identical: $(wc -l <"$results") outputs match $baseline"
else
  echo "DIFFERENT: the outputs above differ from $baseline (< baseline, > now)"
  exit 1
fi
