#!/usr/bin/env bash
# Installs the Debian package into a fresh Debian 12 root and uses it there, as a user on a new machine would:
# prints PASS or FAIL for each step and at the end (exit 0 only when every step passed).
#
#   tools/check_deb.sh DEB CACHE_DIR
#
# CACHE_DIR keeps bookworm-minbase.tar, a `debootstrap --variant=minbase bookworm` root made on the first call
# (a few minutes); later calls unpack it in seconds. Each call unpacks it into a new folder ($CHECK_DEB_WORK, default
# a temporary folder under CACHE_DIR; removed at the end unless KEEP=1), adds Debian's bookworm-updates and
# security suites as a new install has them, then inside the root (chroot, with /proc and /dev mounted):
#   apt-get update; apt-get install --no-install-recommends ./sacfuse_*.deb   (dependencies from the mirror: the
#     package's Depends alone must be enough)
#   sacfuse --version; man page and docs present; sacfuse simulate --preset tiny; sacfuse run; sacfuse validate
# Needs root, debootstrap and access to the Debian mirror (MIRROR, default http://deb.debian.org/debian). Not a
# test of the default suite (network, root, minutes).
set -euo pipefail
[[ $# -eq 2 ]] || { sed -n '2,15p' "$0" >&2; exit 2; }
deb=$(realpath "$1")
cache=$2
mirror=${MIRROR:-http://deb.debian.org/debian}
[[ -f $deb ]] || { echo "$0: no such package: $1" >&2; exit 2; }
[[ $(id -u) -eq 0 ]] || { echo "$0: needs root (debootstrap, chroot, mount)" >&2; exit 2; }
command -v debootstrap >/dev/null || { echo "$0: debootstrap not found (Debian package debootstrap)" >&2; exit 2; }
mkdir -p "$cache"
cache=$(realpath "$cache")
tarball=$cache/bookworm-minbase.tar
start=$(date +%s)
failed=0
log=$cache/check_deb.log  # every step's output; the tail is shown when a step fails
: > "$log"
step() {  # step NAME COMMAND...: runs COMMAND (output to $log), prints PASS/FAIL with its seconds
  local name=$1 t0 rc
  shift
  t0=$(date +%s)
  echo "== $name" >> "$log"
  if "$@" >> "$log" 2>&1; then rc=0; else rc=$?; fi
  if [[ $rc -eq 0 ]]; then echo "PASS  $name ($(( $(date +%s) - t0 )) s)"; else
    echo "FAIL  $name (exit $rc, $(( $(date +%s) - t0 )) s); the end of $log:"; tail -n 20 "$log"; failed=1; fi
  return $rc
}

if [[ ! -f $tarball ]]; then
  echo "making $tarball (debootstrap --variant=minbase bookworm $mirror; done once)"
  fresh=$(mktemp -d "$cache/debootstrap.XXXXXX")
  step "debootstrap" debootstrap --variant=minbase bookworm "$fresh" "$mirror" || { rm -rf "$fresh"; exit 1; }
  tar -C "$fresh" -cf "$tarball.tmp" . && mv "$tarball.tmp" "$tarball"
  rm -rf "$fresh"
fi

work=${CHECK_DEB_WORK:-$(mktemp -d "$cache/root.XXXXXX")}
root=$work/root
mkdir -p "$root"
cleanup() {
  for m in dev/pts dev proc; do if mountpoint -q "$root/$m"; then umount -l "$root/$m"; fi; done
  # Never delete through a mount that is still there (the host's /dev): keep the folder then.
  if grep -q " $root/" /proc/mounts; then echo "$0: $root still has mounts; not removing $work" >&2; return; fi
  [[ ${KEEP:-0} == 1 ]] || rm -rf --one-file-system "$work"
}
trap cleanup EXIT
step "unpack the Debian 12 root" tar -C "$root" -xf "$tarball"
mount -t proc proc "$root/proc"
mount --bind /dev "$root/dev"
mount --bind /dev/pts "$root/dev/pts"
cp /etc/resolv.conf "$root/etc/resolv.conf"
cat > "$root/etc/apt/sources.list" <<SOURCES
deb $mirror bookworm main
deb $mirror bookworm-updates main
deb ${SECURITY_MIRROR:-http://deb.debian.org/debian-security} bookworm-security main
SOURCES
cp "$deb" "$root/tmp/"
name=$(basename "$deb")
in_root() { chroot "$root" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root LANG=C.UTF-8 \
  DEBIAN_FRONTEND=noninteractive "$@"; }

step "apt-get update" in_root apt-get update -qq || exit 1
step "apt install ./$name" in_root sh -c "cd /tmp && apt-get install -y -qq --no-install-recommends ./$name" || exit 1
echo "      installed: $(in_root dpkg-query -W -f='${Package} ${Version}, ${Installed-Size} KiB' sacfuse); root now" \
  "$(du -smx "$root" | cut -f1) MiB"
step "sacfuse --version" in_root sacfuse --version && echo "      $(in_root sacfuse --version)"
step "man page and docs installed" in_root sh -c 'test -s /usr/share/man/man1/sacfuse.1.gz &&
  test -s /usr/share/doc/sacfuse/README.md && test -s /usr/share/doc/sacfuse/copyright &&
  test -s /usr/share/doc/sacfuse/docs/configuration.md && test -s /usr/share/doc/sacfuse/docs/cli.md' || true
step "sacfuse simulate --preset tiny" in_root sacfuse simulate --preset tiny --out /tmp/block || true
step "sacfuse run" in_root sacfuse run /tmp/block/sacfuse.yaml || true
grep -E "^fused cloud:|F1 @" "$log" | sed 's/^/      /' || true
step "sacfuse validate fused.laz" in_root sacfuse validate /tmp/block/out/fused.laz || true
echo "$([[ $failed -eq 0 ]] && echo PASS || echo FAIL): $name in a fresh Debian 12 root," \
  "$(( $(date +%s) - start )) s in all"
exit $failed
