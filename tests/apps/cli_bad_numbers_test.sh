#!/bin/bash
# Every malformed or out-of-range number on the command line exits 2 (bad input) with a message
# naming the option; NaN and infinity used to pass CLI11's own range checks (silently ignored) and
# parse errors exited 104-109. Usage: cli_bad_numbers_test.sh COMPLY SOURCE_DIR
set -u
comply=$1 source=$2
samples=$source/examples/validate/fr3_cartesian_samples.json
task=$source/examples/sim/step_response.yaml
failures=0
expect_bad() {  # expect_bad OPTION VALUE COMMAND...
  local option=$1 value=$2
  shift 2
  local output status
  output=$("$@" "$option" "$value" 2>&1 >/dev/null)
  status=$?
  if [ "$status" -ne 2 ] || ! grep -q -- "$option" <<<"$output"; then
    echo "FAIL: $* $option $value -> exit $status: $output"
    failures=$((failures + 1))
  fi
}
for value in nan inf -inf -1 abc 1e400; do
  expect_bad --duration "$value" "$comply" sim --robot fr3 --task "$task" --no-plot --out /tmp/cli_bad_numbers
  expect_bad --tolerance "$value" "$comply" validate --robot fr3 --plugin cartesian_impedance \
    --inputs "$samples" --expected "$samples"
  expect_bad --rate "$value" "$comply" run --config "$source/config/sim/cartesian_impedance.yaml" --sim
done
expect_bad --duration 1e6 "$comply" sim --robot fr3 --task "$task" --no-plot --out /tmp/cli_bad_numbers
expect_bad --period 0 "$comply" validate --robot fr3 --plugin cartesian_impedance --inputs "$samples"
if [ "$failures" -ne 0 ]; then
  exit 1
fi
echo "ok: every bad number exits 2 naming its option"
