"""Mass properties of a CAD part from its mesh file, drawn in millimetres: read it at scale 0.001
(mm -> m), and check the result against the same part built from two boxes in closed form.

The part is an aluminium L-bracket, 60 x 40 mm, 8 mm thick, 30 mm deep; this script writes it as a
binary STL in millimetres (as a CAD program would export it), then reads it like any other file.

    PYTHONPATH=build/release/python /usr/bin/python3 python/examples/mesh_inertia.py [out/bracket_mm.stl]
"""
import os
import struct
import sys

import numpy as np

import tumble

path = sys.argv[1] if len(sys.argv) > 1 else os.path.join("out", "bracket_mm.stl")

# The L outline (mm), counter-clockwise, extruded 30 mm along z.
outline = np.array([[0, 0], [60, 0], [60, 8], [8, 8], [8, 40], [0, 40]], dtype=float)
n = len(outline)
V = np.vstack([np.c_[outline, np.zeros(n)], np.c_[outline, np.full(n, 30.0)]])  # bottom 0..5, top 6..11
cap = [(3, 4, 5), (3, 5, 0), (3, 0, 1), (3, 1, 2)]  # a fan from the inner corner, which sees every vertex
F = [(a + n, b + n, c + n) for a, b, c in cap] + [(a, c, b) for a, b, c in cap]  # top up, bottom down
for i in range(n):
    j = (i + 1) % n
    F += [(i, j, j + n), (i, j + n, i + n)]  # the side wall of edge i -> j, outward

os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
with open(path, "wb") as f:
    f.write(b"L-bracket, millimetres".ljust(80, b" ") + struct.pack("<I", len(F)))
    for tri in F:
        p = V[list(tri)]
        normal = np.cross(p[1] - p[0], p[2] - p[0])
        f.write(struct.pack("<12fH", *(normal / np.linalg.norm(normal)), *p.ravel(), 0))

part = tumble.inertia(path, density=2700, scale=0.001)  # kg/m^3; the file is in mm
print(f"{path}: {len(F)} triangles, read at scale 0.001 (mm -> m)")
print(f"  mass {part.mass * 1000:.3f} g, volume {part.volume * 1e6:.3f} cm^3, surface {part.surface_area * 1e4:.2f} cm^2")
print(f"  centre of mass {np.array2string(part.center_of_mass * 1000, precision=4)} mm")
print(f"  inertia about the centre of mass (kg m^2, file axes):\n{part.inertia}")
print(f"  principal moments {part.principal_moments} kg m^2")
print(f"  principal axes (columns):\n{part.principal_axes}")
print(f"  moment about the bracket's edge (the z axis through the origin): "
      f"{part.moment_about_axis([0, 0, 1], point=[0, 0, 0]):.6e} kg m^2")

# The same bracket as two boxes (m), each placed by translating its closed form: they must agree to
# rounding (the mesh integration is exact for a polyhedron).
foot = tumble.box([0.060, 0.008, 0.030], density=2700).transformed(t=[0.030, 0.004, 0.015])
web = tumble.box([0.008, 0.032, 0.030], density=2700).transformed(t=[0.004, 0.024, 0.015])
boxes = foot + web
print(f"  two boxes in closed form: mass {boxes.mass * 1000:.3f} g, "
      f"largest inertia difference {np.abs(boxes.inertia - part.inertia).max():.1e} kg m^2")
assert abs(boxes.mass - part.mass) <= 1e-12 * boxes.mass
assert np.abs(boxes.inertia - part.inertia).max() <= 1e-12 * np.abs(boxes.inertia).max()
