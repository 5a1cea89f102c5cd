#!/bin/bash
# A robot folder whose URDF gives a moving link a mass urdfdom cannot read ("nan": urdfdom logged
# it and read 0 kg, so `validate` passed what MuJoCo refused in `sim`) exits 2 from both, naming
# the file, the link and the attribute. Usage: cli_bad_urdf_test.sh COMPLY SOURCE_DIR WORK_DIR
set -u
comply=$1 source=$2 work=$3
rm -rf "$work" && mkdir -p "$work/nan_mass"
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
# The FR3 with link 3's mass (the first <mass> after its <link>) written as "nan".
cp "$source/robots/fr3/robot.yaml" "$work/nan_mass/"
sed '/<link name="fr3_link3">/,/<mass /s/<mass value="[^"]*"/<mass value="nan"/' \
  "$source/robots/fr3/fr3.urdf" >"$work/nan_mass/fr3.urdf"
nan_mass="link 'fr3_link3': <mass value=\"nan\">: not a finite number (in '$work/nan_mass/fr3.urdf')"
expect_refused "$nan_mass" "$comply" validate --robot "$work/nan_mass" \
  --plugin cartesian_impedance --inputs "$source/examples/validate/fr3_cartesian_samples.json"
expect_refused "$nan_mass" "$comply" sim --robot "$work/nan_mass" \
  --task "$source/examples/sim/step_response.yaml" --duration 0.1 --no-plot --out "$work/sim"
if [ "$failures" -ne 0 ]; then
  exit 1
fi
echo "ok: a URDF with an unreadable mass exits 2 naming the file, the link and the attribute"
