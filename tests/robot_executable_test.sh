#!/usr/bin/env bash
# robot_executable_test: nao-soccer-robot is the robot program without the simulator, for the
# NAO's Atom (no AVX), with `nao-soccer run --backend nao`'s command line:
#  - it links no simulator library (MuJoCo, OSMesa, GL, tinyxml2) and has DT_RPATH $ORIGIN/../lib;
#  - no AVX instruction (no ymm/zmm register) in its code but OpenCV's CPU-dispatched variants;
#  - the same --help, and for the same bad options, files and values the same one line and exit
#    code as `nao-soccer run --backend nao` (only the program's name differs);
#  - what only nao-soccer has (the simulator backend, other commands): exit 2, one line.
# usage: robot_executable_test.sh NAO_SOCCER_ROBOT NAO_SOCCER
set -euo pipefail
robot=$1 full=$2
tmp=$(mktemp -d /tmp/robot_executable_test.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "robot_executable_test: FAILED: $*" >&2; exit 1; }

needed=$(readelf -d "$robot" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p')
echo "robot_executable_test: NEEDED: $(echo "$needed" | xargs)"
if echo "$needed" | grep -Eiq 'mujoco|osmesa|libGL\.so|tinyxml|LLVM'; then fail "links the simulator: $(echo "$needed" | grep -Ei 'mujoco|osmesa|libGL\.so|tinyxml|LLVM' | xargs)"; fi
readelf -d "$robot" | grep -q '(RPATH).*\[\$ORIGIN/../lib\]' || fail "no DT_RPATH \$ORIGIN/../lib"
# Functions with AVX registers: only OpenCV's run-time dispatched variants (cv::opt_AVX2::,
# cv::opt_AVX512_SKX::, chosen only on a CPU that has them) may have any.
objdump -d --no-show-raw-insn -C "$robot" |
  awk '/^[0-9a-f]+ <.*>:$/ {fn = $0} /%[yz]mm[0-9]/ {print fn}' | sort -u >"$tmp/avx.txt"
echo "robot_executable_test: $(wc -l <"$tmp/avx.txt") functions with AVX registers, all OpenCV's dispatched ones"
undispatched=$(grep -Ev '::opt_AVX(2|512_SKX)::' "$tmp/avx.txt" | head -n 3 || true)
[ -z "$undispatched" ] || fail "AVX instructions outside OpenCV's CPU dispatch (the NAO's Atom E3845 has no AVX): $undispatched"

# Same command line: help and errors.
"$robot" --help >"$tmp/robot.help"
"$full" run --help >"$tmp/full.help"
sed 's/nao-soccer-robot/nao-soccer/g' "$tmp/robot.help" | cmp -s - "$tmp/full.help" ||
  { diff <(sed 's/nao-soccer-robot/nao-soccer/g' "$tmp/robot.help") "$tmp/full.help" >&2 || true; fail "--help differs from nao-soccer run --help"; }
same() {  # same ARGS...: nao-soccer-robot ARGS and nao-soccer run --backend nao ARGS end alike
  local rr=0 rf=0
  "$robot" "$@" >/dev/null 2>"$tmp/r.err" </dev/null || rr=$?
  "$full" run --backend nao "$@" >/dev/null 2>"$tmp/f.err" </dev/null || rf=$?
  [ "$rr" = "$rf" ] || fail "'$*': exit $rr, nao-soccer run --backend nao: $rf"
  sed 's/^nao-soccer-robot /nao-soccer /' "$tmp/r.err" | cmp -s - "$tmp/f.err" ||
    fail "'$*': '$(cat "$tmp/r.err")' against '$(cat "$tmp/f.err")'"
  [ "$(wc -l <"$tmp/r.err")" = 1 ] || fail "'$*': not one line: $(cat "$tmp/r.err")"
  echo "robot_executable_test: '$*' -> exit $rr: $(cat "$tmp/r.err")"
}
same --seconds 0
same --team 300
same --player abc
same --cameras on
same --no-such-option
same --field "$tmp/missing.json"
echo '{"field": {}}' >"$tmp/bad.json"
same --field "$tmp/bad.json"
same --camera-settings "$tmp/missing.json" --lola-socket "$tmp/none.sock"
same --lockstep
same --lockstep --clock lola --cameras v4l2
# The explicit form the start script uses takes the same options.
"$robot" run --backend nao --help | cmp -s - "$tmp/robot.help" || fail "'run --backend nao --help' differs from '--help'"
only_full() {  # only_full ARGS...: exit 2 and one line
  local rc=0
  "$robot" "$@" >/dev/null 2>"$tmp/o.err" </dev/null || rc=$?
  [ "$rc" = 2 ] && [ "$(wc -l <"$tmp/o.err")" = 1 ] || fail "'$*': exit $rc: $(cat "$tmp/o.err")"
  echo "robot_executable_test: '$*' -> exit 2: $(cat "$tmp/o.err")"
}
only_full --backend sim
only_full run --backend sim --seconds 1
only_full eval walk
echo "robot_executable_test: passed"
