#!/usr/bin/env bash
# The main job: install, build, and run the demo.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh release
echo
echo "== tumble inertia examples/meshes/t_handle.stl --density 2700 (aluminium T-handle) =="
build/release/bin/tumble inertia examples/meshes/t_handle.stl --density 2700
