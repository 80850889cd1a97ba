#!/usr/bin/env bash
# Builds sacfuse and its tests with sanitizers into their own build folder and runs the suite there.
#   tools/sanitize.sh asan [CTEST_REGEX]   ASan + UBSan (build-asan/): the whole suite, or the tests matching the
#                                          regex (e.g. 'config|io|tiling')
#   tools/sanitize.sh tsan [CTEST_REGEX]   TSan (build-tsan/): the tiled and threaded tests (default regex below),
#                                          linked against oneTBB built with TSan from Debian's source package
#                                          (tools/tsan_onetbb.sh, into build-tsan/onetbb; or an existing one given
#                                          as SACFUSE_TSAN_TBB_DIR=PREFIX)
# A sanitizer report aborts the test (no recovery), so any finding fails CTest. A full ASan build takes ~15-20
# CPU minutes; the suite runs 2-5x slower than in Release. SACFUSE_SANITIZE_JOBS sets the build parallelism.
set -euo pipefail
cd "$(dirname "$0")/.."
kind=${1:?usage: tools/sanitize.sh asan|tsan [CTEST_REGEX]}
case "$kind" in
  asan) sanitize=address,undefined dir=build-asan regex=${2:-} ;;
  tsan)
    sanitize=thread dir=build-tsan
    regex=${2:-'tiling/|tiles/|io/laz_writer|core/sac_fusion|core/point_verdicts|tools/sim/simulate|tests/(tiling|queue|resume|run_state)_e2e'}
    ;;
  *) echo "sanitize: unknown kind $kind (asan or tsan)" >&2; exit 2 ;;
esac
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
extra=()
if [ "$kind" = tsan ]; then
  # TSan sees only instrumented code: TBB's own synchronisation must be compiled with it too.
  tbb_prefix=${SACFUSE_TSAN_TBB_DIR:-$dir/onetbb}
  [ -n "${SACFUSE_TSAN_TBB_DIR:-}" ] || tools/tsan_onetbb.sh "$tbb_prefix"
  extra=(-DTBB_DIR="$(realpath "$tbb_prefix")/lib/cmake/TBB")
fi
cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSACFUSE_SANITIZE="$sanitize" "${launcher[@]}" "${extra[@]}" \
  > /dev/null
jobs=${SACFUSE_SANITIZE_JOBS:-$(nproc 2>/dev/null || echo 2)}
if [ -n "$regex" ]; then
  # Only the test executables the regex selects, plus the sacfuse binary when an end-to-end test (tests/, tools/)
  # is among them (they run it).
  mapfile -t names < <(ctest --test-dir "$dir" -N -R "$regex" 2>/dev/null | sed -n 's/^ *Test *#[0-9]*: //p')
  [ ${#names[@]} -gt 0 ] || { echo "sanitize: no test matches $regex" >&2; exit 2; }
  mapfile -t targets < <(printf '%s\n' "${names[@]}" | sed 's|^tests/|tests_|; s|/|_|g' | sort -u)
  if printf '%s\n' "${names[@]}" | grep -v '^tests/fuzz_regression_test$' | grep -q '^tests/\|^tools/'; then
    targets+=(sacfuse)
  fi
  cmake --build "$dir" -j"$jobs" --target "${targets[@]}"
  args=(-R "$regex")
else
  cmake --build "$dir" -j"$jobs"
  args=()
fi
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export TSAN_OPTIONS=${TSAN_OPTIONS:-halt_on_error=1:second_deadlock_stack=1:suppressions=$PWD/tools/tsan.supp}
ctest --test-dir "$dir" --output-on-failure -j"$jobs" --timeout 3600 "${args[@]}"
