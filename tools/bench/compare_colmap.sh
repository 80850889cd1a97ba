#!/usr/bin/env bash
# Side-by-side benchmark of sacfuse and COLMAP's stereo_fusion on one simulated block (issue 4).
#
#   tools/bench/compare_colmap.sh BLOCK_DIR [THREADS] [OUT_DIR]
#
# BLOCK_DIR is a block written by `sacfuse simulate` (its sacfuse.yaml names the workspace, the reference and the
# evaluation settings). THREADS defaults to the number of cores; OUT_DIR to BLOCK_DIR/compare_colmap. The block is
# only read: its config runs with --output-dir OUT_DIR/sacfuse; OUT_DIR/sacfuse and OUT_DIR/colmap are recreated on
# every call (so sacfuse starts cold, without cached superpixels).
#
# Runs, one after the other:
#   /usr/bin/time -v sacfuse run BLOCK_DIR/sacfuse.yaml --output-dir OUT_DIR/sacfuse --threads THREADS
#   /usr/bin/time -v sacfuse colmap-fusion BLOCK_DIR/sacfuse.yaml --out OUT_DIR/colmap --threads THREADS
# and prints a Markdown table (also written to OUT_DIR/compare.md). Columns:
#   wall s, peak RSS MiB  the fusion itself: sacfuse from run_report.json (reading the workspace to fused.las
#                         written; scoring comes after), COLMAP the stereo_fusion child process (reading the
#                         workspace to fused.ply written);
#   cmd wall s, cmd RSS   the whole command under /usr/bin/time -v, scoring included (colmap-fusion also shifts
#                         the model and converts fused.ply to LAS; its RSS is the larger of COLMAP's and its own);
#   F1                    density-normalised F1 (%) from each run's eval.json, scored identically.
#
# Environment: SACFUSE (default: build/bin/sacfuse of this checkout, else sacfuse on PATH), COLMAP (default colmap),
# COLMAP_ARGS (more options for `sacfuse colmap-fusion`: "--use-cache" keeps at most resources.memory_gb of maps in
# memory, and COLMAP then fuses on one thread; "--stereo-fusion max_normal_error=180" sets any StereoFusion option).
# Needs /usr/bin/time (Debian: time) and jq; tools/install_deps.sh installs both with colmap.
set -euo pipefail

usage() { echo "usage: $0 BLOCK_DIR [THREADS] [OUT_DIR]" >&2; exit 2; }
[ $# -ge 1 ] && [ $# -le 3 ] || usage
BLOCK=$(cd "$1" && pwd) || { echo "$0: no such block folder: $1" >&2; exit 2; }
THREADS=${2:-$(nproc)}
OUT=${3:-$BLOCK/compare_colmap}
CONFIG=$BLOCK/sacfuse.yaml
[ -f "$CONFIG" ] || { echo "$0: $CONFIG not found (a block written by \`sacfuse simulate\` has one)" >&2; exit 2; }
case "$THREADS" in '' | *[!0-9]*) echo "$0: THREADS must be a number, not '$THREADS'" >&2; exit 2 ;; esac

REPO=$(cd "$(dirname "$0")/../.." && pwd)
SACFUSE=${SACFUSE:-}
if [ -z "$SACFUSE" ]; then
  if [ -x "$REPO/build/bin/sacfuse" ]; then SACFUSE=$REPO/build/bin/sacfuse; else SACFUSE=$(command -v sacfuse || true); fi
fi
[ -n "$SACFUSE" ] && [ -x "$SACFUSE" ] || { echo "$0: sacfuse binary not found; build it or set SACFUSE" >&2; exit 2; }
COLMAP=${COLMAP:-colmap}
command -v "$COLMAP" >/dev/null || { echo "$0: COLMAP binary '$COLMAP' not found (apt-get install colmap, or set COLMAP)" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "$0: /usr/bin/time not found (Debian package: time)" >&2; exit 2; }
command -v jq >/dev/null || { echo "$0: jq not found (Debian package: jq)" >&2; exit 2; }

mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
rm -rf "$OUT/sacfuse" "$OUT/colmap"

NPROC=$(nproc)
echo "block $BLOCK, $THREADS threads ($NPROC cores), outputs in $OUT"
echo "sacfuse: $("$SACFUSE" version)   COLMAP: $("$COLMAP" -h 2>&1 | sed -n '/./{p;q}')"

tail_log() { echo "--- last lines of $1:" >&2; tail -n 20 "$1" >&2; }

LOAD_BEFORE=$(cut -d' ' -f1-3 /proc/loadavg)
echo "[1/2] sacfuse run ..."
if ! /usr/bin/time -v -o "$OUT/sacfuse_run.time" "$SACFUSE" run "$CONFIG" --output-dir "$OUT/sacfuse" --threads "$THREADS" \
    > "$OUT/sacfuse_run.log" 2>&1; then
  tail_log "$OUT/sacfuse_run.log"; echo "$0: sacfuse run failed" >&2; exit 1
fi
echo "[2/2] sacfuse colmap-fusion ..."
if ! /usr/bin/time -v -o "$OUT/colmap_fusion.time" "$SACFUSE" colmap-fusion "$CONFIG" --out "$OUT/colmap" \
    --threads "$THREADS" --colmap "$COLMAP" ${COLMAP_ARGS:-} > "$OUT/colmap_fusion.log" 2>&1; then
  tail_log "$OUT/colmap_fusion.log"; echo "$0: sacfuse colmap-fusion failed" >&2; exit 1
