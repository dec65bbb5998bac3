#!/usr/bin/env python3
"""Generates the example meshes (Python 3 standard library only; run from anywhere):

  t_handle.stl  a T-handle like the one in the Dzhanibekov effect videos: a bar 0.10 x 0.02 x 0.02 m
                with a 0.06 m stem of 0.02 x 0.02 m from its middle, as ONE closed manifold
                polyhedron (the T-shaped outline extruded), binary STL, metres.
  asteroid.obj  a lumpy closed "asteroid" of mean radius 250 m and a few hundred triangles: an
                icosphere subdivided twice (320 triangles) with a smooth random radial bump field
                (fixed seed, so the file is reproducible).

Every triangle winds counter-clockwise seen from outside (outward normals).
"""
import math
import pathlib
import random
import struct

HERE = pathlib.Path(__file__).resolve().parent


def t_handle():
    """The T outline in the x-z plane, extruded along y from -0.01 to 0.01.

    The outline (counter-clockwise seen from +y... see below) has 8 corners; the bar's lower edge is
    split at x = +-0.01 where the stem joins it, so the caps can be triangulated without T-junctions.
    """
    w, t = 0.05, 0.01  # half bar length, half thickness
    stem, bar = 0.06, 0.02  # stem length, bar height
    # Outline, counter-clockwise in the (x, z) plane seen from -y (x to the right, z up).
    outline = [(-t, 0.0), (t, 0.0), (t, stem), (w, stem), (w, stem + bar), (-w, stem + bar),
               (-w, stem), (-t, stem)]
    n = len(outline)
    vertices = [(x, -t, z) for x, z in outline] + [(x, t, z) for x, z in outline]
    # Cap triangulation by outline index: stem quad (0,1,2,7), bar hexagon (6,7,2,3,4,5).
    cap = [(0, 1, 2), (0, 2, 7), (6, 7, 5), (7, 4, 5), (7, 2, 4), (2, 3, 4)]
    triangles = []
    for a, b, c in cap:
        # Seen from -y the outline is counter-clockwise, so the y = -t cap keeps the order (its
        # outward normal is -y) and the y = +t cap reverses it.
        triangles.append((a, b, c))
        triangles.append((n + a, n + c, n + b))
    for i in range(n):
        j = (i + 1) % n
        # Side wall of outline edge i -> j: outward is to the right of the edge in the (x, z) plane.
        triangles.append((i, n + i, n + j))
        triangles.append((i, n + j, j))
    return vertices, triangles


def check_outward(vertices, triangles):
    """Signed volume > 0 (divergence theorem), so the winding is outward."""
    v6 = 0.0
    for a, b, c in triangles:
        (ax, ay, az), (bx, by, bz), (cx, cy, cz) = vertices[a], vertices[b], vertices[c]
        v6 += ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx)
    assert v6 > 0, "mesh is inside-out"
    return v6 / 6


def write_binary_stl(path, vertices, triangles, title):
    with open(path, "wb") as f:
        f.write(title.encode("ascii").ljust(80, b" "))
        f.write(struct.pack("<I", len(triangles)))
        for tri in triangles:
            p = [vertices[i] for i in tri]
            u = [p[1][k] - p[0][k] for k in range(3)]
            v = [p[2][k] - p[0][k] for k in range(3)]
            nrm = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
            length = math.sqrt(sum(x * x for x in nrm)) or 1.0
            f.write(struct.pack("<3f", *(x / length for x in nrm)))
            for q in p:
                f.write(struct.pack("<3f", *q))
            f.write(struct.pack("<H", 0))


def icosphere(levels):
    g = (1 + math.sqrt(5)) / 2
    verts = [(-1, g, 0), (1, g, 0), (-1, -g, 0), (1, -g, 0), (0, -1, g), (0, 1, g), (0, -1, -g),
             (0, 1, -g), (g, 0, -1), (g, 0, 1), (-g, 0, -1), (-g, 0, 1)]
    verts = [tuple(x / math.sqrt(sum(c * c for c in v)) for x in v) for v in verts]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(levels):
        cache = {}

        def midpoint(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                m = [(verts[a][k] + verts[b][k]) / 2 for k in range(3)]
                r = math.sqrt(sum(x * x for x in m))
                verts.append(tuple(x / r for x in m))
                cache[key] = len(verts) - 1
            return cache[key]

        new = []
        for a, b, c in faces:
            ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
            new += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = new
    return verts, faces


def asteroid(seed=1999, radius=250.0):
    """A star-shaped body: r(u) = R (1 + sum of smooth bumps), so it stays a closed manifold."""
    rng = random.Random(seed)
    verts, faces = icosphere(2)
    bumps = []
    for _ in range(9):
        d = [rng.gauss(0, 1) for _ in range(3)]
        n = math.sqrt(sum(x * x for x in d))
        bumps.append(([x / n for x in d], rng.uniform(-0.25, 0.3), rng.uniform(0.3, 0.8)))
    out = []
    for v in verts:
        r = 1.0
        for d, amp, width in bumps:
            cos_angle = sum(a * b for a, b in zip(v, d))
            r += amp * math.exp((cos_angle - 1) / (width * width))
        r *= 1 + 0.02 * rng.uniform(-1, 1)  # surface roughness
        out.append(tuple(radius * r * x for x in v))
    return out, faces


def write_obj(path, vertices, triangles, header):
    with open(path, "w", encoding="ascii") as f:
        f.write(f"# {header}\n")
        for v in vertices:
            f.write("v {:.6f} {:.6f} {:.6f}\n".format(*v))
        for a, b, c in triangles:
            f.write(f"f {a + 1} {b + 1} {c + 1}\n")


def main():
    v, t = t_handle()
    volume = check_outward(v, t)
    write_binary_stl(HERE / "t_handle.stl", v, t, "tumble example: T-handle, metres")
    print(f"t_handle.stl: {len(t)} triangles, volume {volume:.6e} m^3")
    v, t = asteroid()
    volume = check_outward(v, t)
    write_obj(HERE / "asteroid.obj", v, t,
              "tumble example: lumpy asteroid, metres (examples/meshes/make_meshes.py, seed 1999)")
    print(f"asteroid.obj: {len(t)} triangles, volume {volume:.6e} m^3")


if __name__ == "__main__":
    main()
