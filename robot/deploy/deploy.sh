#!/usr/bin/env bash
# Builds nao-soccer, copies it with its configuration to a NAO V6 over ssh/rsync and starts it
# (a systemd user unit when the robot has one, else the start script under nohup).
#
# usage: robot/deploy/deploy.sh [options] ROBOT
#   ROBOT                  the NAO's address or ssh host (user nao unless USER@HOST is given)
#   --team N               team number (GameController), default 0 = none
#   --player N             player number 1..20, default 1
#   --field FILE           the venue's field_dimensions.json (default config/field_dimensions.json);
#                          placed as ~/nao-soccer/config/field_dimensions.json on the robot
#   --camera-settings FILE camera resolution/exposure/gain/white balance JSON (optional)
#   --extra "ARGS"         more options for `nao-soccer run` (e.g. "--cameras none")
#   --build-dir DIR        where to build (default build-robot)
#   --toolchain FILE       CMake toolchain file for the robot's OS (cross-compiling)
#   --no-build             use the binary already in --build-dir
#   --no-bundle-libs       do not copy the binary's shared libraries along
#   --no-start             copy only
#   --dry-run              build and stage locally, print the ssh/rsync commands, touch no robot
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
team=0 player=1 field="$root/config/field_dimensions.json" camera_settings="" extra=""
build_dir="$root/build-robot" toolchain="" do_build=1 bundle=1 start=1 dry=0 robot=""
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
    -h|--help) sed -n '2,21p' "$0"; exit 0 ;;
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

if [ "$do_build" = 1 ]; then
  cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release ${toolchain:+-DCMAKE_TOOLCHAIN_FILE="$toolchain"} >/dev/null
  cmake --build "$build_dir" --target nao-soccer -j2
fi
binary="$build_dir/bin/nao-soccer"
[ -x "$binary" ] || die "$binary: not built (drop --no-build)"

# The folder the robot gets, exactly: ~/nao-soccer = NAO_SOCCER_HOME.
stage="$build_dir/deploy-stage"
rm -rf "$stage"
mkdir -p "$stage/bin" "$stage/config" "$stage/lib" "$stage/models/vision"
cp "$binary" "$stage/bin/nao-soccer"
# The ball classifier's weights (perception/vision/BallClassifier.h).
cp "$root/models/vision/ball_classifier.yml" "$stage/models/vision/"
cp "$root/robot/deploy/nao-soccer-start" "$stage/bin/"
cp "$root/robot/deploy/nao-soccer.service" "$stage/"
cp "$field" "$stage/config/field_dimensions.json"
# The module pipeline's providers and the modules' parameters (with per-robot overlays).
cp "$root/config/modules.json" "$stage/config/"
cp -r "$root/config/parameters" "$stage/config/"
[ ! -d "$root/config/robots" ] || cp -r "$root/config/robots" "$stage/config/"
[ -z "$camera_settings" ] || cp "$camera_settings" "$stage/config/camera_settings.json"
printf 'TEAM=%s\nPLAYER=%s\nEXTRA_ARGS="%s"\n' "$team" "$player" "$extra" >"$stage/nao-soccer.env"
if [ "$bundle" = 1 ] && [ -z "$toolchain" ]; then
  # Everything the binary links but the C library itself: the robot's OS has no MuJoCo or
  # OpenCV of these versions. (Cross builds take their libraries from the toolchain's sysroot.)
  ldd "$binary" | awk '/=> \// {print $3}' | grep -Ev '/(libc|libm|libdl|libpthread|librt|ld-linux[^/]*)\.so' |
    while read -r lib; do cp -L "$lib" "$stage/lib/"; done
fi
echo "deploy: staged $(du -sh "$stage" | cut -f1) in $stage"

# The robot's own calibration (config/calibration/<head id>.json, written there by the
# calibration) is neither sent nor deleted.
rsync_cmd=(rsync -az --delete --exclude 'config/calibration/' "$stage/" "$target:nao-soccer/")
# Runs on the robot (expanded there, hence the single quotes).
# shellcheck disable=SC2016
remote='set -e
if command -v systemctl >/dev/null && systemctl --user show-environment >/dev/null 2>&1; then
  mkdir -p ~/.config/systemd/user
  cp ~/nao-soccer/nao-soccer.service ~/.config/systemd/user/
  systemctl --user daemon-reload
  systemctl --user enable nao-soccer >/dev/null 2>&1
  systemctl --user restart nao-soccer
  sleep 3
  systemctl --user --no-pager status nao-soccer | head -n 5
  journalctl --user -u nao-soccer -n 15 --no-pager 2>/dev/null || true
else
  if [ -f ~/nao-soccer/run.pid ]; then kill "$(cat ~/nao-soccer/run.pid)" 2>/dev/null || true; sleep 1; fi
  nohup ~/nao-soccer/bin/nao-soccer-start >~/nao-soccer/nao-soccer.log 2>&1 &
  echo $! >~/nao-soccer/run.pid
  sleep 3
  tail -n 15 ~/nao-soccer/nao-soccer.log
fi'
if [ "$dry" = 1 ]; then
  echo "deploy: dry run, would run:"
  printf '  %q' "${rsync_cmd[@]}"; echo
  [ "$start" = 1 ] && echo "  ssh $target <<start script: systemd user unit nao-soccer, or nohup nao-soccer-start>>"
  exit 0
fi
"${rsync_cmd[@]}"
[ "$start" = 1 ] || { echo "deploy: copied to $target:nao-soccer (not started)"; exit 0; }
# shellcheck disable=SC2029
ssh "$target" "$remote"
