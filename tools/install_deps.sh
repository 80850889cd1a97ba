#!/usr/bin/env bash
# Installs the Debian packages sacfuse needs. Idempotent; run as root (or with sudo).
#   tools/install_deps.sh          everything: --test, plus the optional benchmark packages (warn-only); CI runs this;
#   tools/install_deps.sh --test   building and the whole test suite (tools/test.sh runs this first; with every
#                                  package present it only checks, no apt-get and no sudo);
#   tools/install_deps.sh --build  only what configuring, building and running sacfuse needs (tools/demo.sh): no
#                                  Chromium, Node.js/npm, GNU parallel, COLMAP -- on a fresh Debian 12 these are most
#                                  of the download and unpack time, and only the tests and benchmarks use them.
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
MODE=all
case "${1:-}" in
  --build) MODE=build ;;
  --test) MODE=test ;;
  "") ;;
  *) echo "usage: tools/install_deps.sh [--build | --test]" >&2; exit 2 ;;
esac
PKGS=(
  build-essential cmake pkg-config
  libeigen3-dev            # linear algebra, camera geometry
  libopencv-dev libopencv-contrib-dev   # images; ximgproc (SLIC) lives in contrib
  libproj-dev proj-data    # PROJ: the project CRS, geodetic conversions, geoid grids, WKT (io/crs); proj-data holds
                           # proj.db, which PROJ reads at run time
  libtbb-dev               # task parallelism
  libyaml-cpp-dev          # config
  libcli11-dev             # command line
  libspdlog-dev            # logging
  nlohmann-json3-dev       # metadata, reports
  libnanoflann-dev         # kd-trees (eval, correspondences)
  libtiff-dev              # depth rasters
  libgdal-dev              # raster products: the DSM as a Cloud Optimized GeoTIFF, VRT mosaics (io/gdal_raster)
  libgtest-dev libgmock-dev # tests; CMake's configure looks for GoogleTest (SACFUSE_TESTS=ON), so --build has them
)
TEST_PKGS=(
  parallel                 # GNU parallel: running `sacfuse tile` workers (tests/queue_e2e_test.cc)
  chromium                 # tests only: headless screenshot of the HTML run report (tests/report_e2e_test.cc)
  gdal-bin proj-bin        # tests only: gdalsrsinfo and projinfo read back the CRS we write (tests/crs_e2e_test.cc)
  python3-gdal             # tests only: GDAL's COG validator and an independent reader of the DSM (tests/dsm_e2e_test.cc);
                           # also ../shared/aerial-bench/score_dsm.py (sacfuse bench --aerial-bench)
)
if [ "$MODE" != build ]; then PKGS+=("${TEST_PKGS[@]}"); fi
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "[install_deps] installing: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  UPDATED=1
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "[install_deps] all packages present"
fi
if [ "$MODE" = build ]; then exit 0; fi

# Optional: benchmarks (tools/bench, `sacfuse colmap-fusion`, tools/bench/compare_colmap.sh): COLMAP's
# stereo_fusion as the comparison method, GNU time for peak RSS, jq to read the JSON reports; the package check
# (tools/check_deb.sh): debootstrap; fuzzing (tools/fuzz.sh): clang with libFuzzer and the sanitizer runtimes. Building and the test suite do not need them
# (the COLMAP test skips without it; tools/sanitize.sh uses the default compiler's sanitizers), so a package the
# archive lacks (colmap is in Debian main for amd64/arm64 but not on every architecture or derivative) or a failed
# install only warns.
OPTIONAL_PKGS=(
  colmap                   # COLMAP 3.8 (CPU build): stereo_fusion, the comparison of issue 4
  time                     # /usr/bin/time -v: wall time and peak RSS of `sacfuse run` in compare_colmap.sh
  jq                       # reading run_report.json / eval.json in compare_colmap.sh
  debootstrap              # tools/check_deb.sh: a fresh Debian 12 root to install the .deb into (tools/package_deb.sh
                           # needs only dpkg-dev, which build-essential brings)
  clang                    # tools/fuzz.sh: the libFuzzer targets of tests/fuzz are built with clang
  libclang-rt-14-dev       # tools/fuzz.sh: libFuzzer, ASan and UBSan runtimes of clang 14 (Debian 12)
  python3-numpy python3-scipy python3-opencv python3-open3d  # sacfuse bench --aerial-bench: ../shared/aerial-bench's
                           # make_block.py, peers.py and score.py (run with /usr/bin/python3)
)
if [ "$MODE" = all ] && [ "${SACFUSE_SKIP_OPTIONAL:-0}" != "1" ]; then
  not_installed=()
  for p in "${OPTIONAL_PKGS[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || not_installed+=("$p")
  done
  if [ ${#not_installed[@]} -gt 0 ] && [ "${UPDATED:-0}" != "1" ]; then
    $SUDO apt-get update -qq || true
  fi
  optional_missing=()
  for p in ${not_installed[@]+"${not_installed[@]}"}; do
    if apt-cache show "$p" >/dev/null 2>&1; then
      optional_missing+=("$p")
    else
      echo "[install_deps] optional package $p is not available here; skipping it (only benchmarks or fuzzing need it)"
    fi
  done
  if [ ${#optional_missing[@]} -gt 0 ]; then
    echo "[install_deps] installing optional benchmark and fuzzing packages: ${optional_missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    if ! $SUDO apt-get install -y -qq --no-install-recommends "${optional_missing[@]}"; then
      echo "[install_deps] WARNING: could not install ${optional_missing[*]}; benchmarks against COLMAP and" \
           "tools/fuzz.sh will skip or fail, everything else works (set SACFUSE_SKIP_OPTIONAL=1 to skip this step)" >&2
    fi
  fi
fi

# Test-time only: Node.js + npm and the npm packages of tests/las_js -- independent LAS/LAZ readers
# (@loaders.gl/las with laz-rs, and laz-perf; pinned in tests/las_js/package-lock.json) that
# tests/las_js_reader_test.cc runs on the files we write; never used at run time. Debian's nodejs and npm are installed only when node or npm is missing (a
# machine that already has Node.js keeps it). `npm ci` runs again only when package-lock.json changed.
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  echo "[install_deps] installing nodejs npm (test-time LAS reader)"
  export DEBIAN_FRONTEND=noninteractive
  if [ "${UPDATED:-0}" != "1" ]; then $SUDO apt-get update -qq; fi
  $SUDO apt-get install -y -qq --no-install-recommends nodejs npm
fi
LAS_JS_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/tests/las_js"
if [ -f "$LAS_JS_DIR/node_modules/@loaders.gl/las/package.json" ] &&
   [ "$LAS_JS_DIR/node_modules/.package-lock.json" -nt "$LAS_JS_DIR/package-lock.json" ]; then
  echo "[install_deps] tests/las_js npm packages present"
else
  echo "[install_deps] npm ci --prefix tests/las_js (test-time LAS reader)"
  npm ci --prefix "$LAS_JS_DIR" --no-audit --no-fund
fi
