#!/usr/bin/env bash
# Installs exactly the Debian 12 packages nao-soccer builds and tests with. Idempotent; run as root.
set -euo pipefail
packages=(
  build-essential cmake pkg-config git
  mold                   # the linker: about four times faster than GNU ld (cmake/Linker.cmake)
  libmujoco-dev          # MuJoCo 2.2.2: physics
  libosmesa6-dev         # off-screen software OpenGL for the simulated cameras
  libegl-dev libegl-mesa0  # --gl egl: EGL headers, Mesa's EGL (a GPU's or its software device)
  libeigen3-dev          # geometry
  libopencv-dev          # image processing, debug drawing, the ball classifier
  libjpeg62-turbo-dev zlib1g-dev  # sim/ImageIO: JPEG decoding, PNG's deflate (imgcodecs is not linked)
  libceres-dev           # least squares (calibration)
  libmsgpack-cxx-dev     # LoLA packets
  libstb-dev             # stb_image: PNG reading and writing, the robot executable's PNG/JPEG decoder
  nlohmann-json3-dev     # JSON config and results
  libcli11-dev           # the declared command line (apps/cli/)
  libtinyxml2-dev        # MJCF scene assembly (prefixing robot copies)
  libgtest-dev           # tests
  rsync                  # robot/deploy/deploy.sh copies the robot bundle
  liblapack-dev libblas-dev libgfortran-12-dev  # OpenCV's LAPACK calls, static in nao-soccer-robot
  flite1-dev             # the robot's voice in the bundle: nao-soccer-say (apps/robot/SayMain.cpp)
  debootstrap            # the Debian 11 root the robot bundle is tested in (tests/robot_bundle.cmake)
  qemu-user              # the robot executable on a CPU without AVX (tests/robot_bundle.cmake)
  clang libclang-rt-14-dev  # the sanitizer build (.ci/run) and the libFuzzer targets (.ci/fuzz.sh)
  chromium-headless-shell   # the match replay's page tested in a real browser (tests/match_replay_test.cpp)
  parallel                  # batch --runner parallel (GNU parallel)
  slurm-wlm munge           # batch --runner slurm on a single-node Slurm (tools/slurm-local.sh; tests/batch_test.cpp)
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present" >&2
  exit 0
fi
sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: missing ${missing[*]}; run as root" >&2; exit 1; }
  sudo="sudo"
fi
echo "install-deps: installing ${missing[*]}" >&2
$sudo env DEBIAN_FRONTEND=noninteractive apt-get update -q
$sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
