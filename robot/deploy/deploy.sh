#!/usr/bin/env bash
# Builds the robot bundle (nao-soccer-robot with its own dynamic loader and libraries, config/,
# the models it uses), copies it to a NAO V6 over ssh/rsync and starts it (a systemd user unit
# when the robot has one, else the start script under nohup). The install is atomic: the bundle
# goes to a new folder (~/nao-soccer.d/STAMP), the running program is stopped softly (SIGTERM)
# only once the copy is complete, ~/nao-soccer (a symlink) is switched with one rename, and the
# new program is started. A failed check or copy leaves the previous install running.
#
# usage: robot/deploy/deploy.sh [options] ROBOT
#   ROBOT                  the NAO's address or ssh host (user nao unless USER@HOST is given)
#   --team N               team number (GameController), default 0 = none
#   --player N             player number 1..20, default 1
#   --field FILE           the venue's field_dimensions.json (default config/field_dimensions.json);
#                          placed as ~/nao-soccer/config/field_dimensions.json on the robot
#   --camera-settings FILE camera resolution/exposure/gain/white balance JSON (optional)
#   --extra "ARGS"         more options for the program (`nao-soccer run --backend nao`'s, e.g. "--cameras none")
#   --build-dir DIR        where to build (default build-robot; compiled with -march=silvermont)
#   --toolchain FILE       CMake toolchain file (cross-compiling; its sysroot provides the libraries)
#   --no-build             use the binary already in --build-dir
#   --no-bundle-libs       do not copy the loader and libraries (the robot's own must fit)
#   --no-start             copy and switch, but neither stop nor start a program
#   --dry-run              build and stage locally, print the size and the commands, touch no robot
# Exit: 0 done, 1 the robot or the copy failed (one line naming what), 2 bad usage.
# NAO_DEPLOY_SSH: the ssh command (default "ssh"; the tests use a stand-in for a robot).
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
team=0 player=1 field="$root/config/field_dimensions.json" camera_settings="" extra=""
build_dir="$root/build-robot" toolchain="" do_build=1 bundle=1 start=1 dry=0 robot=""
max_mb=40
die() { echo "deploy: $*" >&2; exit 2; }
while [ $# -gt 0 ]; do
  case "$1" in
    --team) team="${2:?}"; shift 2 ;;
    --player) player="${2:?}"; shift 2 ;;
    --field) field="${2:?}"; shift 2 ;;
    --camera-settings) camera_settings="${2:?}"; shift 2 ;;
    --extra) extra="${2:?}"; shift 2 ;;
    --build-dir) build_dir="${2:?}"; shift 2 ;;
    --toolchain) toolchain="${2:?}"; shift 2 ;;
    --no-build) do_build=0; shift ;;
    --no-bundle-libs) bundle=0; shift ;;
    --no-start) start=0; shift ;;
    --dry-run) dry=1; shift ;;
    -h|--help) sed -n '2,25p' "$0"; exit 0 ;;
    -*) die "unknown option $1 (--help lists them)" ;;
    *) [ -z "$robot" ] || die "one robot at a time ('$robot' and '$1')"; robot="$1"; shift ;;
  esac
done
[ -n "$robot" ] || die "which robot? (usage: deploy.sh [options] ROBOT)"
if ! [[ "$team" =~ ^[0-9]+$ ]] || [ "$team" -gt 254 ]; then die "--team: '$team' is not 0..254"; fi
if ! [[ "$player" =~ ^[0-9]+$ ]] || [ "$player" -lt 1 ] || [ "$player" -gt 20 ]; then die "--player: '$player' is not 1..20"; fi
[ -f "$field" ] || die "$field: no such field_dimensions.json"
[ -z "$camera_settings" ] || [ -f "$camera_settings" ] || die "$camera_settings: no such file"
case "$robot" in *@*) target="$robot" ;; *) target="nao@$robot" ;; esac
# The LoLA socket the program will use (its --lola-socket in --extra, else LoLA's default).
lola=/tmp/robocup
if [[ " $extra " =~ [[:space:]]--lola-socket[=[:space:]]+([^[:space:]]+) ]]; then lola="${BASH_REMATCH[1]}"; fi

if [ "$do_build" = 1 ]; then
  # The whole robot program for the NAO's Atom E3845 (Silvermont: SSE4.2, no AVX).
  cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DNAO_ROBOT_CPU=silvermont \
    "-DCMAKE_CXX_FLAGS=-march=silvermont -mtune=silvermont" ${toolchain:+-DCMAKE_TOOLCHAIN_FILE="$toolchain"} >/dev/null
  cmake --build "$build_dir" --target nao-soccer-robot -j2
  # The voice, where flite1-dev is installed (apps/CMakeLists.txt).
  cmake --build "$build_dir" --target nao-soccer-say -j2 >/dev/null 2>&1 || true
