#!/usr/bin/env bash
# Builds the Debian package of sacfuse with CPack (cmake/Install.cmake): a Release build without the tests in
# build-deb/ (or $SACFUSE_BUILD_DIR; ccache makes it quick after tools/build.sh), installed under /usr, the binary
# stripped, the package's dependencies found by dpkg-shlibdeps from the shared libraries the binary links. Prints
# the package's path, size and fields.
#
#   tools/package_deb.sh          -> build-deb/sacfuse_<version>_<arch>.deb
#
# Needs dpkg-dev (dpkg-shlibdeps; build-essential brings it) and the build packages (tools/install_deps.sh --build).
# Check the package in a fresh Debian 12 root with tools/check_deb.sh. The Maintainer field is
# -DSACFUSE_PACKAGE_CONTACT="Name <email>" (passed through: tools/package_deb.sh -DSACFUSE_PACKAGE_CONTACT=...).
set -euo pipefail
cd "$(dirname "$0")/.."
command -v dpkg-shlibdeps >/dev/null || { echo "$0: dpkg-shlibdeps not found (Debian package dpkg-dev)" >&2; exit 2; }
build=${SACFUSE_BUILD_DIR:-build-deb}
SACFUSE_BUILD_DIR=$build tools/build.sh --target sacfuse --target sacfuse_man -DSACFUSE_TESTS=OFF \
  -DCMAKE_INSTALL_PREFIX=/usr "$@"
(cd "$build" && cpack -G DEB >/dev/null)
version=$(sed -n 's/^project(sacfuse VERSION \([0-9.]*\).*/\1/p' CMakeLists.txt)
deb=$build/sacfuse_${version}_$(dpkg --print-architecture).deb
[[ -f $deb ]] || { echo "$0: cpack did not write $deb" >&2; exit 1; }
echo "package: $deb ($(du -k "$deb" | cut -f1) KiB)"
dpkg-deb --field "$deb" Package Version Architecture Installed-Size Depends
