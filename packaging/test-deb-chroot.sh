#!/bin/bash
# SPDX-License-Identifier: MIT
# Installs the Debian package in a fresh Debian 12 (bookworm) and uses it as a new user would:
# debootstrap --variant=minbase into a temporary folder, lintian on the package there (no error
# allowed; the warnings it keeps are explained in docs/packaging.md), `apt-get install
# ./smi-lua_*.deb` (its Depends pull the libraries), then from a home folder: the README's first
# study, `smi-lua doc smi.kde`, the man pages, the tutorial's solver study with smi-beam-solver
# from PATH, and the steering-column study on its committed data (--quick; set STUDY=dry-run for
# the cost plan only, STUDY=none to skip). Run on demand, as root; not in CI (it downloads about
# 150 MB and takes minutes).
#   bash packaging/test-deb-chroot.sh build/smi-lua_0.1.0-1_amd64.deb
# Environment: MIRROR (default: the Debian mirror of this machine's apt sources), KEEP=1 keeps the
# chroot folder, STUDY=quick|dry-run|none.
set -euo pipefail
[ $# -ge 1 ] && [ -f "$1" ] || { echo "usage: $0 path/to/smi-lua_VERSION_amd64.deb" >&2; exit 2; }
[ "$(id -u)" = 0 ] || { echo "$0: debootstrap and chroot need root" >&2; exit 2; }
command -v debootstrap > /dev/null || { echo "$0: needs debootstrap (apt-get install debootstrap)" >&2; exit 2; }
deb=$(realpath "$1")
src=$(cd "$(dirname "$0")/.." && pwd)
study=${STUDY:-quick}

# The mirror the machine already uses for bookworm (deb822 .sources or one-line sources.list).
machine_mirror() {
  cat /etc/apt/sources.list.d/*.sources 2> /dev/null | awk '
    /^URIs:/ { uri = $2 } /^Suites:/ && / bookworm( |$)/ && uri ~ /debian\/?$/ { print uri; exit }' || true
  cat /etc/apt/sources.list /etc/apt/sources.list.d/*.list 2> /dev/null | awk '
    $1 == "deb" && $3 == "bookworm" { print $2; exit }' || true
}
mirror=${MIRROR:-$(machine_mirror | head -n 1)}
mirror=${mirror:-http://deb.debian.org/debian}
echo "mirror: $mirror"

root=$(mktemp -d /var/tmp/smi-deb-chroot.XXXXXX)
cleanup() {
  umount "$root/proc" 2> /dev/null || true
  if [ "${KEEP:-0}" = 1 ]; then echo "chroot kept in $root"; else rm -rf "$root"; fi
}
trap cleanup EXIT

t0=$(date +%s)
debootstrap --variant=minbase bookworm "$root" "$mirror" > "$root.debootstrap.log" 2>&1 ||
  { tail -n 20 "$root.debootstrap.log"; exit 1; }
rm -f "$root.debootstrap.log"
echo "debootstrap: $(( $(date +%s) - t0 )) s, $(du -sm "$root" | cut -f1) MB"
mount -t proc proc "$root/proc"
cp "$deb" "$root/tmp/"
mkdir -p "$root/home/user"
bash "$src/tests/packaging/first_study.sh" "$src/README.md" > "$root/home/user/first.lua"

in_chroot() { chroot "$root" /usr/bin/env -i HOME=/home/user PATH=/usr/bin:/bin:/usr/sbin:/sbin LANG=C.UTF-8 /bin/bash -c "$1"; }

t0=$(date +%s)
in_chroot "apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq /tmp/$(basename "$deb")" > "$root/apt.log" 2>&1 ||
  { tail -n 30 "$root/apt.log"; exit 1; }
echo "apt-get install ./$(basename "$deb"): $(( $(date +%s) - t0 )) s; Depends: $(dpkg-deb -f "$deb" Depends)"

t0=$(date +%s)
in_chroot "DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends lintian" > "$root/lintian-install.log" 2>&1 ||
  { tail -n 30 "$root/lintian-install.log"; exit 1; }
echo "--- lintian $(basename "$deb") (installed in $(( $(date +%s) - t0 )) s)"
# lintian refuses to run as root unless told; --fail-on error: a warning is reported, an error fails.
in_chroot "lintian --allow-root --fail-on error --info /tmp/$(basename "$deb")" ||
  { echo "FAIL: lintian reports errors"; exit 1; }
echo "lintian: no error"

echo "--- cd ~ && smi-lua first.lua"
in_chroot "cd ~ && smi-lua first.lua"
echo "--- smi-lua doc smi.kde (first lines)"
in_chroot "cd ~ && smi-lua doc smi.kde | head -n 5"
echo "--- the man pages"
in_chroot "for p in smi-lua smi-column-fe smi-beam-solver; do zcat /usr/share/man/man1/\$p.1.gz | sed -n 3p; done"
echo "--- cd ~ && smi-lua --allow-exec smi-beam-solver /usr/share/smi-lua/scripts/tutorial/bracket_solver.lua"
in_chroot "cd ~ && smi-lua --quiet --allow-exec smi-beam-solver /usr/share/smi-lua/scripts/tutorial/bracket_solver.lua | head -n 2"
case "$study" in
  quick)
    echo "--- cd ~ && smi-lua --allow-exec smi-column-fe /usr/share/smi-lua/scripts/steering_column.lua --quick"
    t0=$(date +%s)
    in_chroot "cd ~ && smi-lua --quiet --allow-exec smi-column-fe /usr/share/smi-lua/scripts/steering_column.lua --quick | tail -n 3 && ls ~/smi-out/steering_column/"
    echo "study: $(( $(date +%s) - t0 )) s" ;;
  dry-run)
    in_chroot "cd ~ && smi-lua --allow-exec smi-column-fe /usr/share/smi-lua/scripts/steering_column.lua --quick --dry-run | tail -n 5" ;;
esac
echo "PASS: the package installs and runs in a fresh Debian 12"
