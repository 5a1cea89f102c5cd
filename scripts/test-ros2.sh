#!/bin/bash
# make test-ros2: builds the ROS 2 packages under ros2/ with colcon against this build's comply and
# runs ros2/test/system_test.py. Needs ROS 2 Humble sourced (on Ubuntu 22.04:
# `source /opt/ros/humble/setup.bash`); `make test` never does.
# Usage: scripts/test-ros2.sh BUILD_DIR
set -eo pipefail
build=$(cd "${1:-build}" && pwd)
here=$(cd "$(dirname "$0")/.." && pwd)
if [ -z "${ROS_DISTRO:-}" ] || ! command -v colcon >/dev/null || ! command -v ros2 >/dev/null; then
  echo "make test-ros2 needs ROS 2 Humble sourced (source /opt/ros/humble/setup.bash) and colcon;" >&2
  echo "see the README, 'Running under ROS 2'. ROS_DISTRO='${ROS_DISTRO:-}'" >&2
  exit 1
fi
if [ "$ROS_DISTRO" != humble ]; then
  echo "warning: the ROS 2 packages are verified on Humble; this is $ROS_DISTRO" >&2
fi
work=$here/build-ros2
mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" >/dev/null

# Loopback only, unicast discovery: tests neither need nor disturb a network. Interfaces are left
# to ROS_LOCALHOST_ONLY, which rmw_cyclonedds turns into the loopback interface itself.
cat >"$work/cyclonedds.xml" <<'XML'
<CycloneDDS><Domain Id="any">
  <General><AllowMulticast>false</AllowMulticast></General>
  <Discovery><ParticipantIndex>auto</ParticipantIndex>
    <MaxAutoParticipantIndex>31</MaxAutoParticipantIndex>
    <Peers><Peer address="127.0.0.1"/></Peers></Discovery>
</Domain></CycloneDDS>
XML
export RMW_IMPLEMENTATION=rmw_cyclonedds_cpp ROS_LOCALHOST_ONLY=1
export CYCLONEDDS_URI=file://$work/cyclonedds.xml

cd "$here"
colcon --log-base "$work/log" build --base-paths ros2 --build-base "$work/build" \
  --install-base "$work/install" --event-handlers console_direct- \
  --cmake-args -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DCMAKE_CXX_COMPILER_LAUNCHER=ccache
# The packages' own tests (the controller in a ros2_control harness: torque equal to comply's
# wrapper, no allocation in update(), parameters round trip).
colcon --log-base "$work/log" test --base-paths ros2 --build-base "$work/build" \
  --install-base "$work/install" --event-handlers console_direct-
colcon --log-base "$work/log" test-result --test-result-base "$work/build" --verbose
# colcon's setup scripts read unset variables.
set +u
# shellcheck disable=SC1091
source "$work/install/setup.bash"
cd "$work"
ros2 daemon stop >/dev/null 2>&1 || true
python3 "$here/ros2/test/system_test.py" "$build/apps/comply/comply" "$build/python" \
  "$here/config"
