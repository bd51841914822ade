#!/usr/bin/env bash
# deploy_test: what robot/deploy/deploy.sh gives a robot, without a robot. `--dry-run` stages
# the robot bundle that rsync would copy to ~/nao-soccer; this checks its layout and size (at
# most 40 MB), that every library the program loads is the bundle's own (its loader in lib/),
# that the venue's field file lands at config/field_dimensions.json, and that the staged start
# script runs the staged program through the bundle's loader with that file (a good field gets
# as far as waiting for LoLA; a bad one stops the start with exit 2 and a line naming the key).
# usage: deploy_test.sh NAO_SOCCER_ROBOT_BINARY SOURCE_DIR
set -euo pipefail
bin=$1 src=$2
tmp=$(mktemp -d /tmp/deploy_test.XXXXXX)
pid=""
cleanup() {
  if [ -n "$pid" ]; then kill "$pid" 2>/dev/null || true; fi
  rm -rf "$tmp"
}
trap cleanup EXIT
fail() { echo "deploy_test: FAILED: $*" >&2; exit 1; }

mkdir -p "$tmp/build/bin"
ln -s "$bin" "$tmp/build/bin/nao-soccer-robot"
say="$(dirname "$bin")/nao-soccer-say"  # the voice, built beside the robot executable
[ -x "$say" ] || fail "no $say (flite1-dev, .ci/install-deps.sh)"
ln -s "$say" "$tmp/build/bin/nao-soccer-say"
# A venue field that differs from the default one, so the log shows which file was read.
sed -e 's/"length": 9.0/"length": 10.4/' -e 's/"width": 6.0/"width": 7.4/' "$src/config/field_dimensions.json" >"$tmp/venue.json"
grep -q '"length": 10.4' "$tmp/venue.json" || fail "could not make the venue field"

out=$("$src/robot/deploy/deploy.sh" --dry-run --no-build --build-dir "$tmp/build" \
  --team 12 --player 3 --field "$tmp/venue.json" --extra "--cameras none --lola-socket $tmp/lola.sock" nao-12.local)
echo "$out"
stage="$tmp/build/deploy-stage"
echo "$out" | grep -Eq "rsync +-a +--delete +--exclude +config/calibration/ .* $stage/ +nao@nao-12.local:nao-soccer.d/[0-9-]+\.partial/" ||
  fail "no rsync into a new folder nao@nao-12.local:nao-soccer.d/STAMP.partial/ that keeps the robot's config/calibration/"
bytes=$(echo "$out" | sed -n 's/^deploy: staged [0-9.]* MB (\([0-9]*\) bytes.*/\1/p')
[ -n "$bytes" ] || fail "--dry-run did not print the bundle's size"
[ "$bytes" -le $((40 * 1048576)) ] || fail "the bundle is $bytes bytes, more than 40 MB"
for f in bin/nao-soccer-robot bin/nao-soccer-start bin/nao-soccer-say lib/libasound.so.2 lib/ld-linux-x86-64.so.2 lib/libc.so.6 lib/libstdc++.so.6 \
  nao-soccer.service nao-soccer.env config/field_dimensions.json config/modules.json models/vision/ball_classifier.yml; do
  [ -f "$stage/$f" ] || fail "$f is not staged"
done
if [ ! -x "$stage/bin/nao-soccer-robot" ] || [ ! -x "$stage/bin/nao-soccer-start" ]; then fail "the staged programs are not executable"; fi
cmp -s "$stage/bin/nao-soccer-robot" "$bin" || fail "the staged binary is not the built one"
# ldd of the staged program: everything resolves inside the bundle (its DT_RPATH $ORIGIN/../lib),
# and through the bundle's own loader nothing comes from the build machine's folders.
outside=$(ldd "$stage/bin/nao-soccer-robot" | awk '/=>/ {print $3}' | sed 's#/bin/\.\./lib/#/lib/#' | grep -v "^$stage/lib/" || true)
[ -z "$outside" ] || fail "ldd: libraries from outside the bundle: $outside"
outside=$("$stage/lib/ld-linux-x86-64.so.2" --list "$stage/bin/nao-soccer-robot" | awk '/=>/ {print $3}' | sed 's#/bin/\.\./lib/#/lib/#' | grep -v "^$stage/lib/" || true)
[ -z "$outside" ] || fail "the bundle's loader takes libraries from outside the bundle: $outside"
if find "$stage" -name 'libmujoco*' -o -name 'libOSMesa*' -o -name 'libGL.so*' -o -name 'libLLVM*' | grep -q .; then
  fail "the bundle holds simulator libraries: $(find "$stage" -name 'libmujoco*' -o -name 'libOSMesa*' -o -name 'libGL.so*' -o -name 'libLLVM*' | awk 'NR <= 3' | xargs)"
