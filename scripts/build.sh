#!/usr/bin/env bash
# Configures and builds one CMake preset ("release" or "sanitize"): scripts/build.sh PRESET
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
command -v clang++ >/dev/null || ln -sf /usr/bin/clang++-14 /usr/local/bin/clang++
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset" -j "$(nproc)"
