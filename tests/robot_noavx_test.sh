#!/usr/bin/env bash
# robot_noavx_test: nao-soccer-robot on a processor without AVX. The NAO V6's Atom E3845
# (Silvermont) has SSE4.2 and no AVX; qemu-user's Nehalem model has the same instruction set
# and turns any AVX instruction into SIGILL (checked first, with a probe). Under it the robot
# executable runs its whole cognition on the real NAO images of
# ../shared/data/real-nao-images/ (--cameras files:DIR, decoded by the executable itself)
# against lola_peer for 10 s of LoLA time, and must end cleanly with every image's vision run:
# no illegal instruction anywhere in the decoder, the vision, the modeling or the motion.
# Answer times under emulation are measured, not judged (lola_peer --emulated).
# Exit 77 (skipped, with the reason) without qemu-user or the images.
# usage: robot_noavx_test.sh NAO_SOCCER_ROBOT LOLA_PEER SOURCE_DIR
set -euo pipefail
robot=$1 peer=$2 src=$3
cpu=Nehalem-v1
qemu=$(command -v qemu-x86_64 || true)
[ -n "$qemu" ] || { echo "robot_noavx_test: SKIPPED: qemu-x86_64 is not installed (qemu-user, .ci/install-deps.sh)"; exit 77; }
images="$src/../shared/data/real-nao-images"
[ -d "$images" ] || { echo "robot_noavx_test: SKIPPED: no $images"; exit 77; }
tmp=$(mktemp -d /tmp/robot_noavx_test.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "robot_noavx_test: FAILED: $*" >&2; exit 1; }

# The model must refuse AVX, or this test proves nothing.
cat >"$tmp/probe.c" <<'C'
int main(void) { __asm__ volatile("vpxor %%ymm0, %%ymm0, %%ymm0" ::: "xmm0"); return 0; }
C
cc -O0 "$tmp/probe.c" -o "$tmp/probe"
rc=$( ("$qemu" -cpu "$cpu" "$tmp/probe") 2>/dev/null; echo $?) 2>/dev/null
[ "$rc" = 132 ] || fail "an AVX instruction under qemu -cpu $cpu ended with $rc, not SIGILL (132)"
echo "robot_noavx_test: qemu -cpu $cpu: an AVX instruction dies with SIGILL"

# The real images as both cameras' frames (the executable decodes them itself).
mkdir -p "$tmp/frames/top" "$tmp/frames/bottom"
n=0
for f in "$images"/*_RGB.png; do
  ln -s "$f" "$tmp/frames/top/"
  ln -s "$f" "$tmp/frames/bottom/"
  n=$((n + 1))
done
[ "$n" -ge 10 ] || fail "only $n real images in $images"

start=$(date +%s)
"$peer" --nao-soccer "$robot" --soak 10 --emulated --prefix "$qemu" --prefix -cpu --prefix "$cpu" \
  --cameras "files:$tmp/frames" --arg --json --arg "$tmp/run.json" --json "$tmp/peer.json" \
  >"$tmp/peer.out" 2>"$tmp/peer.err" || { cat "$tmp/peer.err" >&2; fail "the robot executable did not pass the LoLA peer under qemu -cpu $cpu"; }
grep -qi "illegal instruction" "$tmp/peer.err" && fail "illegal instruction: $(grep -i 'illegal instruction' "$tmp/peer.err" | head -n 1)"
grep -q "skipped" <(grep "^camera " "$tmp/peer.err" || true) && fail "an image was not decoded: $(grep '^camera ' "$tmp/peer.err" | head -n 1)"

# What cognition saw, per camera (the run JSON's "percepts").
compact=$(tr -d ' \n' <"$tmp/run.json")
field() { echo "$1" | sed -n "s/.*\"$2\":\([0-9]*\).*/\1/p"; }
for camera in top bottom; do
  tally=$(echo "$compact" | sed -n "s/.*\"percepts\":{.*\"$camera\":{\([^}]*\)}.*/\1/p")
  processed=$(field "$tally" processed)
  boundary=$(field "$tally" field_boundary)
  withLines=$(field "$tally" with_lines)
  [ -n "$processed" ] || fail "no percept tally for the $camera camera in the run JSON"
  echo "robot_noavx_test: $camera: $processed images through the vision, field boundary in $boundary, lines in $withLines"
  [ "$processed" -ge 50 ] || fail "$camera: only $processed images through the vision in 10 s"
  [ $((boundary * 10)) -ge $((processed * 9)) ] || fail "$camera: a field boundary in only $boundary of $processed real images"
  [ $((withLines * 5)) -ge "$processed" ] || fail "$camera: lines in only $withLines of $processed real images"
done
echo "robot_noavx_test: passed in $(( $(date +%s) - start )) s: $(tr -d '\n' <"$tmp/peer.out" | sed -n 's/.*"late_answers": \([0-9]*\).*"max_answer_ms": \([0-9.]*\).*/answers later than 12 ms under emulation: \1, the slowest \2 ms/p')"
