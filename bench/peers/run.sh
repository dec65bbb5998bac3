#!/usr/bin/env bash
# Builds and runs bench/peers: tumble beside MuJoCo 2.2.2, Bullet 3.24 and ODE 0.16 (Debian 12).
#
#   bash bench/peers/run.sh [CSV] [peers options]     e.g. bash bench/peers/run.sh --reps 5
#
# Installs the Debian packages it needs (as root, or through sudo), configures build/peers (Release,
# -DTUMBLE_BUILD_PEERS=ON; tests, apps and Google Benchmark programs off), builds the harness and runs
# it from the repository root. The CSV goes to bench/results/<machine tag>/peers.csv unless a path is
# given, and the printed report to the same place with the extension .txt. Options are those of the
# program (build/peers/bin/peers --help). JOBS sets the build parallelism (default 2). On a shared
# machine run the whole script under nice: `nice -n 15 bash bench/peers/run.sh`.
set -euo pipefail
cd "$(dirname "$0")/../.."

# tumble's own library dependencies (scripts/install-deps.sh has the full list for tests and apps),
# and the three engines, which only this harness links.
packages=(
  build-essential cmake pkg-config g++
  libeigen3-dev libxsimd-dev libboost-dev libfmt-dev libassimp-dev libtomlplusplus-dev libhdf5-dev
  libmujoco-dev libbullet-dev libode-dev
)
bash scripts/apt-install-missing.sh --label peers "${packages[@]}"

build=build/peers
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DTUMBLE_BUILD_PEERS=ON \
  -DTUMBLE_BUILD_TESTS=OFF -DTUMBLE_BUILD_APPS=OFF -DTUMBLE_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" -j "${JOBS:-2}" --target peers

# The CSV path: the first argument if it is not an option, else the default of the program.
csv="bench/results/$("$build/bin/peers" --tag)/peers.csv"
if [ $# -gt 0 ] && [ "${1#-}" = "$1" ]; then
  csv="$1"
  shift
fi
mkdir -p "$(dirname "$csv")"
"$build/bin/peers" "$csv" "$@" | tee "${csv%.csv}.txt"
