#!/usr/bin/env bash
# toml++ against Debian's other C++ TOML readers (toml11, cpptoml) on the same scene file: the time to
# parse and free its tree, per [[bodies]] table, and where each says an error is. A scene of N boxes,
# each its own [[bodies]] table with every number to 17 digits, is written first (as bench/scene_setup
# writes them). The readers are header-only Debian packages, installed here; this program is built
# here with g++ and is no part of tumble's build.
#   bash bench/toml_readers.sh [N] [REPEATS]        (defaults 100000 3)
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-100000}
repeats=${2:-3}
bash scripts/apt-install-missing.sh --label toml_readers g++ libtomlplusplus-dev libtoml11-dev libcpptoml-dev
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# toml++ compiled as tumble compiles it (src/io/CMakeLists.txt: floats through std::from_chars).
g++ -O3 -std=c++20 -DTOML_FLOAT_CHARCONV=1 -o "$work/toml_readers" bench/toml_readers/*.cpp
awk -v n="$n" 'BEGIN {
  srand(5)
  print "[simulation]\nduration = 0.2\ntimestep = 1e-3\n[world]\ngravity = [0.0, 0.0, -9.81]"
  for (i = 0; i < n; i++) {
    printf "[[bodies]]\nname = \"box_%d\"\nshape = { type = \"box\", size = [%.17g, %.17g, %.17g] }\n", i, 0.1 + rand(), 0.1 + rand(), 0.1 + rand()
    printf "density = %.17g\nposition = [%.17g, %.17g, %.17g]\norientation = [1.0, 0.0, 0.0, 0.0]\n", 500 + 2500 * rand(), 200 * rand() - 100, 200 * rand() - 100, 200 * rand() - 100
    printf "velocity = [%.17g, %.17g, %.17g]\nangular_velocity = [%.17g, %.17g, %.17g]\n", 2 * rand() - 1, 2 * rand() - 1, 2 * rand() - 1, 20 * rand() - 10, 20 * rand() - 10, 20 * rand() - 10
  }
}' > "$work/bodies.toml"
echo "# machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores; $(date -u +%F)"
"$work/toml_readers" "$work/bodies.toml" "$repeats"
