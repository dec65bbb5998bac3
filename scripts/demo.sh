#!/usr/bin/env bash
# The main job: install, build, and run the demo.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh release
echo
echo "== tumble inertia examples/meshes/t_handle.stl --density 2700 (aluminium T-handle) =="
build/release/bin/tumble inertia examples/meshes/t_handle.stl --density 2700
echo
echo "== tumble run examples/t_handle.toml -o out/t_handle.csv (the handle flips every 4.6 s) =="
build/release/bin/tumble run examples/t_handle.toml -o out/t_handle.csv
echo
echo "The trajectory is in out/t_handle.csv (t, body, position, quaternion w,x,y,z, velocity and angular"
echo "velocity, world) and the energy and momenta in out/t_handle.diagnostics.csv. More scenes: examples/*.toml;"
echo "validate one with 'build/release/bin/tumble check FILE'; the format is docs/scene-format.md."
echo
echo "== the same from Python (Debian's /usr/bin/python3 with NumPy): examples/python/t_handle_flips.py =="
PYTHONPATH=build/release/python /usr/bin/python3 examples/python/t_handle_flips.py
