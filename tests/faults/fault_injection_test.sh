#!/bin/bash
# Each fault a plugin can have, injected from its 200th step, ends in its defined state:
#   NaN torque     FAULT (holding torque), exit 1, the reason in the summary
#   saturation     SATURATED in the summary, exit 1
#   overrun        every late cycle counted as an overrun
#   crash, abort   the process ends by the signal, naming the plugin and the cycle; log.csv holds
#                  every cycle before it (streamed)
#   endless loop   after the step timeout: named the same way, exit 1, log.csv kept
# Usage: fault_injection_test.sh COMPLY FAULT_PLUGIN SOURCE_DIR WORK_DIR
set -u
comply=$1 plugin=$2 source=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
printf 'task:\n  duration_s: %s\n  command_rate_hz: 100\n  snapshot_every_ms: 0\n  waypoints:\n    - time_s: 0.1\n      position_offset: [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]\n' 1.0 >"$work/hold.yaml"
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}
config() {  # config FAULT FILE
  cat >"$2" <<YAML
fault_test:
  ros__parameters:
    plugin: $plugin
    robot: fr3
    initial:
      stiffness: 200.0
      damping: 20.0
    plugin_parameters:
      fault: $1
      at_step: 200
      overrun_ms: 2.0
YAML
}
run() {  # run NAME FAULT -> sets status, output, rows
  config "$2" "$work/$1.yaml"
  output=$(timeout 60 "$comply" sim --config "$work/$1.yaml" --task "$work/hold.yaml" --no-plot \
    --out "$work/$1" 2>&1)
  status=$?
  rows=$(($(wc -l <"$work/$1/log.csv" 2>/dev/null || echo 1) - 1))
}

run nan 1
[ "$status" -eq 1 ] || fail "nan: exit $status"
grep -q "FAULT: plugin: non-finite torque" <<<"$output" || fail "nan: no fault reason: $output"
[ "$rows" -eq 1000 ] || fail "nan: log has $rows rows, not 1000"

run saturate 2
[ "$status" -eq 1 ] || fail "saturate: exit $status"
grep -q "SATURATED: joint" <<<"$output" || fail "saturate: not reported: $output"

run overrun 3
overruns=$(sed -n 's/^ *overruns *\([0-9]*\) cycles.*/\1/p' <<<"$output")
[ "${overruns:-0}" -ge 790 ] || fail "overrun: ${overruns:-none} overruns reported, expected >= 790"

for crash in crash:4:SIGSEGV abort:6:SIGABRT hang:5:"no cycle has finished"; do
  name=${crash%%:*} rest=${crash#*:}
  run "$name" "${rest%%:*}"
  [ "$status" -ne 0 ] || fail "$name: exit 0"
  grep -q "${rest#*:}.* in cycle 19[89] while plugin '$plugin'" <<<"$output" ||
    fail "$name: no message naming the plugin and cycle: $output"
  [ "$rows" -ge 190 ] || fail "$name: log.csv kept $rows rows of the ~199 before the fault"
done

if [ "$failures" -ne 0 ]; then
  exit 1
fi
echo "ok: NaN, saturation, overrun, crash, abort and an endless loop each end as defined"
