#!/bin/bash
# `comply run --hardware franka` against `comply franka-emulator`, two processes as a user runs
# them: the run ends at its --duration with exit 0, names the robot and what its link counted;
# a reflex the emulator injects is a FAULT the run names at its end. Wrong options end in exit 2
# naming them, before anything connects.
# Usage: cli_franka_test.sh COMPLY SOURCE_DIR WORK_DIR
set -u
comply=$1 source=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}
config="$source/config/sim/cartesian_impedance.yaml"

start_emulator() {  # start_emulator EXTRA... ; sets $emulator and $port
  "$comply" franka-emulator --command-port 0 --duration 10 "$@" >"$work/emulator.txt" 2>&1 &
  emulator=$!
  for _ in $(seq 50); do
    grep -q "127.0.0.1:" "$work/emulator.txt" && break
    sleep 0.1
  done
  port=$(grep -o "127.0.0.1:[0-9]*" "$work/emulator.txt" | cut -d: -f2)
  [ -n "$port" ] || fail "the emulator did not say its port: $(cat "$work/emulator.txt")"
}
run_franka() {  # run_franka SECONDS
  timeout 60 "$comply" run --config "$config" --rate 1000 --hardware franka \
    --hardware-option robot_ip=127.0.0.1 --hardware-option client=comply \
    --hardware-option "command_port=$port" --transport in_process --duration "$1" \
    --priority 0 2>&1
}

start_emulator
output=$(run_franka 2)
status=$?
[ "$status" -eq 0 ] || fail "comply run exited $status: $output"
grep -qF "on a Franka robot at 127.0.0.1 (comply's FCI client, protocol version 7" <<<"$output" ||
  fail "the run does not name the robot: $output"
grep -qE "Franka link: [0-9]+ states, [0-9]+ skipped, 1 torque controls started, 0 stops" \
  <<<"$output" || fail "no link summary: $output"
if grep -qF "faulted" <<<"$output"; then fail "a fault in a quiet run: $output"; fi
kill "$emulator" 2>/dev/null
wait "$emulator"

start_emulator --reflex-at 2
output=$(run_franka 3)
grep -qF "faulted 1 time, last: robot: reflex joint_reflex" <<<"$output" ||
  fail "the reflex is not named at the end: $output"
sleep 1.2  # the emulator's next status line
kill "$emulator" 2>/dev/null
wait "$emulator"
grep -qF "reflexes 1 (last: joint_reflex)" "$work/emulator.txt" ||
  fail "the emulator made no reflex: $(tail -2 "$work/emulator.txt")"

expect_error() {  # expect_error NEEDLE ARGS...
  local needle=$1
  shift
  local out
  out=$(timeout 30 "$comply" run --config "$config" --hardware franka --transport in_process \
    --priority 0 --duration 0.1 "$@" 2>&1)
  local code=$?
  if [ "$code" -ne 2 ] || ! grep -qF -- "$needle" <<<"$out"; then
    fail "run --hardware franka $* -> exit $code (expected 2, '$needle'): $out"
  fi
}
expect_error "needs the robot's address: --hardware-option robot_ip=IPV4" --rate 1000
expect_error "run the controller at --rate 1000" --hardware-option robot_ip=127.0.0.1 --rate 500
expect_error "no hardware option 'speed=3'" --rate 1000 --hardware-option robot_ip=127.0.0.1 \
  --hardware-option speed=3
expect_error "command_port=70000 is not a TCP port" --rate 1000 \
  --hardware-option robot_ip=127.0.0.1 --hardware-option command_port=70000
expect_error "cannot connect to the Franka robot at 127.0.0.1:1" --rate 1000 \
  --hardware-option robot_ip=127.0.0.1 --hardware-option client=comply \
  --hardware-option command_port=1
out=$(timeout 10 "$comply" franka-emulator --reflex no_such_error --duration 0.1 2>&1)
code=$?
[ "$code" -eq 2 ] && grep -qF "not one of the robot's errors" <<<"$out" ||
  fail "franka-emulator --reflex no_such_error -> exit $code: $out"

[ "$failures" -eq 0 ] && echo ok
