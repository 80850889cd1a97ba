#!/usr/bin/env bash
# Installs every Debian package sacfuse needs to build and test. Idempotent; run as root (or with sudo).
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
PKGS=(
  build-essential cmake pkg-config
  libeigen3-dev            # linear algebra, camera geometry
  libopencv-dev libopencv-contrib-dev   # images; ximgproc (SLIC) lives in contrib
  libgeographiclib-dev     # UTM / geodetic conversions
  libtbb-dev               # task parallelism
  libyaml-cpp-dev          # config
  libcli11-dev             # command line
  libspdlog-dev            # logging
  nlohmann-json3-dev       # metadata, reports
  libnanoflann-dev         # kd-trees (eval, correspondences)
  libtiff-dev              # depth rasters
  libgtest-dev libgmock-dev # tests
  parallel                 # GNU parallel: running `sacfuse tile` workers (tests/queue_e2e_test.cc)
)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "[install_deps] installing: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "[install_deps] all packages present"
fi
