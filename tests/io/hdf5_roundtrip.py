#!/usr/bin/env python3
"""What `tumble run` writes, read as users read it: h5py for HDF5, the csv module for CSV.

Usage: hdf5_roundtrip.py TUMBLE_CLI SOURCE_DIR WORK_DIR

Checks that the two formats hold the same numbers (CSV's 17 significant digits read back bit for
bit), that the HDF5 attributes carry the scene text and the tumble version, that no temporary file is
left, and the physics of the thrown box: its centre follows o0 + v0 t + g t^2 / 2, which RK4 integrates
exactly (a quadratic in t), so only rounding separates them.
"""
import csv
import pathlib
import shutil
import subprocess
import sys

import h5py
import numpy as np

cli, source, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
shutil.rmtree(work, ignore_errors=True)
work.mkdir(parents=True)
scene = source / "examples" / "thrown_box.toml"


def run(*args):
    done = subprocess.run([cli, *map(str, args)], capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    return done.stdout


run("run", scene, "-o", work / "box.h5", "--quiet")
run("run", scene, "-o", work / "box.csv", "--quiet")
version = run("--version").split()[-1]
assert sorted(p.name for p in work.iterdir()) == ["box.csv", "box.diagnostics.csv", "box.h5", "box.run.json"], list(work.iterdir())

with h5py.File(work / "box.h5", "r") as f:
    assert f.attrs["scene"] == scene.read_text(), "the scene text is stored verbatim"
    assert f.attrs["tumble_version"] == version, (f.attrs["tumble_version"], version)
    assert f.attrs["integrator"] == "rk4" and f.attrs["formulation"] == "mixed"
    assert f.attrs["complete"] == 1
    t = f["t"][:]
    names = [n.decode() if isinstance(n, bytes) else n for n in f["names"][:]]
    position, orientation = f["position"][:], f["orientation"][:]
    velocity, omega = f["velocity"][:], f["angular_velocity"][:]
    diag = {k: f["diagnostics"][k][:] for k in f["diagnostics"]}

n = len(t)
assert names == ["box"]
assert position.shape == (n, 1, 3) and orientation.shape == (n, 1, 4) and omega.shape == (n, 1, 3)
assert t[0] == 0.0 and t[-1] == 1.2 and n == 121, (t[0], t[-1], n)

with open(work / "box.csv", newline="") as fh:
    reader = csv.reader(fh)
    header = next(reader)
    rows = list(reader)
assert header == "t,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz".split(","), header
assert len(rows) == n
for i, row in enumerate(rows):
    assert row[1] == "box"
    values = np.array([float(x) for x in [row[0]] + row[2:]])
    expected = np.concatenate([[t[i]], position[i, 0], orientation[i, 0], velocity[i, 0], omega[i, 0]])
    assert np.array_equal(values, expected), (i, values - expected)

with open(work / "box.diagnostics.csv", newline="") as fh:
    drows = list(csv.DictReader(fh))
assert len(drows) == n
for key in ["kinetic_energy", "potential_energy", "total_energy", "energy_drift"]:
    assert np.array_equal([float(r[key]) for r in drows], diag[key]), key
assert np.array_equal([[float(r[k]) for k in ("Lx", "Ly", "Lz")] for r in drows], diag["angular_momentum"])
# The box is at rest in no direction at t = 0, but its momentum changes under gravity: the drift is
# defined (|p0| > 0) and written; angular momentum about the origin too.
assert "linear_momentum_drift" in diag and "angular_momentum_drift" in diag

# Physics: the box's reference origin is its centre of mass.
g = np.array([0.0, 0.0, -9.81])
o0, v0 = np.array([0.0, 0.0, 1.0]), np.array([2.0, 0.5, 5.0])
parabola = o0 + np.outer(t, v0) + 0.5 * np.outer(t * t, g)
# Rounding of ~1200 RK4 steps on numbers of size ~3: far below 1e-12 m.
assert np.max(np.abs(position[:, 0] - parabola)) < 1e-12, np.max(np.abs(position[:, 0] - parabola))
# Unit quaternions to rounding (renormalised every step).
assert np.max(np.abs(np.linalg.norm(orientation[:, 0], axis=1) - 1)) < 4e-16
# Energy conserved to RK4's error at ω h = 0.009: the run reports ~1e-14.
assert np.max(np.abs(diag["energy_drift"])) < 1e-10
print(f"ok: {n} samples agree between HDF5 and CSV; parabola and energy hold")