fi
binary="$build_dir/bin/nao-soccer-robot"
[ -x "$binary" ] || die "$binary: not built (drop --no-build)"
say="$build_dir/bin/nao-soccer-say"

# The folder the robot gets, exactly: ~/nao-soccer = NAO_SOCCER_HOME.
stage="$build_dir/deploy-stage"
rm -rf "$stage"
mkdir -p "$stage/bin" "$stage/config" "$stage/lib" "$stage/models/vision"
cp "$binary" "$stage/bin/nao-soccer-robot"
# The ball classifier's weights (perception/vision/BallClassifier.h).
cp "$root/models/vision/ball_classifier.yml" "$stage/models/vision/"
cp "$root/robot/deploy/nao-soccer-start" "$stage/bin/"
if [ -x "$say" ]; then
  cp "$say" "$stage/bin/nao-soccer-say"
else
  echo "deploy: note: no $say (flite1-dev, .ci/install-deps.sh): the robot will not speak"
fi
cp "$root/robot/deploy/nao-soccer.service" "$stage/"
cp "$field" "$stage/config/field_dimensions.json"
# The module pipelines' providers (config/*modules.json) and the modules' parameters (with
# per-robot overlays).
cp "$root/config/"*modules.json "$stage/config/"
cp -r "$root/config/parameters" "$stage/config/"
[ ! -d "$root/config/robots" ] || cp -r "$root/config/robots" "$stage/config/"
[ -z "$camera_settings" ] || cp "$camera_settings" "$stage/config/camera_settings.json"
printf 'TEAM=%s\nPLAYER=%s\nEXTRA_ARGS="%s"\n' "$team" "$player" "$extra" >"$stage/nao-soccer.env"
if [ "$bundle" = 1 ] && [ -z "$toolchain" ]; then
  # Self-contained: the build machine's dynamic loader, C library and every library the
  # program links, all in lib/. The start script runs the program through lib/'s loader, and
  # the program's DT_RPATH ($ORIGIN/../lib) finds each library there first: nothing of the
  # robot OS's user space is used (ldd on the staged program names lib/ only).
  ldd "$binary" >"$stage/lib/.ldd" || die "$binary: ldd failed (not a dynamic x86-64 program?)"
  loader=$(awk '$1 ~ /^\/.*ld-linux/ {print $1}' "$stage/lib/.ldd")
  [ -n "$loader" ] || die "$binary: no dynamic loader in ldd's output"
  cp -L "$loader" "$stage/lib/ld-linux-x86-64.so.2"
  awk '/=> \// {print $3}' "$stage/lib/.ldd" | while read -r lib; do cp -L "$lib" "$stage/lib/"; done
  if grep -q 'not found' "$stage/lib/.ldd"; then die "$binary: $(grep -m 1 'not found' "$stage/lib/.ldd" | xargs)"; fi
  rm "$stage/lib/.ldd"
  # The voice (nao-soccer-say: flite with one voice), run through the same loader.
  if [ -x "$say" ]; then
    ldd "$say" | awk '/=> \// {print $3}' | while read -r lib; do
      [ -f "$stage/lib/$(basename "$lib")" ] || cp -L "$lib" "$stage/lib/"
    done
  fi
  # Debug sections are not needed on the robot (the build tree keeps the unstripped program).
  strip --strip-debug "$stage/lib/"*.so* 2>/dev/null || true
fi
bytes=$(du -sb "$stage" | cut -f1)
mb=$(awk -v b="$bytes" 'BEGIN {printf "%.1f", b / 1048576}')
echo "deploy: staged $mb MB ($bytes bytes; at most $max_mb MB) in $stage"
[ "$bytes" -le $((max_mb * 1048576)) ] || echo "deploy: warning: the bundle is larger than $max_mb MB" >&2

stamp=$(date -u +%Y%m%d-%H%M%S)-$$
ssh_cmd=(${NAO_DEPLOY_SSH:-ssh} -o BatchMode=yes -o ConnectTimeout=10)
# The robot's own calibration (config/calibration/<head id>.json, written there by the
# calibration) is carried over from the running install, never overwritten.
rsync_cmd=(rsync -a --delete --exclude 'config/calibration/' -e "${ssh_cmd[*]}" "$stage/" "$target:nao-soccer.d/$stamp.partial/")
if [ "$dry" = 1 ]; then
  echo "deploy: dry run, would run:"
  echo "  ssh $target <<check: LoLA's socket $lola, $mb MB free in ~>>"
  printf '  %q' "${rsync_cmd[@]}"; echo
  echo "  ssh $target <<switch: keep config/calibration/, stop the program (SIGTERM), rename ~/nao-soccer to nao-soccer.d/$stamp$([ "$start" = 1 ] && echo ", start it")>>"
  exit 0
fi

