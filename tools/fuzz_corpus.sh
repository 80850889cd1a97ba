#!/usr/bin/env bash
# Seed corpora of the fuzz targets (tests/fuzz/fuzz_readers.h), written to DIR/<target>/ (outside the repo):
# files the simulator writes for a `tiny` block, in every input format `sacfuse convert` produces, plus the
# LAS and TIFF files of ../shared/research-data (read only; never copied into the repo). Files over 1 MiB are cut
# to their first 1 MiB (a truncated file is a useful seed too and keeps the fuzzers fast). Seeds are named by
# their content hash.
# Usage: tools/fuzz_corpus.sh DIR   (needs build/bin/sacfuse: cmake --build build --target sacfuse)
set -eu  # no pipefail: `find | head` closes its pipe early on purpose
cd "$(dirname "$0")/.."
out=${1:?usage: tools/fuzz_corpus.sh DIR}
sacfuse=${SACFUSE_BIN:-build/bin/sacfuse}
shared=${SACFUSE_SHARED:-../shared}/research-data
[ -x "$sacfuse" ] || { echo "fuzz_corpus: $sacfuse missing (cmake --build build --target sacfuse)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sep=$'\n#--sacfuse-fuzz-next-file--\n'  # tests/fuzz/fuzz_readers.h kFileSeparator

seed() {  # seed TARGET FILE: copies FILE (at most 1 MiB of it) into the target's corpus
  mkdir -p "$out/$1"
  head -c 1048576 "$2" > "$out/$1/tmp"
  mv "$out/$1/tmp" "$out/$1/$(sha1sum "$out/$1/tmp" | cut -c1-16)"
}

"$sacfuse" simulate --preset tiny --out "$work/sim" > "$work/simulate.log"
colmap=$(dirname "$(find "$work/sim" -path '*/sparse/cameras.*' | head -1)")/..
config=$(find "$work/sim" -maxdepth 2 -name '*.yaml' | head -1)
for to in openmvs rasters; do "$sacfuse" convert "$config" --to "$to" --out "$work/$to" > /dev/null; done

# COLMAP models: cameras, images and points3D in one input (text and binary; each form of the simulated model).
for ext in bin txt; do
  if [ -f "$colmap/sparse/cameras.$ext" ]; then
    target=$([ "$ext" = bin ] && echo colmap_binary || echo colmap_text)
    mkdir -p "$out/$target"
    { cat "$colmap/sparse/cameras.$ext"; printf '%s' "$sep"; cat "$colmap/sparse/images.$ext"; printf '%s' "$sep"
      head -c 65536 "$colmap/sparse/points3D.$ext"; } > "$out/$target/sim_model"
  fi
done
for maps in depth_maps normal_maps; do
  find "$colmap/stereo/$maps" -name '*.bin' | sort | head -3 | while read -r f; do seed colmap_array "$f"; done
done
find "$work/openmvs" -name '*.dmap' | head -4 | while read -r f; do seed openmvs_dmap "$f"; done
find "$work/rasters" -name '*.tif' | head -4 | while read -r f; do seed tiff_depth "$f"; done
find "$work/rasters" "$work/sim" \( -name '*.yaml' -o -name '*.yml' \) | while read -r f; do
  case "$f" in */cameras.y*) seed camera_yaml "$f" ;; *) seed job_config "$f" ;; esac
done
find "$work" -name '*.csv' | head -4 | while read -r f; do seed camera_csv "$f"; done
find "$work" -name '*.las' | head -4 | while read -r f; do seed las "$f"; done
# Superpixel caches of a run over the simulated block (the banded 16-bit layout).
if "$sacfuse" run "$config" --threads 2 > "$work/run.log" 2>&1; then
  find "$work/sim" -name '*.spx' | sort | head -3 | while read -r f; do seed superpixel_cache "$f"; done
else
  echo "fuzz_corpus: the run for superpixel seeds failed (see $work/run.log); no superpixel_cache seeds" >&2
fi
# The default config, every key with its comment.
"$sacfuse" run --print-defaults > "$work/defaults.yaml" 2>/dev/null && seed job_config "$work/defaults.yaml" || true

# Small hand-made seeds of what the simulator does not write: a COLMAP text model, a CSV camera file, a 4 x 3
# dense array (the simulator's are cut to 1 MiB, so their size no longer matches their header).
mkdir -p "$out/colmap_text" "$out/camera_csv" "$out/colmap_array"
{ printf '# Camera list\n1 PINHOLE 640 480 500 500 320 240\n2 SIMPLE_RADIAL 640 480 510 320 240 0\n%s' "$sep"
  printf '# Image list\n1 0 1 0 0 -5 2 100 1 nadir_1.jpg\n10 20 1 30.5 40 -1\n'
  printf '2 0.0087 0.9999 0 0 5 2 100 2 sub/nadir_2.jpg\n\n%s' "$sep"
  printf '# 3D point list\n1 5 -2 0.5 200 100 50 0.3 1 0 2 0\n'; } > "$out/colmap_text/hand_model"
cat > "$out/camera_csv/hand_cameras" <<'CSV'
# a hand-made example
image,depth,image_path,width_px,height_px,focal_px,cx_px,cy_px,x_m,y_m,z_m,omega_deg,phi_deg,kappa_deg
a.jpg,depth.tif,,16,12,20,8,6,390512.25,5705130.5,1065,0.5,-1.25,90
"b,c.jpg",depth.tif,,16,12,20,,,390612.25,5705130.5,1066,0,0,0
CSV
printf 'image,depth,width_px,height_px,focal_mm,pixel_size_um,ppx_mm,ppy_mm,lat_deg,lon_deg,h_m,r11,r12,r13,r21,r22,r23,r31,r32,r33,attitude_frame\ne.jpg,depth.tif,16,12,50,6,0.01,-0.01,51.5,7.4,1100,1,0,0,0,1,0,0,0,1,local_enu\n' \
  > "$out/camera_csv/hand_geodetic"
{ printf '4&3&1&'; head -c 48 /dev/zero | tr '\0' 'B'; } > "$out/colmap_array/hand_4x3"

if [ -d "$shared" ]; then
  find "$shared" -name '*.las' -size -2M | head -40 | while read -r f; do seed las "$f"; done
  find "$shared" \( -name '*.tif' -o -name '*.tiff' \) | head -8 | while read -r f; do seed tiff_depth "$f"; done
else
  echo "fuzz_corpus: $shared absent; seeds from the simulator only" >&2
fi
for d in "$out"/*/; do echo "fuzz_corpus: $(basename "$d"): $(ls "$d" | wc -l) seeds"; done
