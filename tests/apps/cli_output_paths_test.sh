#!/bin/bash
# Where comply writes: a recording's folder must exist (`--record FILE` of comply sim and comply
# run is refused before the run, with a message naming the missing folder, and nothing is made);
# an output folder (`--out DIR` of sim, experiment, codegen, plugin new) is made, but only as its
# last folder. The default out/sim-<robot> still works in a fresh working folder.
# Usage: cli_output_paths_test.sh COMPLY SOURCE_DIR WORK_DIR
set -u
comply=$1 source=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}
expect_refused() {  # expect_refused NEEDLE COMMAND...
  local needle=$1
  shift
  local output status
  output=$(timeout 60 "$@" 2>&1 >/dev/null)
  status=$?
  if [ "$status" -ne 2 ] || ! grep -qF -- "$needle" <<<"$output"; then
    fail "$* -> exit $status: ${output:0:300}"
  fi
}
expect_absent() {
  if [ -e "$1" ]; then
    fail "$1 was made"
  fi
}
config=$source/config/sim/cartesian_impedance.yaml
task=$source/examples/sim/step_response.yaml
sim=("$comply" sim --robot fr3 --config "$config" --task "$task" --duration 0.05 --no-plot)

# A recording in a missing folder: refused before the run (no --out folder, no log).
expect_refused "the folder '$work/missing/deeper' does not exist (create it first: mkdir -p" \
  "${sim[@]}" --out "$work/sim" --record "$work/missing/deeper/run.mcap"
expect_absent "$work/missing"
expect_absent "$work/sim"
expect_refused "the folder '$work/missing' does not exist" \
  "$comply" run --config "$config" --sim --duration 0.05 --transport in_process \
  --record "$work/missing/run.mcap"
expect_absent "$work/missing"
# An output folder whose parent is missing: refused, nothing made.
expect_refused "cannot make the output folder '$work/missing/sim': the folder '$work/missing' does not exist" \
  "${sim[@]}" --out "$work/missing/sim"
expect_absent "$work/missing"
expect_refused "the folder '$work/missing' does not exist" \
  "$comply" experiment chunks --out "$work/missing/chunks"
expect_absent "$work/missing"
expect_refused "the folder '$work/missing' does not exist" \
  "$comply" codegen simulink --out "$work/missing/gen"
expect_absent "$work/missing"
expect_refused "the folder '$work/missing' does not exist" \
  "$comply" plugin new law --kind joint --lang cpp --out "$work/missing/law"
expect_absent "$work/missing"

# Existing folders: the output folder is made, the recording written.
if ! "${sim[@]}" --out "$work/sim" --record "$work/run.mcap" >/dev/null 2>&1; then
  fail "a run into existing folders failed"
fi
[ -f "$work/sim/log.csv" ] || fail "no $work/sim/log.csv"
[ -f "$work/run.mcap" ] || fail "no $work/run.mcap"
# The default output folder, out/sim-fr3, in a working folder without out/.
mkdir -p "$work/fresh"
if ! (cd "$work/fresh" && "${sim[@]}" >/dev/null 2>&1); then
  fail "a run into the default output folder failed"
fi
[ -f "$work/fresh/out/sim-fr3/log.csv" ] || fail "no out/sim-fr3/log.csv in a fresh folder"

if [ "$failures" -ne 0 ]; then
  echo "$failures failures"
  exit 1
fi
echo ok
