#!/usr/bin/env bash
# robot_noavx_test: nao-soccer-robot on a processor without AVX. The NAO V6's Atom E3845
# (Silvermont) has SSE4.2 and no AVX; qemu-user's Nehalem model has the same instruction set
# and turns any AVX instruction into SIGILL (checked first, with a probe). Under it the robot
# executable runs its whole cognition on the real NAO images of
# ../shared/data/real-nao-images/ (--cameras files:DIR, decoded by the executable itself)
# against lola_peer for 10 s of LoLA time, and must end cleanly with every image's vision run:
# no illegal instruction anywhere in the decoder, the vision, the modeling or the motion.
# Answer times under emulation are measured, not judged (lola_peer --emulated).
# What the vision found is judged on a replay of the soak's packets in --lockstep, still under
# qemu: there every frame due on the LoLA clock goes through the vision, in order, so the
# tallies do not depend on which frames the emulated camera threads happened to skip.
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
  --cameras "files:$tmp/frames" --arg --json --arg "$tmp/run.json" --json "$tmp/peer.json" --record "$tmp/packets.bin" \
  >"$tmp/peer.out" 2>"$tmp/peer.err" || { cat "$tmp/peer.err" >&2; fail "the robot executable did not pass the LoLA peer under qemu -cpu $cpu"; }
grep -qi "illegal instruction" "$tmp/peer.err" && fail "illegal instruction: $(grep -i 'illegal instruction' "$tmp/peer.err" | head -n 1)"
grep -q "skipped" <(grep "^camera " "$tmp/peer.err" || true) && fail "an image was not decoded: $(grep '^camera ' "$tmp/peer.err" | head -n 1)"

compact() { tr -d ' \n' <"$1"; }
field() { echo "$1" | sed -n "s/.*\"$2\":\([0-9]*\).*/\1/p"; }
tally() { echo "$1" | sed -n "s/.*\"percepts\":{.*\"$2\":{\([^}]*\)}.*/\1/p"; }

# The live run: both camera threads ran the vision under emulation.
live=$(compact "$tmp/run.json")
for camera in top bottom; do
  processed=$(field "$(tally "$live" $camera)" processed)
  [ -n "$processed" ] || fail "no percept tally for the $camera camera in the soak's run JSON"
  echo "robot_noavx_test: soak: $camera: $processed images through the vision"
  [ "$processed" -ge 50 ] || fail "$camera: only $processed images through the vision in 10 s"
done

# The same packets again, one at a time, in --lockstep: every frame due goes through the vision.
# Once under qemu, once natively: the vision without AVX finds what it finds with it.
replay() {  # replay NAME [PREFIX...]
  local name=$1 prefix=()
  shift
  for p in "$@"; do prefix+=(--prefix "$p"); done
  "$peer" --nao-soccer "$robot" --replay "$tmp/packets.bin" --answers "$tmp/$name.txt" "${prefix[@]}" \
    --cameras "files:$tmp/frames" --arg --lockstep --arg --clock --arg lola --arg --json --arg "$tmp/$name.json" \
    >/dev/null 2>"$tmp/$name.err" || { cat "$tmp/$name.err" >&2; fail "the lockstep replay ($name) failed"; }
  grep -qi "illegal instruction" "$tmp/$name.err" && fail "illegal instruction in the replay: $(grep -i 'illegal instruction' "$tmp/$name.err" | head -n 1)"
  compact "$tmp/$name.json"
}
emulated=$(replay emulated "$qemu" -cpu "$cpu")
native=$(replay native)
for camera in top bottom; do
  t=$(tally "$emulated" $camera)
  processed=$(field "$t" processed)
  boundary=$(field "$t" field_boundary)
  withLines=$(field "$t" with_lines)
  [ -n "$processed" ] || fail "no percept tally for the $camera camera in the replay's run JSON"
  n=$(tally "$native" $camera)
  echo "robot_noavx_test: replay: $camera: $processed images through the vision, field boundary in $boundary, lines in $withLines (natively: $(field "$n" processed), $(field "$n" field_boundary), $(field "$n" with_lines))"
  [ "$processed" -ge 250 ] || fail "$camera: only $processed of the about 300 frames due in 10 s went through the vision"
  [ "$processed" = "$(field "$n" processed)" ] || fail "$camera: $processed frames under emulation, $(field "$n" processed) natively"
  for k in field_boundary with_lines; do
    a=$(field "$t" $k) b=$(field "$n" $k)
    d=$((a > b ? a - b : b - a))
    [ $((d * 50)) -le "$processed" ] || fail "$camera: $k in $a images under emulation, $b natively"
  done
  [ $((boundary * 10)) -ge $((processed * 9)) ] || fail "$camera: a field boundary in only $boundary of $processed real images"
  [ $((withLines * 8)) -ge "$processed" ] || fail "$camera: lines in only $withLines of $processed real images"
done
echo "robot_noavx_test: passed in $(( $(date +%s) - start )) s: $(tr -d '\n' <"$tmp/peer.out" | sed -n 's/.*"late_answers": \([0-9]*\).*"max_answer_ms": \([0-9.]*\).*/answers later than 12 ms under emulation: \1, the slowest \2 ms/p')"
