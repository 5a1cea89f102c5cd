#!/bin/bash
# Each fault a plugin can have, injected from its 200th step, ends in its defined state:
#   NaN torque     FAULT (holding torque), exit 1, the reason in the summary
#   saturation     SATURATED in the summary, exit 1; 1e300 N m as well, every torque sent within
#                  the FR3's effort limits (87 N m, 12 N m on joints 4-6)
#   overrun        every late cycle counted as an overrun; the run itself is not failed (exit 0): in
#                  simulation the plant waits for the law
#   crash, abort   the process ends by the signal (exit 139, 134), naming the plugin and the cycle;
#                  log.csv holds every cycle before it (streamed)
#   endless loop   after the step timeout: named the same way, exit 1, log.csv kept
#   an exception   (THROWING_PLUGIN, a C++ law on the raw ABI throwing from its first cycle's step)
#                  FAULT with the reason 'step threw an exception', exit 1, the process lives on
# Usage: fault_injection_test.sh COMPLY FAULT_PLUGIN THROWING_PLUGIN SOURCE_DIR WORK_DIR
set -u
comply=$1 plugin=$2 throwing_plugin=$3 source=$4 work=$5
rm -rf "$work" && mkdir -p "$work"
task() {  # task FILE TIME OFFSET_0
  printf 'task:\n  duration_s: 1.0\n  command_rate_hz: 100\n  snapshot_every_ms: 0\n  waypoints:\n    - time_s: %s\n      position_offset: [%s, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]\n' "$2" "$3" >"$1"
}
task "$work/hold.yaml" 0.1 0.0
# Joint 0 asked 3 rad away: every command from ~0.38 s on is a pose_jump rejection.
task "$work/far.yaml" 0.5 3.0
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}
config() {  # config FAULT FILE [PLUGIN]
  cat >"$2" <<YAML
fault_test:
  ros__parameters:
    plugin: ${3:-$plugin}
    robot: fr3
    initial:
      stiffness: 200.0
      damping: 20.0
    stability_guard:
      enabled: false  # these are the law's own faults; a chasing arm would overspeed first
    governor:
      enabled: false  # and the governor would take a saturating law's torque back first
    plugin_parameters:
      fault: $1
      at_step: 200
      overrun_ms: 2.0
YAML
}
run() {  # run NAME FAULT [PLUGIN] [TASK] -> sets status, output, rows
  config "$2" "$work/$1.yaml" "${3:-}"
  output=$(timeout 60 "$comply" sim --config "$work/$1.yaml" --task "${4:-$work/hold.yaml}" \
    --no-plot --out "$work/$1" 2>&1)
  status=$?
  rows=$(($(wc -l <"$work/$1/log.csv" 2>/dev/null || echo 1) - 1))
}

run nan 1
[ "$status" -eq 1 ] || fail "nan: exit $status"
grep -q "FAULT: plugin: non-finite torque" <<<"$output" || fail "nan: no fault reason: $output"
[ "$rows" -eq 1000 ] || fail "nan: log has $rows rows, not 1000"

# The fault's reason is its own summary line: rejection notes after it never push it out.
run nan_then_rejections 1 "" "$work/far.yaml"
[ "$status" -eq 1 ] || fail "nan_then_rejections: exit $status"
notes=$(grep -c "note: .* command rejected: pose_jump" <<<"$output")
[ "$notes" -ge 8 ] || fail "nan_then_rejections: $notes rejection notes, the case needs at least 8"
grep -q "FAULT: plugin: non-finite torque" <<<"$output" ||
  fail "nan_then_rejections: the fault reason is lost: $output"

run saturate 2
[ "$status" -eq 1 ] || fail "saturate: exit $status"
grep -q "SATURATED: joint" <<<"$output" || fail "saturate: not reported: $output"

run huge 7
[ "$status" -eq 1 ] || fail "huge: exit $status"
grep -q "SATURATED: joint" <<<"$output" || fail "huge: not reported: $output"
# Columns 16-22 are tau0..tau6.
beyond=$(awk -F, 'NR > 1 { for (j = 0; j < 7; ++j) { t = $(16 + j); limit = j < 4 ? 87 : 12;
  if (!(t <= limit && t >= -limit)) { print NR ": tau" j " = " t; exit } } }' "$work/huge/log.csv")
[ -z "$beyond" ] || fail "huge: a torque beyond the effort limit was sent: $beyond"
[ "$rows" -eq 1000 ] || fail "huge: log has $rows rows, not 1000"

run overrun 3
overruns=$(sed -n 's/^ *overruns *\([0-9]*\) cycles.*/\1/p' <<<"$output")
[ "${overruns:-0}" -ge 790 ] || fail "overrun: ${overruns:-none} overruns reported, expected >= 790"
[ "$status" -eq 0 ] || fail "overrun: exit $status"

# NAME:FAULT:EXIT:MESSAGE; 128 + the signal's number for a process that ends by it.
for crash in crash:4:139:SIGSEGV abort:6:134:SIGABRT hang:5:1:"no cycle has finished"; do
  IFS=: read -r name fault expected message <<<"$crash"
  run "$name" "$fault"
  [ "$status" -eq "$expected" ] || fail "$name: exit $status, not $expected"
  grep -q "$message.* in cycle 19[89] while plugin '$plugin'" <<<"$output" ||
    fail "$name: no message naming the plugin and cycle: $output"
  [ "$rows" -ge 190 ] || fail "$name: log.csv kept $rows rows of the ~199 before the fault"
done

run throw 0 "$throwing_plugin"
[ "$status" -eq 1 ] || fail "throw: exit $status"
grep -q "FAULT: plugin: step threw an exception" <<<"$output" ||
  fail "throw: no fault reason: $output"
[ "$rows" -eq 1000 ] || fail "throw: log has $rows rows, not 1000 (the run must go on in FAULT)"

if [ "$failures" -ne 0 ]; then
  exit 1
fi
echo "ok: NaN, saturation, overrun, crash, abort, an endless loop and an exception end as defined"
