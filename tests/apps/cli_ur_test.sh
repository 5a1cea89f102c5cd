#!/bin/bash
# `comply run --hardware ur` against `comply ur-emulator`, two processes as a user runs them: the
# run ends at its --duration with exit 0, says which controller it drove and what its link
# counted; the emulator saw the program run and every package answered, then its watchdog stop
# when comply left. Wrong options end in exit 2 naming them, before anything connects.
# Usage: cli_ur_test.sh COMPLY SOURCE_DIR WORK_DIR
set -u
comply=$1 source=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}
sed -e 's/robot: fr3/robot: ur5e/' \
  -e 's/    command_timeout_s: 0.5/    command_timeout_s: 0.5\n    output: {mode: position}/' \
  "$source/config/sim/cartesian_impedance.yaml" >"$work/ur.yaml"

"$comply" ur-emulator --rtde-port 0 --script-port 0 --dashboard-port 0 --duration 8 \
  >"$work/emulator.txt" 2>&1 &
emulator=$!
for _ in $(seq 50); do
  grep -q "dashboard" "$work/emulator.txt" && break
  sleep 0.1
done
rtde=$(grep -o "RTDE [0-9]*" "$work/emulator.txt" | cut -d' ' -f2)
script=$(grep -o "secondary [0-9]*" "$work/emulator.txt" | cut -d' ' -f2)
[ -n "$rtde" ] || fail "the emulator did not say its ports: $(cat "$work/emulator.txt")"
output=$(timeout 60 "$comply" run --config "$work/ur.yaml" --rate 500 --hardware ur \
  --hardware-option robot_ip=127.0.0.1 --hardware-option "rtde_port=$rtde" \
  --hardware-option "script_port=$script" --transport in_process --duration 2 --priority 0 2>&1)
status=$?
[ "$status" -eq 0 ] || fail "comply run exited $status: $output"
grep -qF "on a UR controller at 127.0.0.1 (PolyScope 5.23.0, servoj)" <<<"$output" ||
  fail "the run does not name the controller: $output"
grep -qE "UR link: [0-9]+ data packages, 0 controller cycles without one" <<<"$output" ||
  fail "no link summary: $output"
wait "$emulator"
last=$(tail -1 "$work/emulator.txt")
grep -qE "answered [1-9][0-9]{2,}" <<<"$last" || fail "the emulator applied no answers: $last"
grep -qF "watchdog stops 1" <<<"$last" || fail "no watchdog stop once comply left: $last"

expect_error() {  # expect_error NEEDLE ARGS...
  local needle=$1
  shift
  local out
  out=$(timeout 30 "$comply" run --config "$work/ur.yaml" --hardware ur --transport in_process \
    --priority 0 --duration 0.1 "$@" 2>&1)
  local code=$?
  if [ "$code" -ne 2 ] || ! grep -qF -- "$needle" <<<"$out"; then
    fail "run --hardware ur $* -> exit $code (expected 2, '$needle'): $out"
  fi
}
expect_error "needs the controller's address: --hardware-option robot_ip=IPV4" --rate 500
expect_error "runs its cycle at 500 Hz: run the controller at --rate 500" \
  --hardware-option robot_ip=127.0.0.1
expect_error "no hardware option 'speed'" --rate 500 --hardware-option robot_ip=127.0.0.1 \
  --hardware-option speed=3
expect_error "rtde_port=70000 is not a TCP port" --rate 500 \
  --hardware-option robot_ip=127.0.0.1 --hardware-option rtde_port=70000
expect_error "cannot connect to 127.0.0.1:1" --rate 500 --hardware-option robot_ip=127.0.0.1 \
  --hardware-option rtde_port=1

[ "$failures" -eq 0 ] && echo ok
