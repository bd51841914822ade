#!/usr/bin/env bash
# robot_bundle_test: the robot bundle that deploy.sh stages runs on an OS that is not the build
# machine's. The bundle (nao-soccer-robot, nao-soccer-say, its own dynamic loader, C library and libraries,
# config/, models/) is staged with `deploy.sh --dry-run`, copied to ROOT/home/nao/nao-soccer and
# started in `chroot ROOT` through the bundle's loader, exactly as its start script does.
# lola_peer (tests/lola_peer.cpp) plays LoLA on a socket inside ROOT/tmp: the ramp, 10 s of
# cycles with every answer within the 12 ms cycle, then SIGTERM: soft in place, exit 0.
#   empty:    ROOT holds nothing but the bundle (no /bin/sh, no /lib, no /proc, no /etc).
#   debian11: ROOT is Debian 11 (glibc 2.31) made with `debootstrap --variant=minbase bullseye`
#             from Debian's mirror, cached in $NAO_DEBIAN11_ROOT (default
#             /var/cache/nao-soccer/debian11-minbase); skipped (exit 77) when the mirror cannot be
#             reached. There the program started the OS's way (its own glibc) must fail, too.
# usage: robot_bundle_test.sh empty|debian11 NAO_SOCCER_ROBOT LOLA_PEER SOURCE_DIR   (as root)
set -euo pipefail
mode=$1 bin=$2 peer=$3 src=$4
skip() { echo "robot_bundle_test ($mode): SKIPPED: $*"; exit 77; }
fail() { echo "robot_bundle_test ($mode): FAILED: $*" >&2; exit 1; }
[ "$(id -u)" = 0 ] || skip "chroot needs root"
tmp=$(mktemp -d /tmp/robot_bundle_test.XXXXXX)
root="" home=""
cleanup() {
  if [ -n "$home" ]; then rm -rf "$home"; fi
  rm -rf "$tmp"
}
trap cleanup EXIT
start=$(date +%s.%N)

mkdir -p "$tmp/build/bin"
ln -s "$bin" "$tmp/build/bin/nao-soccer-robot"
say="$(dirname "$bin")/nao-soccer-say"  # the voice, built beside the robot executable
[ -x "$say" ] || fail "no $say (flite1-dev, .ci/install-deps.sh)"
ln -s "$say" "$tmp/build/bin/nao-soccer-say"
"$src/robot/deploy/deploy.sh" --dry-run --no-build --build-dir "$tmp/build" nao-test.invalid >"$tmp/deploy.out"
stage="$tmp/build/deploy-stage"
[ -x "$stage/lib/ld-linux-x86-64.so.2" ] || fail "the bundle has no loader"

case "$mode" in
  empty)
    root="$tmp/root"
    mkdir -p "$root/home/nao"
    ;;
  debian11)
    root=${NAO_DEBIAN11_ROOT:-/var/cache/nao-soccer/debian11-minbase}
    if [ ! -x "$root/bin/sh" ]; then
      command -v debootstrap >/dev/null || skip "debootstrap is not installed (.ci/install-deps.sh)"
      mkdir -p "$(dirname "$root")"
      rm -rf "$root.partial"
      echo "robot_bundle_test: making the Debian 11 root $root (debootstrap --variant=minbase bullseye; cached)"
      if ! debootstrap --variant=minbase bullseye "$root.partial" http://deb.debian.org/debian >"$tmp/debootstrap.log" 2>&1 &&
        ! { rm -rf "$root.partial"; debootstrap --variant=minbase bullseye "$root.partial" http://archive.debian.org/debian >>"$tmp/debootstrap.log" 2>&1; }; then
        rm -rf "$root.partial"
        skip "Debian's mirror cannot be reached or debootstrap failed: $(grep -E '^E:|W:' "$tmp/debootstrap.log" | tail -n 1)"
      fi
      mv "$root.partial" "$root"
    fi
    # awk reads to the end: `head` would leave ldd writing into a closed pipe (SIGPIPE, and with
    # pipefail a silent exit of this script).
    glibc=$(chroot "$root" /usr/bin/ldd --version 2>/dev/null | awk 'NR == 1 {print $NF}')
    echo "robot_bundle_test: Debian $(cat "$root/etc/debian_version") root, glibc $glibc"
    ;;
  *) fail "mode '$mode' (empty or debian11)" ;;
esac
home="$root/home/nao/nao-soccer-test.$$"
mkdir -p "$(dirname "$home")"
cp -a "$stage" "$home"
inside=${home#"$root"}

if [ "$mode" = debian11 ]; then
  # The OS's own loader and glibc 2.31 cannot run the program: the bundle's loader is what makes it run.
  if chroot "$root" "$inside/bin/nao-soccer-robot" --help >"$tmp/native.out" 2>&1; then
    echo "robot_bundle_test: note: the program also starts with the root's own glibc"
  else
    echo "robot_bundle_test: without the bundle's loader (expected to fail): $(head -n 1 "$tmp/native.out")"
  fi
fi
if [ "$mode" = empty ]; then
  others=$(cd "$root" && find . -mindepth 1 -not -path './home' -not -path './home/nao' -not -path "./home/nao/nao-soccer-test.$$*" | awk 'NR <= 3')
  [ -z "$others" ] || fail "the root holds more than the bundle: $others"
fi

# ldd as the loader sees it in the root: every library from the bundle's lib/.
chroot "$root" "$inside/lib/ld-linux-x86-64.so.2" --list "$inside/bin/nao-soccer-robot" >"$tmp/ldd.out" 2>&1 ||
  { cat "$tmp/ldd.out" >&2; fail "the bundle's loader cannot list the program's libraries in the root"; }
outside=$(awk '/=>/ {print $3}' "$tmp/ldd.out" | sed 's#/bin/\.\./lib/#/lib/#' | grep -v "^$inside/lib/" || true)
[ -z "$outside" ] || fail "libraries from outside the bundle: $outside"
grep -q 'not found' "$tmp/ldd.out" && fail "missing libraries: $(grep -m 3 'not found' "$tmp/ldd.out" | xargs)"

NAO_SOCCER_HOME="$inside" "$peer" --nao-soccer "$inside/bin/nao-soccer-robot" --soak 10 --chroot "$root" \
  --prefix "$inside/lib/ld-linux-x86-64.so.2" --prefix --argv0 --prefix "$inside/bin/nao-soccer-robot" \
  --json "$tmp/peer.json" || fail "the bundle did not pass the LoLA peer in the $mode root"
# The voice in the root, through the bundle's loader: speech into a WAV file.
mkdir -p "$root/tmp"
rm -f "$root/tmp/said.$$.wav"
chroot "$root" "$inside/lib/ld-linux-x86-64.so.2" "$inside/bin/nao-soccer-say" "Calibration finished" "/tmp/said.$$.wav" \
  >"$tmp/say.out" 2>&1 || { cat "$tmp/say.out" >&2; fail "nao-soccer-say did not run in the $mode root"; }
[ "$(head -c 4 "$root/tmp/said.$$.wav")" = RIFF ] || fail "nao-soccer-say wrote no WAV in the $mode root"
rm -f "$root/tmp/said.$$.wav"
echo "robot_bundle_test ($mode): passed in $(awk -v s="$start" -v e="$(date +%s.%N)" 'BEGIN {printf "%.1f", e - s}') s"
