#!/usr/bin/env bash
# Installs the Debian 12 packages comply builds and tests with, then the npm packages of the MCAP
# and Parquet cross-check readers (tests/record/node, tests/export/node) and of the live view's
# browser test (tests/viewer/node: Foxglove's client, playwright-core driving Debian's Chromium)
# when node and npm are there. Idempotent: when every package is already installed it only says so; apt lists are
# refreshed only when something is missing, and npm ci runs only when node_modules is missing or
# older than package-lock.json.
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
  cyclonedds-dev cyclonedds-tools openssl
  pybind11-dev python3-numpy
  libzstd-dev python3-zstandard
  octave
  ffmpeg python3-distributed
  libboost-dev chromium
)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "deps: all ${#packages[@]} packages already installed"
else
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
fi

# npm writes node_modules/.package-lock.json on every install, so its age tells whether the
# installed packages predate the lockfile.
root=$(cd "$(dirname "$0")/.." && pwd)
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  echo "deps: no node/npm: the MCAP and Parquet cross-check tests and the browser test cannot run"
else
  for node_dir in "$root/tests/record/node" "$root/tests/export/node" "$root/tests/viewer/node"; do
    what=${node_dir#"$root"/}
    if [ ! -f "$node_dir/node_modules/.package-lock.json" ] ||
      [ "$node_dir/package-lock.json" -nt "$node_dir/node_modules/.package-lock.json" ]; then
      echo "deps: npm ci in $what (an independent reader of the cross-check tests)"
      npm ci --prefix "$node_dir" --no-audit --no-fund
    else
      echo "deps: npm packages of $what already installed"
    fi
  done
fi
