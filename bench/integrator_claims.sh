#!/usr/bin/env bash
# The measurements behind the README's "Choosing an integrator" advice, with the shipped examples and
# the tumble CLI (build first: bash scripts/build.sh release).
#
#   bash bench/integrator_claims.sh [build/release/bin/tumble]
#
# 1. Translation: one orbit of examples/satellite.toml (5828 s); the final centre of mass against rk4 at
#    h = 0.1 s. splitting is second order in the translation, rk4 fourth.
# 2. Rotation: 20 s of examples/t_handle.toml; flips counted as sign changes of ω about the intermediate
#    principal axis (w2), and the kinetic energy's relative change (it is conserved exactly).
set -euo pipefail
cd "$(dirname "$0")/.."
tumble=${1:-build/release/bin/tumble}
python=/usr/bin/python3  # Debian's interpreter (csv module only)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "== one orbit of examples/satellite.toml: end position against rk4 at h = 0.1 s"
for cfg in "rk4 0.1" "rk4 10" "splitting 1" "splitting 10" "splitting4 10"; do
  set -- $cfg
  "$tumble" run examples/satellite.toml --integrator "$1" --timestep "$2" --output-interval 5828 \
    --fields com_position -o "$work/sat_$1_$2.csv" --quiet --drift-threshold 0
done
"$python" - "$work" <<'PY'
import csv, math, sys
work = sys.argv[1]
def end(name):
    row = list(csv.DictReader(open(f"{work}/sat_{name}.csv")))[-1]
    return [float(row[k]) for k in ("com_x", "com_y", "com_z")]
ref = end("rk4_0.1")
for name in ("rk4_10", "splitting_1", "splitting_10", "splitting4_10"):
    print(f"  {name:15s} off by {math.dist(end(name), ref):.3g} m after one orbit")
PY

echo "== 20 s of examples/t_handle.toml: flips and energy"
for cfg in "rk4 0.001" "implicit_gyro 0.01" "implicit_gyro 0.001" "euler 0.001" "euler 0.0001" \
           "semi_implicit_euler 0.001"; do
  set -- $cfg
  "$tumble" run examples/t_handle.toml --integrator "$1" --timestep "$2" \
    --fields angular_velocity_principal -o "$work/th_$1_$2.csv" --quiet --drift-threshold 0
done
"$python" - "$work" <<'PY'
import csv, glob, os, sys
work = sys.argv[1]
for path in sorted(glob.glob(f"{work}/th_*.diagnostics.csv")):
    name = os.path.basename(path)[3:-len(".diagnostics.csv")]
    w2 = [float(r["w2"]) for r in csv.DictReader(open(f"{work}/th_{name}.csv"))]
    flips = sum(1 for a, b in zip(w2, w2[1:]) if a * b < 0)
    d = list(csv.DictReader(open(path)))
    E0, E1 = float(d[0]["kinetic_energy"]), float(d[-1]["kinetic_energy"])
    print(f"  {name:25s} {flips} flips, energy {100 * (E1 - E0) / E0:+.3g} %")
PY
