#!/usr/bin/env bash
# Installs the Debian 12 packages comply builds and tests with. Idempotent: when every package is
# already installed it only says so; apt lists are refreshed only when something is missing.
set -euo pipefail

packages=(
  build-essential cmake ninja-build ccache pkg-config
  libeigen3-dev
  liburdfdom-dev
  libyaml-cpp-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  liborocos-kdl-dev
  libmujoco-dev libqhull-dev
  libegl-dev libegl1 libegl-mesa0 libgl1-mesa-dri libpng-dev libglfw3-dev
  python3-matplotlib
  nlohmann-json3-dev libcli11-dev
  cyclonedds-dev cyclonedds-tools
  pybind11-dev python3-numpy
  octave
)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "deps: all ${#packages[@]} packages already installed"
  exit 0
fi

if [ "$(id -u)" -eq 0 ]; then
  sudo_cmd=()
elif command -v sudo >/dev/null 2>&1; then
  sudo_cmd=(sudo)
else
  echo "deps: need root or sudo to install: ${missing[*]}" >&2
  exit 1
fi

echo "deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "deps: done"
