#!/usr/bin/env bash
# deploy_target_test: robot/deploy/deploy.sh against stand-in robots, never a real address. A
# stand-in ssh (NAO_DEPLOY_SSH) makes host H the local folder ROBOTS/H (the robot's home; an
# unknown host is unreachable) and runs the remote commands and rsync's server there. Checked:
#  - an unreachable robot, a robot without LoLA (no socket), a full disk (a 4 MB tmpfs as the
#    robot's home), and a disk that fills during the copy (the stand-in's df lies): exit 1 and
#    one line naming what failed;
#    the previous install untouched and still running, no half-copied folder left;
#  - a good deploy: the running program is stopped softly (SIGTERM) only after the copy,
#    ~/nao-soccer switched by a rename to the new folder, the robot's calibration carried over,
#    the new program started (through the bundle's loader, up to waiting for LoLA); a second
#    deploy keeps the current and the previous install.
# usage: deploy_target_test.sh NAO_SOCCER_ROBOT_BINARY SOURCE_DIR
set -euo pipefail
bin=$1 src=$2
tmp=$(mktemp -d /tmp/deploy_target_test.XXXXXX)
pids=() mounted=""
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  for f in "$tmp"/robots/*/nao-soccer.d/run.pid; do [ -f "$f" ] && kill "$(cat "$f")" 2>/dev/null || true; done
  sleep 0.3
  if [ -n "$mounted" ]; then umount -l "$mounted" 2>/dev/null || true; fi
  rm -rf "$tmp"
}
trap cleanup EXIT
fail() { echo "deploy_target_test: FAILED: $*" >&2; exit 1; }
start=$(date +%s.%N)

robots="$tmp/robots"
mkdir -p "$robots" "$tmp/build/bin"
ln -s "$bin" "$tmp/build/bin/nao-soccer-robot"
cat >"$tmp/ssh" <<'SSH'
#!/usr/bin/env bash
# ssh stand-in: host H = the folder $STANDIN_ROBOTS/H as the robot's home.
while [ $# -gt 0 ]; do
  case "$1" in -o|-p|-i|-l) shift 2 ;; -*) shift ;; *) break ;; esac
done
host=${1#*@}
shift
home="$STANDIN_ROBOTS/$host"
[ -d "$home" ] || { echo "ssh: connect to host $host port 22: Connection refused" >&2; exit 255; }
cd "$home"
if [ -n "${STANDIN_DF_LIES:-}" ]; then
  # df claims 100 GB free: the check passes and the copy runs into the full disk.
  mkdir -p "$STANDIN_ROBOTS/.bin"
  printf '#!/bin/sh\necho "Filesystem 1024-blocks Used Available Capacity Mounted on"\necho "lie 104857600 0 104857600 0%% /"\n' >"$STANDIN_ROBOTS/.bin/df"
  chmod +x "$STANDIN_ROBOTS/.bin/df"
  export PATH="$STANDIN_ROBOTS/.bin:$PATH"
fi
HOME="$home" exec bash -c "$*"
SSH
chmod +x "$tmp/ssh"
export NAO_DEPLOY_SSH="$tmp/ssh" STANDIN_ROBOTS="$robots"

# LoLA's socket: a listening Unix socket (nobody answers; the program gets as far as connecting).
lola="$tmp/lola.sock"
if command -v python3 >/dev/null; then
  python3 -c 'import socket, sys, time; s = socket.socket(socket.AF_UNIX); s.bind(sys.argv[1]); s.listen(4); time.sleep(600)' "$lola" &
else
  perl -MIO::Socket::UNIX -e '$s = IO::Socket::UNIX->new(Local => $ARGV[0], Listen => 4) or die; sleep 600' "$lola" &
fi
pids+=($!)
for _ in $(seq 50); do [ -S "$lola" ] && break; sleep 0.1; done
[ -S "$lola" ] || fail "could not make the stand-in LoLA socket"

# A robot with an install of the old layout (a folder, run.pid), its program running: a stand-in
# that notes SIGTERM (a soft stop) before it ends.
old_install() {  # old_install HOME
  local h=$1
  mkdir -p "$h/nao-soccer/bin" "$h/nao-soccer/config/calibration"
  echo '{"head": "H1"}' >"$h/nao-soccer/config/calibration/H1.json"
  cat >"$h/nao-soccer/bin/nao-soccer-start" <<'PROG'
#!/usr/bin/env bash
trap 'echo "SIGTERM" >>"$HOME/old-program.log"; exit 0' TERM
echo "running" >>"$HOME/old-program.log"
while :; do sleep 0.1; done
PROG
  chmod +x "$h/nao-soccer/bin/nao-soccer-start"
  (cd "$h" || exit 1; HOME="$h" bash "$h/nao-soccer/bin/nao-soccer-start" >/dev/null 2>&1 </dev/null & echo $! >"$h/nao-soccer/run.pid")
  pids+=("$(cat "$h/nao-soccer/run.pid")")
  for _ in $(seq 50); do grep -q running "$h/old-program.log" 2>/dev/null && break; sleep 0.1; done
}
# The state a failure must leave: the old folder, its program running, nothing half-copied.
untouched() {  # untouched HOME WHAT
  local h=$1 what=$2
  [ -d "$h/nao-soccer" ] && [ ! -L "$h/nao-soccer" ] || fail "$what: ~/nao-soccer was changed"
  kill -0 "$(cat "$h/nao-soccer/run.pid")" 2>/dev/null || fail "$what: the previous program is not running any more"
  ! grep -q SIGTERM "$h/old-program.log" || fail "$what: the previous program was stopped"
  [ -z "$(find "$h" -maxdepth 2 -name '*.partial')" ] || fail "$what: a half-copied folder was left: $(find "$h" -maxdepth 2 -name '*.partial')"
}
deploy() {  # deploy ROBOT [deploy.sh options]: exit code in $rc, stderr in $tmp/err
  local r=$1
  shift
  set +e
  "$src/robot/deploy/deploy.sh" --no-build --build-dir "$tmp/build" --team 12 --player 3 \
    --extra "--cameras none --lola-socket $lola" "$@" "$r" >"$tmp/out" 2>"$tmp/err"
  rc=$?
  set -e
}
one_line() {  # one_line WHAT PATTERN: exit 1, exactly one stderr line, matching
  [ "$rc" = 1 ] || { cat "$tmp/out" "$tmp/err" >&2; fail "$1: exit $rc, expected 1"; }
  [ "$(wc -l <"$tmp/err")" = 1 ] || { cat "$tmp/err" >&2; fail "$1: not one line on stderr"; }
  grep -Eq "$2" "$tmp/err" || { cat "$tmp/err" >&2; fail "$1: the line does not say '$2'"; }
  echo "deploy_target_test: $1: $(cat "$tmp/err")"
}

mkdir -p "$robots/nao-1"
old_install "$robots/nao-1"

deploy nao-gone
one_line "unreachable robot" '^deploy: nao-gone: unreachable over ssh \(ssh: connect to host nao-gone port 22: Connection refused\)$'

mv "$lola" "$lola.away"
deploy nao-1
mv "$lola.away" "$lola"
one_line "no LoLA" "^deploy: nao-1: no LoLA: $lola is not a socket"
untouched "$robots/nao-1" "no LoLA"

if mkdir -p "$robots/nao-full" && mount -t tmpfs -o size=4m tmpfs "$robots/nao-full" 2>/dev/null; then
  mounted="$robots/nao-full"
  old_install "$robots/nao-full"
  deploy nao-full
  one_line "full disk" '^deploy: nao-full: full disk: [0-9]+ MB free in .*, the bundle needs [0-9]+ MB$'
  untouched "$robots/nao-full" "full disk"
else
  echo "deploy_target_test: full disk: SKIPPED (cannot mount a tmpfs here; needs root)"
fi

if [ -n "$mounted" ]; then
  STANDIN_DF_LIES=1 deploy nao-full
  one_line "disk full during the copy" '^deploy: nao-full: copying the bundle failed \(.*No space left on device.*\); the previous install was left running$'
  untouched "$robots/nao-full" "disk full during the copy"
else
  echo "deploy_target_test: disk full during the copy: SKIPPED (cannot mount a tmpfs here; needs root)"
fi

# A good deploy.
deploy nao-1
[ "$rc" = 0 ] || { cat "$tmp/out" "$tmp/err" >&2; fail "good deploy: exit $rc"; }
h="$robots/nao-1"
grep -q SIGTERM "$h/old-program.log" || { cat "$tmp/out" "$tmp/err" "$h/old-program.log" >&2; fail "good deploy: the previous program was not stopped with SIGTERM"; }
[ -L "$h/nao-soccer" ] || fail "good deploy: ~/nao-soccer is not the switched link"
first=$(readlink "$h/nao-soccer")
[[ "$first" == nao-soccer.d/* ]] && [ -x "$h/$first/bin/nao-soccer-robot" ] || fail "good deploy: ~/nao-soccer -> '$first'"
[ -n "$(find "$h/nao-soccer.d" -maxdepth 1 -name 'old-*')" ] || fail "good deploy: the old install was not kept aside"
cmp -s "$h/nao-soccer/config/calibration/H1.json" <(echo '{"head": "H1"}') || fail "good deploy: the robot's calibration was not carried over"
[ -f "$h/nao-soccer.d/run.pid" ] || fail "good deploy: no pid file"
for _ in $(seq 100); do grep -q "lola: connecting to $lola" "$h/nao-soccer/nao-soccer.log" 2>/dev/null && break; sleep 0.1; done
grep -q "run: field $h/nao-soccer/config/field_dimensions.json" "$h/nao-soccer/nao-soccer.log" &&
  grep -q "lola: connecting to $lola" "$h/nao-soccer/nao-soccer.log" ||
  { cat "$tmp/out" "$h/nao-soccer/nao-soccer.log" >&2; fail "good deploy: the new program did not start"; }
grep -q "^deploy: nao@nao-1:nao-soccer -> $first$" "$tmp/out" || { cat "$tmp/out" >&2; fail "good deploy: no last line naming the switch"; }
echo "deploy_target_test: good deploy: $(tail -n 1 "$tmp/out")"

# A second deploy: the first is now the previous install, the old one is gone.
sleep 1
deploy nao-1
[ "$rc" = 0 ] || { cat "$tmp/out" "$tmp/err" >&2; fail "second deploy: exit $rc"; }
second=$(readlink "$h/nao-soccer")
[ "$second" != "$first" ] || fail "second deploy: ~/nao-soccer was not switched"
[ -d "$h/$first" ] || fail "second deploy: the previous install is gone"
[ "$(find "$h/nao-soccer.d" -mindepth 1 -maxdepth 1 -type d | wc -l)" = 2 ] || fail "second deploy: not exactly the current and the previous install: $(ls "$h/nao-soccer.d")"
echo "deploy_target_test: passed in $(awk -v s="$start" -v e="$(date +%s.%N)" 'BEGIN {printf "%.1f", e - s}') s"
