#!/usr/bin/env python3
"""Writes the robot models the robot-layer tests read (tests/robot/*_test.cpp), with every authored
inertial computed here in exact rational arithmetic (fractions; pi only where a cylinder needs it, to
double precision) from closed forms independent of tumble's code:

  box a x b x c, mass m:     I = m/12 diag(b²+c², a²+c², a²+b²)
  cylinder r, length L (z):  I = m/12 diag(3r²+L², 3r²+L², 6r²)
  sphere r:                  I = 2/5 m r² I₃
  parallel axis:             I_o = I_c + m((c·c)I₃ − c cᵀ)

arm.urdf is clean; arm_flawed.urdf plants each defect `tumble model check` names once, on its own link
(the link's name says which). Run from this directory: python3 make_models.py
"""
from fractions import Fraction as F
import math

def box_I(m, a, b, c):
    return [[m * (b * b + c * c) / 12, 0, 0], [0, m * (a * a + c * c) / 12, 0], [0, 0, m * (a * a + b * b) / 12]]

def add(A, B):
    return [[A[i][j] + B[i][j] for j in range(3)] for i in range(3)]

def shift(I, m, c):
    """About a point at -c from the COM: I + m((c·c)E - c c^T)."""
    cc = sum(x * x for x in c)
    return [[I[i][j] + m * ((cc if i == j else 0) - c[i] * c[j]) for j in range(3)] for i in range(3)]

def num(x):
    return repr(float(x))

def inertia_attrs(I):
    return ('ixx="%s" ixy="%s" ixz="%s" iyy="%s" iyz="%s" izz="%s"'
            % (num(I[0][0]), num(I[0][1]), num(I[0][2]), num(I[1][1]), num(I[1][2]), num(I[2][2])))

def rot_z(t):
    c, s = math.cos(t), math.sin(t)
    return [[c, -s, 0], [s, c, 0], [0, 0, 1]]

