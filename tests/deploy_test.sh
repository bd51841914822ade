#!/usr/bin/env bash
# deploy_test: what robot/deploy/deploy.sh gives a robot, without a robot. `--dry-run` stages
# the folder that rsync would copy to ~/nao-soccer; this checks its layout, that the venue's
# field file lands at config/field_dimensions.json, and that the staged start script runs the
# staged program with that file (a good field gets as far as waiting for LoLA; a bad one stops
# the start with exit 2 and a line naming the key).
# usage: deploy_test.sh NAO_SOCCER_BINARY SOURCE_DIR
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
ln -s "$bin" "$tmp/build/bin/nao-soccer"
# A venue field that differs from the default one, so the log shows which file was read.
sed -e 's/"length": 9.0/"length": 10.4/' -e 's/"width": 6.0/"width": 7.4/' "$src/config/field_dimensions.json" >"$tmp/venue.json"
grep -q '"length": 10.4' "$tmp/venue.json" || fail "could not make the venue field"

out=$("$src/robot/deploy/deploy.sh" --dry-run --no-build --no-bundle-libs --build-dir "$tmp/build" \
  --team 12 --player 3 --field "$tmp/venue.json" --extra "--cameras none --lola-socket $tmp/lola.sock" nao-12.local)
echo "$out"
stage="$tmp/build/deploy-stage"
echo "$out" | grep -Eq "rsync +-az +--delete +--exclude +config/calibration/ +$stage/ +nao@nao-12.local:nao-soccer/" ||
  fail "no rsync to nao@nao-12.local:nao-soccer/ that keeps the robot's config/calibration/"
for f in bin/nao-soccer bin/nao-soccer-start nao-soccer.service nao-soccer.env config/field_dimensions.json \
  models/vision/ball_classifier.yml; do
  [ -f "$stage/$f" ] || fail "$f is not staged"
done
if [ ! -x "$stage/bin/nao-soccer" ] || [ ! -x "$stage/bin/nao-soccer-start" ]; then fail "the staged programs are not executable"; fi
cmp -s "$stage/bin/nao-soccer" "$bin" || fail "the staged binary is not the built one"
cmp -s "$stage/config/field_dimensions.json" "$tmp/venue.json" || fail "the venue field is not config/field_dimensions.json"
if ! grep -qx 'TEAM=12' "$stage/nao-soccer.env" || ! grep -qx 'PLAYER=3' "$stage/nao-soccer.env"; then fail "nao-soccer.env lacks TEAM/PLAYER"; fi
grep -q '^ExecStart=%h/nao-soccer/bin/nao-soccer-start$' "$stage/nao-soccer.service" || fail "the unit does not start nao-soccer-start"

# The start script as the robot runs it (NAO_SOCCER_HOME = the staged folder).
NAO_SOCCER_HOME="$stage" "$stage/bin/nao-soccer-start" 2>"$tmp/start.log" &
pid=$!
for _ in $(seq 100); do
  grep -q "lola: connecting to $tmp/lola.sock" "$tmp/start.log" && break
  sleep 0.1
done
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