fi

# /usr/bin/time -v: "Elapsed (wall clock) time (h:mm:ss or m:ss): 1:02.33", "Maximum resident set size (kbytes): N"
time_wall() { awk -F': ' '/Elapsed \(wall clock\)/ { n = split($NF, p, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + p[i]; print s }' "$1"; }
time_rss() { awk -F': ' '/Maximum resident set size/ { print $NF / 1024 }' "$1"; }
# Primary F1 (%) at tau = k x GSD from an eval.json ("-" when the run was not scored).
f1_at() {
  [ -f "$1" ] || { echo "-"; return; }
  jq -r --argjson g "$GSD" --argjson k "$2" \
    '[.scores[] | select(((.tau_m / $g) - $k) | (. < 1e-6 and . > -1e-6)) | .f1] | if length > 0 then .[0] else "-" end' \
    "$1" | awk '/^-$/ { print; next } { printf "%.2f\n", 100 * $1 }'
}

LOAD_AFTER=$(cut -d' ' -f1-3 /proc/loadavg)
RUN_REPORT=$OUT/sacfuse/run_report.json
COLMAP_JSON=$OUT/colmap/colmap_fusion.json
GSD=$(jq -r '.evaluation.gsd_m // 0.1' "$COLMAP_JSON")
METHOD=$(jq -r '.method' "$RUN_REPORT")
C_METHOD="COLMAP stereo_fusion$(jq -r '[(if .options.use_cache then "use_cache, \(.options.cache_size_gb) GB" else empty end),
  ((.options.stereo_fusion // {}) | to_entries[] | "\(.key)=\(.value)")] | if length > 0 then " (" + join(", ") + ")" else "" end' "$COLMAP_JSON")"

S_WALL=$(jq -r '.wall_seconds' "$RUN_REPORT");  C_WALL=$(jq -r '.wall_s' "$COLMAP_JSON")
S_RSS=$(jq -r '.peak_rss_mib' "$RUN_REPORT");   C_RSS=$(jq -r '.peak_rss_mib' "$COLMAP_JSON")
S_PTS=$(jq -r '.output_points' "$RUN_REPORT");  C_PTS=$(jq -r '.points' "$COLMAP_JSON")
S_F2=$(f1_at "$OUT/sacfuse/eval.json" 2);       C_F2=$(f1_at "$OUT/colmap/eval.json" 2)
S_F5=$(f1_at "$OUT/sacfuse/eval.json" 5);       C_F5=$(f1_at "$OUT/colmap/eval.json" 5)
S_CWALL=$(time_wall "$OUT/sacfuse_run.time");   C_CWALL=$(time_wall "$OUT/colmap_fusion.time")
S_CRSS=$(time_rss "$OUT/sacfuse_run.time");     C_CRSS=$(time_rss "$OUT/colmap_fusion.time")
C_CPU=$(jq -r '.cpu_s' "$COLMAP_JSON");         S_CPU=$(jq -r '.cpu_seconds' "$RUN_REPORT")

ratio() { awk -v a="$1" -v b="$2" 'BEGIN { if (b > 0) printf "%.2f", a / b; else printf "-" }'; }
fmt() { awk -v v="$1" -v f="$2" 'BEGIN { printf f, v }'; }

{
  echo "| method | wall s | peak RSS MiB | points | F1@2×GSD | F1@5×GSD | CPU s | cmd wall s | cmd peak RSS MiB |"
  echo "|---|---|---|---|---|---|---|---|---|"
  echo "| sacfuse ($METHOD) | $(fmt "$S_WALL" %.1f) | $(fmt "$S_RSS" %.0f) | $S_PTS | $S_F2 | $S_F5 | $(fmt "$S_CPU" %.1f) | $(fmt "$S_CWALL" %.1f) | $(fmt "$S_CRSS" %.0f) |"
  echo "| $C_METHOD | $(fmt "$C_WALL" %.1f) | $(fmt "$C_RSS" %.0f) | $C_PTS | $C_F2 | $C_F5 | $(fmt "$C_CPU" %.1f) | $(fmt "$C_CWALL" %.1f) | $(fmt "$C_CRSS" %.0f) |"
  echo "| COLMAP / sacfuse | $(ratio "$C_WALL" "$S_WALL") | $(ratio "$C_RSS" "$S_RSS") | $(ratio "$C_PTS" "$S_PTS") | | | $(ratio "$C_CPU" "$S_CPU") | $(ratio "$C_CWALL" "$S_CWALL") | $(ratio "$C_CRSS" "$S_CRSS") |"
  echo
  echo "wall s / peak RSS: the fusion alone (sacfuse: run_report.json; COLMAP: the stereo_fusion process). cmd: the"
  echo "whole command under /usr/bin/time -v, scoring included. F1 in %, density-normalised, GSD $GSD m;"
  echo "$THREADS threads on $NPROC cores; load average before $LOAD_BEFORE, after $LOAD_AFTER."
  echo "COLMAP options: $(jq -r '.command[2:] | join(" ")' "$COLMAP_JSON")"
} | tee "$OUT/compare.md"
