#!/usr/bin/env bash
# Builds the libFuzzer targets (LoLA and GameController parsers, the module parameter loader) with
# Debian's clang in build-fuzz (or $NAO_FUZZ_BUILD_DIR) and runs them one after the other, one job each.
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
cmake --build "$b" --target lola_fuzz gamecontroller_fuzz params_fuzz fuzz_seeds -j2
"$b"/bin/fuzz_seeds "$b"/seeds
# The parameter loader starts from the committed parameter files.
mkdir -p "$b"/seeds/params
cp config/parameters/*.json "$b"/seeds/params/
mkdir -p "$b"/findings
for target in lola gamecontroller params; do
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
