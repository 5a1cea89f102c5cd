#!/bin/bash
# Input files that are not what they claim end in exit 2 with a message naming them, never in a
# crash or an exhausted memory: JSON nested 100,000 levels deep (a stack overflow before), a
# device as an inputs file or as a scene's tool (read until bad_alloc before), a file larger than
# an input may be, a symlink loop (reported as a missing file before), a URDF whose link mass
# urdfdom cannot read ("nan": urdfdom read 0 kg, so `validate` passed what MuJoCo refused).
# Usage: cli_bad_files_test.sh COMPLY SOURCE_DIR WORK_DIR
set -u
comply=$1 source=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
failures=0
expect_refused() {  # expect_refused NEEDLE COMMAND...
  local needle=$1
  shift
  local output status
  output=$(timeout 60 "$@" 2>&1 >/dev/null)
  status=$?
  if [ "$status" -ne 2 ] || ! grep -qF -- "$needle" <<<"$output"; then
    echo "FAIL: $* -> exit $status: ${output:0:300}"
    failures=$((failures + 1))
  fi
}
python3 - "$work" <<'PY'
import sys
work = sys.argv[1]
deep = '{"a":' * 100000 + '1' + '}' * 100000
with open(f'{work}/deep_command.json', 'w') as f:
    f.write('[{"q": [0, -0.78, 0, -2.36, 0, 1.57, 0.78], "dq": [0, 0, 0, 0, 0, 0, 0], '
            f'"command": {deep}}}]')
with open(f'{work}/deep.json', 'w') as f:
    f.write('[' * 100000 + ']' * 100000)
with open(f'{work}/huge.json', 'w') as f:
    f.write('[' + ' ' * (17 << 20) + ']')
with open(f'{work}/device_tool.yaml', 'w') as f:
    f.write('task:\n  duration_s: 0.1\n  scene:\n    tool: /dev/zero\n'
            '  waypoints:\n    - time_s: 0.05\n      position_offset: [0.0, 0.0, 0.0]\n')
PY
samples=$source/examples/validate/fr3_cartesian_samples.json
validate=("$comply" validate --robot fr3 --plugin cartesian_impedance)
expect_refused "nested deeper than 64 levels" "${validate[@]}" --inputs "$work/deep_command.json"
expect_refused "nested deeper than 64 levels" "${validate[@]}" --inputs "$samples" --expected "$work/deep.json"
expect_refused "'/dev/zero' is not a regular file" "${validate[@]}" --inputs /dev/zero
expect_refused "more than an input file may be" "${validate[@]}" --inputs "$work/huge.json"
expect_refused "'/dev/zero' is not a regular file" "$comply" sim --robot fr3 \
  --task "$work/device_tool.yaml" --no-plot --out "$work/sim"
# Symlink loops, as each kind of input file: named as a loop, with the path.
ln -s loop.yaml "$work/loop.yaml"
loop="'$work/loop.yaml': too many levels of symbolic links (a symlink loop)"
task=$source/examples/sim/step_response.yaml
expect_refused "$loop" "$comply" sim --robot fr3 --config "$work/loop.yaml" --task "$task" \
  --no-plot --out "$work/sim"
expect_refused "$loop" "$comply" sim --robot fr3 --task "$work/loop.yaml" --no-plot \
  --out "$work/sim"
expect_refused "$loop" "${validate[@]}" --inputs "$work/loop.yaml"
ln -s robot_loop "$work/robot_loop"
expect_refused "robot folder '$work/robot_loop' cannot be read: too many levels of symbolic links" \
  "$comply" sim --robot "$work/robot_loop" --task "$task" --no-plot --out "$work/sim"
# The FR3 with link 3's mass (the first <mass> after its <link>) written as "nan": named with the
# file, the link and the attribute, by validate and sim alike.
mkdir -p "$work/nan_mass"
cp "$source/robots/fr3/robot.yaml" "$work/nan_mass/"
sed '/<link name="fr3_link3">/,/<mass /s/<mass value="[^"]*"/<mass value="nan"/' \
  "$source/robots/fr3/fr3.urdf" >"$work/nan_mass/fr3.urdf"
nan_mass="link 'fr3_link3': <mass value=\"nan\">: not a finite number (in '$work/nan_mass/fr3.urdf')"
expect_refused "$nan_mass" "$comply" validate --robot "$work/nan_mass" \
  --plugin cartesian_impedance --inputs "$source/examples/validate/fr3_cartesian_samples.json"
expect_refused "$nan_mass" "$comply" sim --robot "$work/nan_mass" --task "$task" --duration 0.1 \
  --no-plot --out "$work/sim"
if [ "$failures" -ne 0 ]; then
  exit 1
fi
echo "ok: every malformed input file exits 2 naming it"
