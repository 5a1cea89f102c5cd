#!/usr/bin/env bash
# `comply plugin new --kind hardware` from an installed comply: the generated backend (an arm
# simulated without gravity) builds against the prefix, and the installed `comply run` loads it by
# path and drives it with the robot-neutral joint impedance configuration for one second.
# Usage: hardware_new_test.sh PREFIX WORKDIR
set -euo pipefail
prefix=$1 work=$2
comply=$prefix/bin/comply
name=myarm
rm -rf "$work" && mkdir -p "$work" && cd "$work"
"$comply" plugin new "$name" --kind hardware --out "$name" >files.txt
test -f "$name/CMakeLists.txt" && test -f "$name/$name.cpp" && test -f "$name/README.md"
cd "$name"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix" \
  >../cmake.log 2>&1 || { cat ../cmake.log; exit 1; }
cmake --build build >../build.log || { cat ../build.log; exit 1; }
backend=$PWD/build/libcomply_hardware_$name.so
test -f "$backend"

# The installed configuration, as a user of the prefix would take it.
config=$prefix/share/comply/config/sim/joint_impedance.yaml
status=0
timeout 120 "$comply" run --config "$config" --robot fr3 --hardware "$backend" --duration 1 \
  --priority 0 --name hardware_new_test >../run.log 2>&1 || status=$?
if [ "$status" -ne 0 ]; then
  echo "FAIL: comply run --hardware $backend exited $status:"; cat ../run.log; exit 1
fi
# 1 s at the default 1 kHz: about 1000 cycles, each with a valid measurement.
cycles=$(sed -nE 's/.*comply run: ([0-9]+) cycles.*/\1/p' ../run.log | tail -n 1)
if [ -z "$cycles" ] || [ "$cycles" -le 900 ]; then
  echo "FAIL: expected more than 900 cycles, the summary says '${cycles:-nothing}':"
  cat ../run.log; exit 1
fi
if ! grep -Eq '(^|[^0-9])0 read failures|read failures:? 0([^0-9]|$)' ../run.log; then
  echo "FAIL: the summary does not report 0 read failures:"; cat ../run.log; exit 1
fi
# The skeleton's arm compensates gravity itself: the host must say it adds none.
if ! grep -q 'the hardware compensates gravity itself; comply adds none' ../run.log; then
  echo "FAIL: the host did not take the backend's own gravity compensation into account:"
  cat ../run.log; exit 1
fi
# DDS in its own process: the installed transport program, not the build tree's.
if ! grep -Eq "in its own process \($prefix/.*comply-transport\)" ../run.log; then
  echo "FAIL: the installed comply run did not start the installed comply-transport:"
  cat ../run.log; exit 1
fi
echo "plugin new --kind hardware: built, comply run drove it for $cycles cycles"
