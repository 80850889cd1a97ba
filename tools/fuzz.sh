#!/usr/bin/env bash
# Fuzzes every reader of user files (tests/fuzz): builds the libFuzzer targets with clang, ASan and UBSan into
# build-fuzz/, makes seed corpora (tools/fuzz_corpus.sh) on first use, then runs each target for MINUTES (default
# 10), one at a time and niced, and prints per target the executions, the corpus size and the findings (crash,
# sanitizer report, timeout > 10 s, out of memory > 2 GB: libFuzzer's crash-*/timeout-*/oom-*/leak-* files).
# Corpora and findings live outside the repo in $SACFUSE_FUZZ_DIR (default ../scratch/fuzz). A finding is fixed,
# then its file is kept as a regression test: tests/fuzz/regressions/<target>/ (tests/fuzz_regression_test).
# Usage: tools/fuzz.sh [MINUTES] [TARGET...]   (targets: tests/fuzz/CMakeLists.txt; default all)
# Exit status: 0 when no target had a finding, 1 otherwise.
set -euo pipefail
cd "$(dirname "$0")/.."
minutes=${1:-10}
shift || true
fuzz_dir=${SACFUSE_FUZZ_DIR:-$(cd .. && pwd)/scratch/fuzz}
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(colmap_text colmap_binary colmap_array openmvs_dmap tiff_depth camera_yaml camera_csv las job_config
           superpixel_cache)
fi
command -v clang++ >/dev/null || { echo "fuzz: clang++ missing (tools/install_deps.sh installs it)" >&2; exit 2; }

launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ -DSACFUSE_FUZZ=ON \
  -DSACFUSE_TESTS=OFF "${launcher[@]}" > /dev/null
nice -n 15 cmake --build build-fuzz -j"${SACFUSE_FUZZ_JOBS:-2}" --target "${targets[@]/#/fuzz_}"

if [ ! -d "$fuzz_dir/seeds" ]; then
  [ -x build/bin/sacfuse ] || nice -n 15 cmake --build build -j2 --target sacfuse
  tools/fuzz_corpus.sh "$fuzz_dir/seeds"
fi

status=0
printf '\n%-14s %8s %12s %8s %8s  %s\n' target minutes executions corpus findings files
for t in "${targets[@]}"; do
  corpus="$fuzz_dir/corpus/$t" findings="$fuzz_dir/findings/$t" log="$fuzz_dir/logs/$t.log"
  mkdir -p "$corpus" "$findings" "$(dirname "$log")" "$fuzz_dir/seeds/$t"
  touch "$log.start"  # findings newer than this are this run's
  # -rss_limit_mb / -malloc_limit_mb: a reader that allocates more than 2 GB for a small file is a finding.
  nice -n 15 build-fuzz/tests/fuzz/fuzz_"$t" "$corpus" "$fuzz_dir/seeds/$t" -max_total_time=$((minutes * 60)) \
    -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$findings/" \
    > "$log" 2>&1 || true
  execs=$(grep -o 'stat::number_of_executed_units: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*$' || echo '?')
  found=$(find "$findings" -type f \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) \
    -newer "$log.start" 2>/dev/null | wc -l || true)
  printf '%-14s %8s %12s %8s %8s  %s\n' "$t" "$minutes" "${execs:-?}" "$(ls "$corpus" | wc -l)" "$found" \
    "$(find "$findings" -type f -newer "$log.start" 2>/dev/null | tr '\n' ' ')"
  [ "$found" -eq 0 ] || status=1
done
echo "logs: $fuzz_dir/logs/<target>.log"
exit $status
