#!/usr/bin/env bash
# Installs tumble from a build tree into a temporary prefix and builds examples/cpp against it with
# find_package(tumble), then runs the examples: the exported package works for another project.
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
# ... and `tumble --help` names that folder of the prefix it is in, even after the tree was moved.
"$work/prefix/bin/tumble" --help | tr -s ' \n' ' ' | grep -qF "installed in $(realpath "$work")/prefix/share/doc/tumble." ||
  { echo "tumble --help does not name $work/prefix/share/doc/tumble"; exit 1; }
cp -a "$work/prefix" "$work/moved"
"$work/moved/bin/tumble" --help | tr -s ' \n' ' ' | grep -qF "installed in $(realpath "$work")/moved/share/doc/tumble." ||
  { echo "a moved tumble --help does not name its own share/doc/tumble"; exit 1; }
rm -rf "$work/moved"
cmake -S "$source_dir/examples/cpp" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/build" >/dev/null
"$work/build/t_handle_flips" | tee "$work/out.txt"
grep -q "flip at t" "$work/out.txt"
# Frame-by-frame stepping: the program exits 1 if the centre of mass leaves its parabola by more than
# rounding (RK4 integrates a quadratic exactly).
"$work/build/game_loop"
# The T-handle mesh is a bar 0.10 x 0.02 x 0.02 m and a stem 0.06 x 0.02 x 0.02 m: 6.4e-5 m^3, at
# 2700 kg/m^3 0.1728 kg. Its vertices are float32 (~4e-9 m off at 0.1 m): 1e-6 kg bounds that.
"$work/build/mesh_inertia" "$source_dir/examples/meshes/t_handle.stl" 2700 | tee "$work/mesh.txt"
awk '/^mass/ { found = 1; d = $2 - 0.1728; if (d < 0) d = -d; if (d > 1e-6) { print "mass " $2 " is not 0.1728 kg"; exit 1 } }
     END { if (!found) { print "no mass line"; exit 1 } }' "$work/mesh.txt"
# A missing file is an error with the path, not a crash.
if "$work/build/mesh_inertia" "$work/no_such.stl" 2> "$work/err.txt"; then exit 1; fi
grep -q "no_such.stl" "$work/err.txt"
