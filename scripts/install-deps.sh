#!/usr/bin/env bash
# Installs the Debian 12 packages tumble needs to build, test and benchmark. Safe to run again.
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config g++ clang-14 libclang-rt-14-dev clang-format-14
  libeigen3-dev libxsimd-dev libomp-14-dev libboost-dev libfmt-dev libcli11-dev libassimp-dev libtomlplusplus-dev libpugixml-dev libhdf5-dev nlohmann-json3-dev libceres-dev librandom123-dev libopenmpi-dev openmpi-bin
  libgtest-dev libgmock-dev libbenchmark-dev
  chromium
  libmujoco-dev libmujoco-samples  # MuJoCo's sample models and MuJoCo itself, as a reference in one test only
  python3 python3-numpy python3-h5py python3-dev python3-pybind11 python3-pytest python3-venv python3-pip python3-setuptools python3-tomli-w python3-matplotlib python3-mpmath
)
# The report viewer (viewer/) is built with node and npm: the machine's own where present (Debian's npm
# package conflicts with a Node installed otherwise), Debian's nodejs and npm where node is missing.
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  packages+=(nodejs npm)
fi
bash "$(dirname "$0")/apt-install-missing.sh" --label install-deps "${packages[@]}"
# clang++ from the clang-14 package is named clang++-14; give CMake presets a plain clang++.
if ! command -v clang++ >/dev/null; then
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO ln -sf /usr/bin/clang++-14 /usr/local/bin/clang++
fi
