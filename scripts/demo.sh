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
echo "== tumble run examples/t_handle.toml -o out/t_handle.csv --report out/t_handle.html (it flips every 4.6 s) =="
build/release/bin/tumble run examples/t_handle.toml -o out/t_handle.csv --report out/t_handle.html
echo
echo "The trajectory is in out/t_handle.csv (t, body, position, quaternion w,x,y,z, velocity and angular"
echo "velocity, world), the energy and momenta in out/t_handle.diagnostics.csv and the flips in"
echo "out/t_handle.events.csv. More scenes: examples/*.toml; validate one with"
echo "'build/release/bin/tumble check FILE'; the format is docs/scene-format.md."
echo
echo "== the same from Python (Debian's /usr/bin/python3 with NumPy): python/examples/t_handle_flips.py =="
PYTHONPATH=build/release/python /usr/bin/python3 python/examples/t_handle_flips.py out/t_handle_omega.png
echo
echo "The interactive 3D report of the T-handle (open it in a browser; no network needed):"
echo "  $(pwd)/out/t_handle.html"
