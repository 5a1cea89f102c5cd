#!/usr/bin/env bash
# A hand-written model in Embedded Coder's conventions, built through comply codegen simulink's
# adapter and CMakeLists.txt against an installed comply, gives the reference plugin's torques on
# the validate samples, takes its tunable parameter from the controller YAML, and runs in comply sim.
# Usage: simulink_plugin_test.sh PREFIX WORKDIR MODEL KIND REFERENCE_PLUGIN SAMPLES PARAMETERS TASK
#          [CONFIG]
# CONFIG: the reference's controller YAML (`plugin: REFERENCE_PLUGIN`; lines ending in
# `# reference only` are dropped for the model); default: the reference's defaults for fr3.
set -euo pipefail
prefix=$1 work=$2 model=$3 kind=$4 reference=$5 samples=$6 parameters=$7 task=$8 config=${9:-}
here=$(cd "$(dirname "$0")" && pwd)
comply=$prefix/bin/comply
rm -rf "$work" && mkdir -p "$work" && cd "$work"
"$comply" codegen simulink --out gen >/dev/null
# The model's code folder with the models' shared rtwtypes.h in it.
cp -r "$here/models/${model}_ert_rtw" model && cp "$here/models/rtwtypes.h" model/
cmake -S gen -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix" \
  -DCOMPLY_MODEL="$model" -DCOMPLY_MODEL_DIR="$work/model" \
  -DCOMPLY_KIND="$kind" -DCOMPLY_PARAMETERS="$parameters" >cmake.log
cmake --build build >build.log
plugin=$work/build/libcomply_$model.so
nm -D --defined-only "$plugin" | grep -q ' T comply_plugin_entry$'

if [ -n "$config" ]; then
  cp "$config" reference.yaml
else
  "$comply" config --defaults --robot fr3 --plugin "$reference" >reference.yaml
fi
sed -e "s#plugin: $reference#plugin: $plugin#" -e '/# reference only$/d' reference.yaml >model.yaml
"$comply" validate --config reference.yaml --inputs "$samples" --out reference.json
grep -q '"torque"' reference.json  # the reference produced torques to compare
"$comply" validate --config model.yaml --inputs "$samples" --expected reference.json \
  --tolerance 1e-12

# The tunable parameter from plugin_parameters: zero (a gain, a damping) must change the torque.
cp model.yaml tuned.yaml
printf '    plugin_parameters:\n      %s: 0.0\n' "${parameters%%;*}" >>tuned.yaml
set +e
"$comply" validate --config tuned.yaml --inputs "$samples" --expected reference.json \
  --tolerance 1e-12 >tuned.log 2>&1
status=$?
set -e
if [ "$status" -ne 1 ]; then
  echo "FAIL: with ${parameters%%;*} = 0 validate returned $status, expected 1 (torques differ)"
  cat tuned.log
  exit 1
fi

timeout 120 "$comply" sim --config model.yaml --task "$task" --out sim --no-plot \
  >sim.log 2>&1 || { cat sim.log; exit 1; }
grep -q "faults *0" sim.log
test -s sim/log.csv
echo "plugin $model: torques match $reference to 1e-12, parameter settable, sim ran"
