#!/usr/bin/env bash
# `comply plugin new` from an installed comply: the generated project configures and builds against
# the prefix, its own test passes, and the plugin runs through comply validate on the generated
# samples and through comply sim with the generated controller YAML and task.
# Usage: plugin_new_test.sh PREFIX WORKDIR KIND LANG
set -euo pipefail
prefix=$1 work=$2 kind=$3 lang=$4
comply=$prefix/bin/comply
name=law_${kind}_${lang}
rm -rf "$work" && mkdir -p "$work" && cd "$work"
"$comply" plugin new "$name" --kind "$kind" --lang "$lang" >files.txt
cd "$name"
# Every template name and placeholder is replaced (the C laws' shared lifecycle included).
if grep -rn "COMPLY_TEMPLATE\|my_law\|MyLaw" .; then
  echo "a template placeholder is left in the generated project" >&2
  exit 1
fi
[ "$lang" != c ] || grep -q "static void\* create(" "$name.c"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix" >../cmake.log
cmake --build build >../build.log || { cat ../build.log; exit 1; }
(cd build && ctest --output-on-failure) >../ctest.log || { cat ../ctest.log; exit 1; }
"$comply" validate --plugin "build/libcomply_$name.so" --robot fr3 --inputs fr3_samples.json \
  --out ../validate.json
timeout 120 "$comply" sim --config "$name.yaml" --task task.yaml --out ../sim --no-plot \
  >../sim.log 2>&1 || { cat ../sim.log; exit 1; }
grep -q "faults *0" ../sim.log
test -s ../sim/log.csv
echo "plugin new $kind/$lang: built, own test passed, validate and sim ran"
