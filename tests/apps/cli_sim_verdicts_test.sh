#!/bin/bash
# `comply sim` fails (exit 1) on what used to pass as success: a task whose final target was
# refused (a target 10 m or 1e300 m away: the error was measured against the last accepted
# reference) and a law that drives the arm beyond what it can do (stiffness 9e5 N/m on a 2 cm step:
# a joint overspeeds, and the stability guard ends it in FAULT); a normal step still exits 0. A stiffness beyond any arm (1e9 N/m) does not run at all (exit 2,
# field and limit named).
# Usage: cli_sim_verdicts_test.sh COMPLY SOURCE_DIR WORK_DIR
set -u
comply=$1 source=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
step() {  # step FILE OFFSET_X DURATION
  printf 'task:\n  duration_s: %s\n  command_rate_hz: 100\n  snapshot_every_ms: 0\n  waypoints:\n    - time_s: 0.1\n      position_offset: [%s, 0.0, 0.0]\n' "$3" "$2" >"$1"
}
step "$work/far.yaml" 10.0 0.5
step "$work/huge.yaml" 1.0e300 0.5
step "$work/step.yaml" 0.02 1.5
sed 's/stiffness_translational: 3000.0/stiffness_translational: 9.0e5/' \
  "$source/config/sim/cartesian_impedance.yaml" >"$work/stiff.yaml"
# The same with the gain bound and the governor off: what stops such gains then is the stability
# guard (tests/sim/stop_means_stop_test.cpp has the governor keeping them below the speeds).
sed 's/command_timeout_s: 0.5/command_timeout_s: 0.5\n    validation: {max_wn_period: 0.0}\n    governor: {enabled: false}/' \
  "$work/stiff.yaml" >"$work/stiff_unbounded.yaml"
sed 's/stiffness_translational: 3000.0/stiffness_translational: 1.0e9/' \
  "$source/config/sim/cartesian_impedance.yaml" >"$work/absurd.yaml"
failures=0
run() {  # run EXPECTED_EXIT NEEDLE ARGS...
  local expected=$1 needle=$2
  shift 2
  local output status
  output=$(timeout 120 "$comply" sim --no-plot "$@" 2>&1)
  status=$?
  if [ "$status" -ne "$expected" ] || ! grep -qF -- "$needle" <<<"$output"; then
    echo "FAIL: sim $* -> exit $status (expected $expected, '$needle'):"
    grep -v "note:" <<<"$output" | head -20
    failures=$((failures + 1))
  fi
}
run 1 "TARGET NOT REACHED: the task's last command was refused (pose_jump" \
  --robot fr3 --task "$work/far.yaml" --out "$work/far"
run 1 "TARGET NOT REACHED: the task's last command was refused (pose_jump: target is 1e+300 m" \
  --robot fr3 --task "$work/huge.yaml" --out "$work/huge"
run 2 "stiffness_translational 9e+05 N/m is above what the arm renders stably, 1.04e+05 N/m" \
  --config "$work/stiff.yaml" --task "$work/step.yaml" --out "$work/stiff"
run 1 "FAULT: stability guard: " --config "$work/stiff_unbounded.yaml" --task "$work/step.yaml" \
  --out "$work/stiff_unbounded"
run 2 "stiffness_translational has an entry of 1000000000 N/m, above the limit of 1000000 N/m" \
  --config "$work/absurd.yaml" --task "$work/step.yaml" --out "$work/absurd"
run 0 "faults                0" --robot fr3 --task "$work/step.yaml" --out "$work/normal"
if [ "$failures" -ne 0 ]; then
  exit 1
fi
echo "ok: refused targets and a runaway fail the run; absurd or unrenderable gains do not run"
