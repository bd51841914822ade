#!/usr/bin/env bash
# Builds the libFuzzer targets (LoLA and GameController parsers, the module parameter loader, the
# command line, the calibration log reader, the recorded camera matrices, the venues) with
# Debian's clang in build-fuzz (or $NAO_FUZZ_BUILD_DIR)
# and runs them one after the other, one job each.
#   bash .ci/fuzz.sh              1,000,000 executions each (the figure the README quotes)
#   bash .ci/fuzz.sh -runs N      N executions each
#   bash .ci/fuzz.sh -seconds S   S seconds each (CI)
# Exit 0 when no target found a crash; findings are written to <build dir>/findings/.
set -euo pipefail
cd "$(dirname "$0")/.."
b="${NAO_FUZZ_BUILD_DIR:-build-fuzz}"
limit="-runs=1000000"
case "${1:-}" in
  -runs) limit="-runs=${2:?}" ;;
  -seconds) limit="-max_total_time=${2:?}" ;;
  "") ;;
  *) echo "usage: $0 [-runs N | -seconds S]" >&2; exit 2 ;;
esac
cmake -S . -B "$b" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DNAO_FUZZ=ON \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ >/dev/null
cmake --build "$b" --target lola_fuzz gamecontroller_fuzz params_fuzz argv_fuzz calibration_log_fuzz camera_matrix_fuzz venues_fuzz fuzz_seeds -j2
"$b"/bin/fuzz_seeds "$b"/seeds
# The parameter loader starts from the committed parameter files.
mkdir -p "$b"/seeds/params
cp config/parameters/*.json "$b"/seeds/params/
# Recorded camera matrices start from the real goal-box frames' (beside the checkout, when there).
mkdir -p "$b"/seeds/camera_matrix
cp ../shared/data/real-goalbox-images/*.json "$b"/seeds/camera_matrix/ 2>/dev/null || true
printf '{"position":"Top","camera_matrix":{"camera_to_ground":{"rotation":[0,0.13,0,0.99],"translation":[0,0,0.48]},"focal_length":[608,609],"optical_center":[320,240]}}' >"$b"/seeds/camera_matrix/minimal.json
# The venues start from the committed file.
mkdir -p "$b"/seeds/venues
cp config/venues.json "$b"/seeds/venues/
# Command lines, their words separated by NUL bytes: a valid one of every command and a few bad.
mkdir -p "$b"/seeds/argv
i=0
while IFS= read -r line; do
  printf '%s' "$line" | tr ' ' '\0' >"$b"/seeds/argv/seed$i
  i=$((i + 1))
done <<'SEEDS'
render --camera bottom --pose -3.2,-3,90 --head 35,12 --out x.png --json -
run --backend sim --seconds 2 --pose 0,0,0 --cameras off --images d
run --backend nao --team 5 --player 2 --gc-address 127.0.0.1 --cameras none
bench sim --seconds 5 --repeats 1
bench perception --frames 10 --camera bottom --lighting sweep
bench calibration --miscalibration 1,2,3,-1,-2,-3
perceive x.png --size 640x480 --head 10,5 --scale 2
perceive x.jpg --camera bottom --camera-matrix x.json --out y.png --json -
perceive x.png --torso 3,-2 --head 0,20
eval real --dir d --failures f --json -
render --camera-matrix x.json --lighting noise=0 --out t.png
eval perception --trials 3 --max-offset 2 --images d --images-every 2
eval calibration --trials 2 --solver ceres
eval walk --trials 2 --seconds 10 --randomize
eval walk-to --trials 1
eval getup --seconds 5
walk --vx 300 --vtheta -20 --seconds 3
walk --to 1,0.5,90 --randomize
kick --trials 2
train ball --scenes 10 --hidden 8
calibrate --solver ceres --compare --start left --placement-error 0.1,0,5 --save --store d
match --seconds 5 --half 30 --randomize --lighting dark --opponent baseline
eval match --games 3 --seconds 20 --opponent self --rows r.jsonl
match --situation tests/situations/goal.json --replay r.html
batch eval challenge --seeds 1-40,45 --randomize --runner slurm --chunk 2 --dir d --resume
batch eval localization --trials 3 --runner parallel --sshlogin 2/:,host --jobs 4 --json -
eval localization --seeds 5,7-9 --seconds 5 --rows r.jsonl
render --seed -1 --pose nan,1,2 --out
eval bogus --trials 99999999999
SEEDS
mkdir -p "$b"/findings
for target in lola gamecontroller params argv calibration_log camera_matrix venues; do
  corpus="$b"/corpus/$target
  mkdir -p "$corpus"
  log="$b"/$target.log
  # The GameController target binds a UDP socket on loopback once; nothing is sent anywhere.
  if ! "$b"/bin/${target}_fuzz "$limit" -dict=tests/fuzz/$target.dict -max_len=4096 \
      -artifact_prefix="$b"/findings/$target- -print_final_stats=1 \
      "$corpus" "$b"/seeds/$target >"$log" 2>&1; then
    tail -n 40 "$log" >&2
    echo "fuzz: $target FOUND A CRASH (input in $b/findings/, log $log)" >&2
    exit 1
  fi
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo "?")
  secs=$(grep -o 'Done [0-9]* runs in [0-9]* second' "$log" | grep -o 'in [0-9]*' | grep -o '[0-9]*' || echo "?")
  echo "fuzz: $target: $runs executions in ${secs:-?} s, 0 crashes"
done
