#!/usr/bin/env bash
# same_answers_test: the robot executable (nao-soccer-robot, what the bundle runs) and
# `nao-soccer run --backend nao` give the same answers to the same LoLA packets and images.
#  1. Record: lola_peer's soak of nao-soccer (answer times not judged: --emulated; its servo model answering the program's
#     commands) writes every sensor packet it sends; the cameras are the real NAO images of
#     ../shared/data/real-nao-images/ (--cameras files:DIR).
#  2. Replay the packets, one at a time, to each program in --lockstep (built before the first
#     answer, cognition in the motion cycle, frames due on the LoLA clock): nao-soccer twice
#     (the replay is deterministic, or the comparison would prove nothing), the robot
#     executable once. The answers must be identical, line for line, and not trivial (the
#     program takes over, its stiffness ramps up, the joints move, both cameras' vision runs),
#     with the same beliefs (pose, ball, percepts in the run JSON), which other images change:
#     the comparison covers the vision and the modeling too.
# usage: same_answers_test.sh NAO_SOCCER_ROBOT NAO_SOCCER LOLA_PEER SOURCE_DIR
set -euo pipefail
robot=$1 full=$2 peer=$3 src=$4
images="$src/../shared/data/real-nao-images"
[ -d "$images" ] || { echo "same_answers_test: SKIPPED: no $images"; exit 77; }
tmp=$(mktemp -d /tmp/same_answers_test.XXXXXX)
[ -n "${KEEP_TMP:-}" ] || trap 'rm -rf "$tmp"' EXIT
fail() { echo "same_answers_test: FAILED: $*" >&2; exit 1; }

mkdir -p "$tmp/frames/top" "$tmp/frames/bottom" "$tmp/reversed/top" "$tmp/reversed/bottom"
n=0
for f in "$images"/*_RGB.png; do
  ln -s "$f" "$tmp/frames/top/"
  ln -s "$f" "$tmp/frames/bottom/"
  # The same images in the opposite order: what the cameras show must change the answers.
  ln -s "$f" "$tmp/reversed/top/$(printf '%03d' $((999 - n))).png"
  ln -s "$f" "$tmp/reversed/bottom/$(printf '%03d' $((999 - n))).png"
  n=$((n + 1))
done

"$peer" --nao-soccer "$full" --soak 3 --emulated --cameras "files:$tmp/frames" --record "$tmp/packets.bin" \
  --json "$tmp/record.json" >/dev/null 2>"$tmp/record.err" || { cat "$tmp/record.err" >&2; fail "the recording run failed"; }
echo "same_answers_test: recorded $(stat -c %s "$tmp/packets.bin") bytes of LoLA packets"

replay() {  # replay NAME BIN [FRAMES]
  "$peer" --nao-soccer "$2" --replay "$tmp/packets.bin" --answers "$tmp/$1.txt" --cameras "files:$tmp/${3:-frames}" \
    --arg --lockstep --arg --clock --arg lola --arg --json --arg "$tmp/$1.json" >/dev/null 2>"$tmp/$1.err" ||
    { cat "$tmp/$1.err" >&2; fail "the replay to $1 failed"; }
  echo "same_answers_test: $1: $(wc -l <"$tmp/$1.txt") answers"
}
replay full "$full"
replay full_again "$full"
replay robot "$robot"
replay reversed "$full" reversed

packets=$(grep -c . "$tmp/full.txt")
[ "$packets" -ge 300 ] || fail "only $packets answers"
cmp -s "$tmp/full.txt" "$tmp/full_again.txt" ||
  fail "nao-soccer --lockstep is not deterministic: $(diff "$tmp/full.txt" "$tmp/full_again.txt" | head -n 2 | cut -c1-200)"
cmp -s "$tmp/full.txt" "$tmp/robot.txt" ||
  fail "the robot executable answered differently: $(diff "$tmp/full.txt" "$tmp/robot.txt" | head -n 2 | cut -c1-200)"
# What cognition made of the images: the beliefs once a second (pose and ball) and the percept
# tallies of the run JSON are the same too, and other images (the same ones in another order)
# make other beliefs: the comparison covers the vision and the modeling. (In these seconds of
# standing the answers themselves do not depend on them: the head sweeps while the pose is
# not valid.)
beliefs() { sed -n '/^  "per_second": \[/,/^  \],\?$/p; /^  "percepts": {/,/^  },\?$/p' "$tmp/$1.json"; }
[ "$(beliefs full | wc -l)" -ge 20 ] || fail "no beliefs in the run JSON"
for other in full_again robot; do
  cmp -s <(beliefs full) <(beliefs "$other") ||
    fail "$other believed otherwise: $(diff <(beliefs full) <(beliefs "$other") | head -n 3 | tr '\n' ' ')"
done
cmp -s <(beliefs full) <(beliefs reversed) && fail "the images in another order changed nothing the program believed"
differing=$(diff <(beliefs full) <(beliefs reversed) | grep -c '^<' || true)

# Not trivial: the program took over (its stiffness ramped up), its positions changed between
# answers, and both cameras' images went through the vision.
stiff=$(tail -n 1 "$tmp/full.txt" | awk '{for (i = 1; i <= NF; i++) if ($i == "Stiffness") { m = 0; for (j = i + 1; j <= i + 25; j++) if ($j > m) m = $j; print m }}')
awk -v s="$stiff" 'BEGIN { exit !(s >= 0.5) }' || fail "the last answer's stiffness is at most $stiff: the program never took over"
distinct=$(sed 's/.*Position\(.*\)Sonar.*/\1/' "$tmp/full.txt" | sed 's/ Stiffness.*//' | sort -u | wc -l)
[ "$distinct" -ge 50 ] || fail "only $distinct distinct joint position answers"
compact=$(tr -d ' \n' <"$tmp/robot.json")
for camera in top bottom; do
  n=$(echo "$compact" | sed -n "s/.*\"images_processed\":{[^}]*\"$camera\":\([0-9]*\).*/\1/p")
  [ -n "$n" ] && [ "$n" -ge 30 ] || fail "the robot executable's vision ran on ${n:-no} $camera images"
  [ "$(tr -d ' \n' <"$tmp/full.json" | sed -n "s/.*\"images_processed\":{[^}]*\"$camera\":\([0-9]*\).*/\1/p")" = "$n" ] ||
    fail "the two programs processed different numbers of $camera images"
done
echo "same_answers_test: passed: $packets identical answers, $distinct distinct joint positions, both cameras' vision in each; $differing lines of beliefs differ with the images reordered"