# What failed, in one line: the robot's host and the last thing ssh/rsync or the robot said.
fail() { echo "deploy: $robot: $*" >&2; exit 1; }
last_line() { grep -v '^[[:space:]]*$' "$1" | tail -n 1; }
err=$(mktemp /tmp/deploy.XXXXXX)
trap 'rm -f "$err"' EXIT
remote() {  # remote SCRIPT: runs SCRIPT with sh on the robot; its stdout is ours, its stderr in $err
  "${ssh_cmd[@]}" "$target" sh -s <<<"$1" 2>"$err"
}

# 1. Before anything is copied: the robot answers, LoLA runs, the bundle fits.
need_kb=$(( bytes / 1024 + 1024 ))
set +e
remote "if [ ! -S '$lola' ]; then echo 'no LoLA: $lola is not a socket (is the lola service running?)' >&2; exit 3; fi
avail=\$(df -Pk \"\$HOME\" | awk 'NR == 2 {print \$4}')
if [ \"\$avail\" -lt $need_kb ]; then echo \"full disk: \$((avail / 1024)) MB free in \$HOME, the bundle needs $((need_kb / 1024)) MB\" >&2; exit 4; fi
mkdir -p \"\$HOME/nao-soccer.d\" || exit 5
rm -rf \"\$HOME/nao-soccer.d/\"*.partial"
rc=$?
set -e
case $rc in
  0) ;;
  255) fail "unreachable over ssh ($(last_line "$err"))" ;;
  3|4) fail "$(last_line "$err")" ;;
  *) fail "the check before copying failed (exit $rc: $(last_line "$err"))" ;;
esac

# 2. The copy into a new folder; the running install is not touched.
if ! "${rsync_cmd[@]}" 2>"$err" >/dev/null; then
  msg=$(grep -m 1 -E 'No space left|rsync:|ssh:' "$err" || true)
  "${ssh_cmd[@]}" "$target" "rm -rf nao-soccer.d/$stamp.partial" 2>/dev/null || true
  fail "copying the bundle failed (${msg:-$(last_line "$err")}); the previous install was left running"
fi

# 3. The switch: stop softly, rename, start.
# shellcheck disable=SC2016 # expanded on the robot
switch='set -e
cd "$HOME"
new=nao-soccer.d/STAMP
mv "$new.partial" "$new"
if [ -d nao-soccer/config/calibration ]; then cp -a nao-soccer/config/calibration "$new/config/"; fi
systemd=0
if command -v systemctl >/dev/null && systemctl --user show-environment >/dev/null 2>&1; then systemd=1; fi
if [ START = 1 ]; then
  if [ $systemd = 1 ]; then systemctl --user stop nao-soccer 2>/dev/null || true; fi
  for pidfile in nao-soccer.d/run.pid nao-soccer/run.pid; do
    [ -f "$pidfile" ] || continue
    pid=$(cat "$pidfile")
    if kill -TERM "$pid" 2>/dev/null; then
      i=0; while kill -0 "$pid" 2>/dev/null && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
      kill -KILL "$pid" 2>/dev/null || true
    fi
    rm -f "$pidfile"
  done
fi
# An install from before the switch folder (a real directory) moves aside first.
if [ -d nao-soccer ] && [ ! -L nao-soccer ]; then mv nao-soccer "nao-soccer.d/old-$(date +%s)"; fi
ln -sfn "$new" nao-soccer.next
mv -T nao-soccer.next nao-soccer
# Keep the current and the previous install.
ls -1dt nao-soccer.d/*/ | tail -n +3 | while read -r d; do [ "${d%/}" = "$new" ] || rm -rf "$d"; done
[ START = 1 ] || { echo "deploy: installed (not started)"; exit 0; }
if [ $systemd = 1 ]; then
  mkdir -p ~/.config/systemd/user
  cp ~/nao-soccer/nao-soccer.service ~/.config/systemd/user/
  systemctl --user daemon-reload
  systemctl --user enable nao-soccer >/dev/null 2>&1
  systemctl --user start nao-soccer
  sleep 3
  systemctl --user --no-pager status nao-soccer 2>&1 | sed -n '1,5p' || true
  journalctl --user -u nao-soccer -n 15 --no-pager 2>/dev/null || true
else
  nohup ~/nao-soccer/bin/nao-soccer-start >~/nao-soccer/nao-soccer.log 2>&1 </dev/null &
  echo $! >nao-soccer.d/run.pid
  sleep 3
  tail -n 15 ~/nao-soccer/nao-soccer.log
fi'
switch=${switch//STAMP/$stamp}
switch=${switch//START/$start}
set +e
remote "$switch"
rc=$?
set -e
[ $rc = 0 ] || fail "switching to the new install failed (exit $rc: $(last_line "$err"))"
echo "deploy: $target:nao-soccer -> nao-soccer.d/$stamp"
