#!/usr/bin/env bash
# Installs tumble from a build tree into a temporary prefix and builds examples/cpp against it with
# find_package(tumble), then runs the example: the exported package works for another project.
set -euo pipefail
build_dir="$1"
source_dir="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cmake --install "$build_dir" --prefix "$work/prefix" >/dev/null
# The documentation is installed where `tumble --help` says (share/doc/tumble).
for doc in README.md scene-format.md NOTATION.md ARCHITECTURE.md examples/t_handle.toml; do
  test -f "$work/prefix/share/doc/tumble/$doc" || { echo "not installed: share/doc/tumble/$doc"; exit 1; }
done
cmake -S "$source_dir/examples/cpp" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/build" >/dev/null
"$work/build/t_handle_flips" | tee "$work/out.txt"
grep -q "flip at t" "$work/out.txt"
