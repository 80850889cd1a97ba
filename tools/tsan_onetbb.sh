#!/usr/bin/env bash
# Builds oneTBB with ThreadSanitizer from Debian's own source package (the version of the installed libtbb-dev) and
# installs it into PREFIX (default build-tsan/onetbb). tools/sanitize.sh tsan links the tests against it: with
# Debian's uninstrumented libtbb, TSan cannot see TBB's own synchronisation and reports races inside the library
# (false positives, docs/development.md, "Sanitizers").
#   tools/tsan_onetbb.sh [PREFIX]
# Needs deb-src entries for apt (`apt-get source`); tools/install_deps.sh does not add them. ~3 CPU minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
prefix=$(realpath -m "${1:-build-tsan/onetbb}")
if [ -f "$prefix/lib/cmake/TBB/TBBConfig.cmake" ] && [ -f "$prefix/.sacfuse-tsan-version" ]; then
  echo "tsan_onetbb: $prefix already holds oneTBB $(cat "$prefix/.sacfuse-tsan-version") built with TSan"
  exit 0
fi
version=$(dpkg-query -W -f='${Version}' libtbb-dev 2>/dev/null) || {
  echo "tsan_onetbb: libtbb-dev is not installed (tools/install_deps.sh)" >&2
  exit 2
}
work="$prefix.src"
rm -rf "$work"
mkdir -p "$work"
cd "$work"
if ! apt-get source --download-only "onetbb=$version" > apt-source.log 2>&1; then
  echo "tsan_onetbb: 'apt-get source onetbb=$version' failed (see $work/apt-source.log); it needs a deb-src line" \
       "for the Debian release, e.g. 'Types: deb-src' in /etc/apt/sources.list.d/, then apt-get update" >&2
  exit 2
fi
dpkg-source -x ./*.dsc src > dpkg-source.log
cmake -S src -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTBB_SANITIZE=thread -DTBB_TEST=OFF -DTBB_STRICT=OFF \
  -DTBB_EXAMPLES=OFF -DTBBMALLOC_BUILD=OFF -DCMAKE_INSTALL_PREFIX="$prefix" > cmake.log
cmake --build build -j"$(nproc 2>/dev/null || echo 2)" > build.log 2>&1 || {
  echo "tsan_onetbb: build failed, see $work/build.log" >&2
  exit 1
}
cmake --install build > install.log
echo "$version" > "$prefix/.sacfuse-tsan-version"
echo "tsan_onetbb: oneTBB $version with TSan in $prefix"