def rotate(R, I):
    RI = [[sum(R[i][k] * I[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
    return [[sum(RI[i][k] * R[j][k] for k in range(3)) for j in range(3)] for i in range(3)]

# --- meshes: a bar 0.3 x 0.04 x 0.04 m centred at its origin (12 triangles, outward), in m and mm ----
def bar_obj(scale, drop_last=False):
    a, b, c = F(3, 10) * scale, F(4, 100) * scale, F(4, 100) * scale
    v = [(x, y, z) for x in (-a / 2, a / 2) for y in (-b / 2, b / 2) for z in (-c / 2, c / 2)]
    # vertex k = 4 ix + 2 iy + iz (1-based in OBJ); faces counter-clockwise seen from outside
    quads = [(1, 2, 4, 3), (5, 7, 8, 6), (1, 5, 6, 2), (3, 4, 8, 7), (1, 3, 7, 5), (2, 6, 8, 4)]
    tris = []
    for q in quads:
        tris += [(q[0], q[1], q[2]), (q[0], q[2], q[3])]
    if drop_last:
        tris = tris[:-1]
    out = ["# a bar 0.3 x 0.04 x 0.04 m (written by make_models.py)"]
    out += ["v %s %s %s" % tuple(num(x) for x in p) for p in v]
    out += ["f %d %d %d" % t for t in tris]
    return "\n".join(out) + "\n"

open("meshes/bar.obj", "w").write(bar_obj(1))
open("meshes/bar_mm.obj", "w").write(bar_obj(1000))
open("meshes/open_bar.obj", "w").write(bar_obj(1, drop_last=True))

# --- the links ----------------------------------------------------------------------------------------
links = {}
# base: box 0.2 x 0.2 x 0.1 standing on the link origin (centre at z = 0.05), 8 kg (2000 kg/m³).
base_I = box_I(F(8), F(2, 10), F(2, 10), F(1, 10))
# upper: cylinder r = 0.05, L = 0.4 along z, centred at z = 0.2, 2.5 kg.
m, r, L = 2.5, 0.05, 0.4
upper_I = [[m * (3 * r * r + L * L) / 12, 0, 0], [0, m * (3 * r * r + L * L) / 12, 0], [0, 0, m * r * r / 2]]
# fore: the bar mesh centred at x = 0.15 plus a sphere r = 0.03 at x = 0.3; uniform density 2700:
rho = F(2700)
Vbar = F(3, 10) * F(4, 100) * F(4, 100)
Vsph = 4 * math.pi * 0.03 ** 3 / 3
mbar, msph = rho * Vbar, 2700 * Vsph
fore_m = float(mbar) + msph
fore_c = (float(mbar) * 0.15 + msph * 0.3) / fore_m
Ibar = shift(box_I(float(mbar), 0.3, 0.04, 0.04), float(mbar), (0.15 - fore_c, 0, 0))
Isph = shift([[0.4 * msph * 0.03 ** 2 if i == j else 0 for j in range(3)] for i in range(3)], msph, (0.3 - fore_c, 0, 0))
fore_I = add(Ibar, Isph)
# tool: a box 0.05 x 0.05 x 0.05 welded to fore by a fixed joint, 0.3 kg.
tool_I = box_I(F(3, 10), F(5, 100), F(5, 100), F(5, 100))

def urdf_link(name, inertial, geometry, extra=""):
    return ('  <link name="%s">\n%s%s%s  </link>\n' % (name, inertial, geometry, extra))

def inertial(m, xyz, I, rpy="0 0 0"):
    return ('    <inertial>\n      <origin xyz="%s" rpy="%s"/>\n      <mass value="%s"/>\n'
            '      <inertia %s/>\n    </inertial>\n' % (xyz, rpy, m, inertia_attrs(I)))

def collision(shape, xyz="0 0 0", rpy="0 0 0"):
    return ('    <collision>\n      <origin xyz="%s" rpy="%s"/>\n      <geometry>\n        %s\n      </geometry>\n'
            '    </collision>\n' % (xyz, rpy, shape))

clean = ['<?xml version="1.0"?>\n<!-- A clean 4-link arm (make_models.py): every inertial exact. -->\n<robot name="arm">\n']
clean.append(urdf_link("base", inertial("8", "0 0 0.05", base_I), collision('<box size="0.2 0.2 0.1"/>', "0 0 0.05")))
clean.append(urdf_link("upper", inertial("2.5", "0 0 0.2", upper_I), collision('<cylinder radius="0.05" length="0.4"/>', "0 0 0.2")))
clean.append(urdf_link("fore", inertial(num(fore_m), "%s 0 0" % num(fore_c), fore_I),
                       collision('<mesh filename="meshes/bar.obj"/>', "0.15 0 0") + collision('<sphere radius="0.03"/>', "0.3 0 0")))
clean.append(urdf_link("tool", inertial("0.3", "0 0 0", tool_I), collision('<box size="0.05 0.05 0.05"/>')))
clean.append('  <joint name="shoulder" type="revolute">\n    <parent link="base"/>\n    <child link="upper"/>\n'
             '    <origin xyz="0 0 0.1" rpy="0 0 0"/>\n    <axis xyz="0 0 1"/>\n'
             '    <limit lower="-3" upper="3" effort="10" velocity="1"/>\n  </joint>\n')
clean.append('  <joint name="elbow" type="revolute">\n    <parent link="upper"/>\n    <child link="fore"/>\n'
             '    <origin xyz="0 0 0.4" rpy="0 -1.5707963267948966 0"/>\n    <axis xyz="0 1 0"/>\n'
             '    <limit lower="-3" upper="3" effort="10" velocity="1"/>\n  </joint>\n')
clean.append('  <joint name="flange" type="fixed">\n    <parent link="fore"/>\n    <child link="tool"/>\n'
             '    <origin xyz="0.355 0 0" rpy="0 0 0.5"/>\n  </joint>\n')
clean.append('</robot>\n')
open("arm.urdf", "w").write("".join(clean))

# --- one defect per link ------------------------------------------------------------------------------
box = '<box size="0.1 0.1 0.1"/>'
bI = box_I(F(2), F(1, 10), F(1, 10), F(1, 10))  # 2 kg: 2000 kg/m³
flawed = ['<?xml version="1.0"?>\n<!-- Each defect tumble model check names, once (make_models.py). -->\n<robot name="flawed">\n']
flawed.append(urdf_link("clean", inertial("2", "0 0 0", bI), collision(box)))
flawed.append(urdf_link("not_positive_definite", inertial("2", "0 0 0", [[0.01, 0, 0], [0, -0.001, 0], [0, 0, 0.01]]), collision(box)))
flawed.append(urdf_link("triangle_inequality", inertial("2", "0 0 0", [[0.001, 0, 0], [0, 0.001, 0], [0, 0, 0.01]]), collision(box)))
flawed.append(urdf_link("zero_mass_with_geometry", inertial("0", "0 0 0", [[0] * 3] * 3), collision(box)))
flawed.append(urdf_link("implied_density", inertial("0.03", "0 0 0", box_I(F(3, 100), F(1, 10), F(1, 10), F(1, 10))), collision(box)))
mmI = box_I(F(432, 1000), F(3, 10), F(4, 100), F(4, 100))  # 2700 kg/m³ had the mesh been read in m
flawed.append(urdf_link("mesh_scale", inertial("0.432", "0 0 0", mmI), collision('<mesh filename="meshes/bar_mm.obj"/>')))
flawed.append(urdf_link("tensor_about_origin", inertial("2", "0 0 0.2", shift(bI, F(2), (0, 0, F(2, 10)))),
                        collision(box, "0 0 0.2")))
flawed.append(urdf_link("com_outside_geometry", inertial("2", "1 0 0", bI), collision(box)))
rI = box_I(F(2), F(3, 10), F(1, 10), F(1, 10))  # 0.3 x 0.1 x 0.1, 6000 kg/m³... use 1.8 kg below
rI = box_I(F(18, 10), F(3, 10), F(1, 10), F(1, 10))  # 600 kg/m³
flawed.append(urdf_link("tensor_mismatch", inertial("1.8", "0 0 0", [[rI[1][1], 0, 0], [0, rI[0][0], 0], [0, 0, rI[2][2]]]),
                        collision('<box size="0.3 0.1 0.1"/>')))
# The same box turned 0.5 rad about z: its link-frame tensor written with rpy 0 0 0.5 (applied twice).
turned = rotate(rot_z(0.5), [[float(x) for x in row] for row in rI])
flawed.append(urdf_link("inertial_rotation", inertial("1.8", "0 0 0", turned, rpy="0 0 0.5"),
                        collision('<box size="0.3 0.1 0.1"/>', rpy="0 0 0.5")))
flipped = [row[:] for row in turned]
flipped[0][1] = flipped[1][0] = -turned[0][1]
flawed.append(urdf_link("product_sign", inertial("1.8", "0 0 0", flipped), collision('<box size="0.3 0.1 0.1"/>', rpy="0 0 0.5")))
flawed.append(urdf_link("missing_mesh", inertial("2", "0 0 0", bI), collision('<mesh filename="meshes/no_such_mesh.stl"/>')))
flawed.append(urdf_link("open_mesh", inertial("0.1", "0 0 0", box_I(F(1, 10), F(3, 10), F(4, 100), F(4, 100))),
                        collision('<mesh filename="meshes/open_bar.obj"/>')))
flawed.append('</robot>\n')
open("arm_flawed.urdf", "w").write("".join(flawed))
