#!/usr/bin/env bash
# comply codegen simulink's comply_buses.m, run by Octave against the Simulink stand-in, must list
# the same elements (names, order, counts, types, offsets) and sizes as abi.h.
# Usage: buses_octave_test.sh COMPLY ABI_LAYOUT_DUMP WORKDIR
set -euo pipefail
comply=$1 dump=$2 work=$3 here=$(cd "$(dirname "$0")" && pwd)
if ! command -v octave >/dev/null; then
  echo "SKIP: octave not installed (apt-get install octave)"
  exit 77
fi
rm -rf "$work" && mkdir -p "$work"
"$comply" codegen simulink --out "$work/gen" >/dev/null
"$dump" >"$work/abi.txt"
# Octave may print a harmless message while exiting; only stdout is compared.
(cd "$work/gen" && timeout 120 octave --no-gui --no-window-system --quiet --norc \
   --path "$here/stand_in" --path "$here" --eval "print_buses") >"$work/octave.txt"
diff -u "$work/abi.txt" "$work/octave.txt"
test "$(wc -l <"$work/abi.txt")" -gt 40
echo "buses match abi.h: $(grep -c sizeof "$work/abi.txt") buses, $(grep -vc sizeof "$work/abi.txt") elements"