fi
cmp -s "$stage/config/field_dimensions.json" "$tmp/venue.json" || fail "the venue field is not config/field_dimensions.json"
if ! grep -qx 'TEAM=12' "$stage/nao-soccer.env" || ! grep -qx 'PLAYER=3' "$stage/nao-soccer.env"; then fail "nao-soccer.env lacks TEAM/PLAYER"; fi
grep -q '^ExecStart=%h/nao-soccer/bin/nao-soccer-start$' "$stage/nao-soccer.service" || fail "the unit does not start nao-soccer-start"

# The voice: nao-soccer-say in the bundle, its libraries there too, run through the bundle's
# loader; it speaks (into a WAV file here) what it is given.
[ -x "$stage/bin/nao-soccer-say" ] || fail "bin/nao-soccer-say is not staged"
outside=$("$stage/lib/ld-linux-x86-64.so.2" --list "$stage/bin/nao-soccer-say" | awk '/=>/ {print $3}' | sed 's#/bin/\.\./lib/#/lib/#' | grep -v "^$stage/lib/" || true)
[ -z "$outside" ] || fail "nao-soccer-say takes libraries from outside the bundle: $outside"
"$stage/lib/ld-linux-x86-64.so.2" "$stage/bin/nao-soccer-say" "The ball is at: -1500 2250" "$tmp/said.wav" ||
  fail "bin/nao-soccer-say failed"
[ "$(head -c 4 "$tmp/said.wav")" = RIFF ] && [ "$(stat -c %s "$tmp/said.wav")" -gt 20000 ] ||
  fail "bin/nao-soccer-say wrote no speech ($(stat -c %s "$tmp/said.wav" 2>/dev/null || echo 0) bytes)"

# The start script as the robot runs it (NAO_SOCCER_HOME = the staged folder).
NAO_SOCCER_HOME="$stage" "$stage/bin/nao-soccer-start" 2>"$tmp/start.log" &
pid=$!
for _ in $(seq 100); do
  grep -q "lola: connecting to $tmp/lola.sock" "$tmp/start.log" && break
  sleep 0.1
done
tr '\0' ' ' <"/proc/$pid/cmdline" | grep -q -- "--speech-command $stage/lib/ld-linux-x86-64.so.2 $stage/bin/nao-soccer-say" ||
  fail "the start script does not give the program the bundle's voice: $(tr '\0' ' ' <"/proc/$pid/cmdline")"
grep -q "run: field $stage/config/field_dimensions.json (10.40 x 7.40 m)" "$tmp/start.log" ||
  { cat "$tmp/start.log" >&2; fail "the start script did not run the program on the staged venue field"; }
grep -q "lola: connecting to $tmp/lola.sock" "$tmp/start.log" || { cat "$tmp/start.log" >&2; fail "the program did not wait for LoLA"; }
kill -TERM "$pid"
wait "$pid" || true
pid=""

# A bad venue file: the start stops at once with one line naming the key, exit 2 (the unit's
# RestartPreventExitStatus).
sed 's/"goalBoxAreaWidth": 2.2,//' "$tmp/venue.json" >"$stage/config/field_dimensions.json"
set +e
NAO_SOCCER_HOME="$stage" timeout 20 "$stage/bin/nao-soccer-start" 2>"$tmp/bad.log"
rc=$?
set -e
[ "$rc" = 2 ] || { cat "$tmp/bad.log" >&2; fail "exit $rc with a bad field file, expected 2"; }
grep -q "$stage/config/field_dimensions.json: field.goalBoxAreaWidth: missing" "$tmp/bad.log" ||
  { cat "$tmp/bad.log" >&2; fail "the bad field's line does not name the file and key"; }
[ "$(wc -l <"$tmp/bad.log")" -eq 1 ] || { cat "$tmp/bad.log" >&2; fail "more than one line for a bad field file"; }
echo "deploy_test: passed"
