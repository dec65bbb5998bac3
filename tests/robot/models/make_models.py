#!/usr/bin/env python3
"""Writes the robot models the robot-layer tests read (tests/robot/*_test.cpp), with every authored
inertial computed here in exact rational arithmetic (fractions; pi only where a cylinder needs it, to
double precision) from closed forms independent of tumble's code:

  box a x b x c, mass m:     I = m/12 diag(b²+c², a²+c², a²+b²)
  cylinder r, length L (z):  I = m/12 diag(3r²+L², 3r²+L², 6r²)
  sphere r:                  I = 2/5 m r² I₃
  parallel axis:             I_o = I_c + m((c·c)I₃ − c cᵀ)

arm.urdf is clean; arm_flawed.urdf plants each defect `tumble model check` names once, on its own link
(the link's name says which). arm.xml (MJCF) and arm.sdf (SDF) are the same clean arm in those formats;
arm_flawed.xml and arm_flawed.sdf plant the defects again, as each format writes them. Run from this
directory: python3 make_models.py
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
mmI = box_I(F(432, 1000), F(3, 10), F(4, 100), F(4, 100))  # 900 kg/m³ had the mesh been in metres
flawed.append(urdf_link("mesh_scale", inertial("0.432", "0 0 0", mmI), collision('<mesh filename="meshes/bar_mm.obj"/>')))
flawed.append(urdf_link("tensor_about_origin", inertial("2", "0 0 0.2", shift(bI, F(2), (0, 0, F(2, 10)))),
                        collision(box, "0 0 0.2")))
flawed.append(urdf_link("com_outside_geometry", inertial("2", "1 0 0", bI), collision(box)))
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

# --- the same arm, and the defects, in MJCF and SDF -------------------------------------------------------
# Each format's own semantics: MJCF sizes are half-sizes, angles radians (<compiler angle="radian">, MuJoCo's
# default is degrees), meshes named by <asset><mesh> under <compiler meshdir>, and every geom weighed by its
# own density or mass (MuJoCo's rule: so each geom's density is the authored mass over its volume, and the
# geometry gives back the authored inertial); SDF link poses are in the model's frame, inertial and
# collision poses in the link's, box sizes full sizes, values element text.

def mat(R):
    return [[float(x) for x in row] for row in R]

def matmul(A, B):
    return [[sum(A[i][k] * B[k][j] for k in range(3)) for j in range(3)] for i in range(3)]

def rot_y(t):
    c, s = math.cos(t), math.sin(t)
    return [[c, 0, s], [0, 1, 0], [-s, 0, c]]

def rpy_of(R):
    """Roll, pitch, yaw of R = Rz(yaw) Ry(pitch) Rx(roll) (away from pitch = ±π/2)."""
    return (math.atan2(R[2][1], R[2][2]), -math.asin(R[2][0]), math.atan2(R[1][0], R[0][0]))

def nums(v):
    return " ".join(num(x) for x in v)

def diag(I):
    return nums([I[0][0], I[1][1], I[2][2]])

def full(I):  # MJCF's order: ixx iyy izz ixy ixz iyz
    return nums([I[0][0], I[1][1], I[2][2], I[0][1], I[0][2], I[1][2]])

# MJCF --------------------------------------------------------------------------------------------------
def mj_inertial(pad, m, pos, I, rotation="", full_tensor=False):
    tensor = 'fullinertia="%s"' % full(I) if full_tensor else 'diaginertia="%s"' % diag(I)
    return '%s<inertial pos="%s" mass="%s"%s %s/>\n' % (pad, pos, m, rotation, tensor)

def mj_geom(pad, shape, weight, pos="0 0 0", rotation=""):
    return '%s<geom %s pos="%s"%s %s/>\n' % (pad, shape, pos, rotation, weight)

def density(m, V):
    return 'density="%s"' % num(F(m) / F(V) if not isinstance(V, float) else float(m) / V)

mj = ['<?xml version="1.0"?>\n<!-- The clean 4-link arm of arm.urdf in MJCF (make_models.py): every inertial exact, every geom\n'
      '     weighed at the density that gives the authored mass. -->\n<mujoco model="arm">\n'
      '  <compiler angle="radian" meshdir="meshes"/>\n  <asset>\n    <mesh name="bar" file="bar.obj"/>\n  </asset>\n'
      '  <worldbody>\n']
p = "    "
mj.append(p + '<body name="base">\n')
mj.append(mj_inertial(p + "  ", "8", "0 0 0.05", base_I))
mj.append(mj_geom(p + "  ", 'type="box" size="0.1 0.1 0.05"', density(8, F(4, 1000)), "0 0 0.05"))
p += "  "
mj.append(p + '<body name="upper" pos="0 0 0.1">\n')
mj.append(p + '  <joint name="shoulder" type="hinge" axis="0 0 1" range="-3 3"/>\n')
mj.append(mj_inertial(p + "  ", "2.5", "0 0 0.2", upper_I))
mj.append(mj_geom(p + "  ", 'type="cylinder" size="0.05 0.2"', 'mass="2.5"', "0 0 0.2"))
p += "  "
mj.append(p + '<body name="fore" pos="0 0 0.4" euler="0 -1.5707963267948966 0">\n')
mj.append(p + '  <joint name="elbow" type="hinge" axis="0 1 0" range="-3 3"/>\n')
mj.append(mj_inertial(p + "  ", num(fore_m), "%s 0 0" % num(fore_c), fore_I))
mj.append(mj_geom(p + "  ", 'type="mesh" mesh="bar"', 'density="2700"', "0.15 0 0"))
mj.append(mj_geom(p + "  ", 'type="sphere" size="0.03"', 'density="2700"', "0.3 0 0"))
p += "  "
mj.append(p + '<!-- No joint: MuJoCo welds the tool to fore. -->\n')
mj.append(p + '<body name="tool" pos="0.355 0 0" euler="0 0 0.5">\n')
mj.append(mj_inertial(p + "  ", "0.3", "0 0 0", tool_I, full_tensor=True))
mj.append(mj_geom(p + "  ", 'type="box" size="0.025 0.025 0.025"', density(F(3, 10), F(5, 100) ** 3)))
for depth in range(3, -1, -1):
    mj.append("    " + "  " * depth + "</body>\n")
mj.append('  </worldbody>\n</mujoco>\n')
open("arm.xml", "w").write("".join(mj))

def mj_body(name, inertial_text, geom_text):
    return '    <body name="%s">\n%s%s    </body>\n' % (name, inertial_text, geom_text)

cube = 'type="box" size="0.05 0.05 0.05"'  # the 0.1 m cube of arm_flawed.urdf
bar = 'type="box" size="0.15 0.05 0.05"'   # the 0.3 x 0.1 x 0.1 box
q = "      "
mf = ['<?xml version="1.0"?>\n<!-- The defects of arm_flawed.urdf as MJCF writes them (make_models.py). -->\n'
      '<mujoco model="flawed">\n  <compiler angle="radian" meshdir="meshes"/>\n  <asset>\n'
      '    <mesh name="bar_mm" file="bar_mm.obj"/>\n    <mesh name="open_bar" file="open_bar.obj"/>\n'
      '    <mesh name="no_such_mesh" file="no_such_mesh.stl"/>\n  </asset>\n  <worldbody>\n']
rho2 = density(2, F(1, 1000))
mf.append(mj_body("clean", mj_inertial(q, "2", "0 0 0", bI), mj_geom(q, cube, rho2)))
mf.append(mj_body("not_positive_definite", mj_inertial(q, "2", "0 0 0", [[0.01, 0, 0], [0, -0.001, 0], [0, 0, 0.01]]),
                  mj_geom(q, cube, rho2)))
mf.append(mj_body("triangle_inequality", mj_inertial(q, "2", "0 0 0", [[0.001, 0, 0], [0, 0.001, 0], [0, 0, 0.01]]),
                  mj_geom(q, cube, rho2)))
mf.append(mj_body("implied_density", mj_inertial(q, "0.03", "0 0 0", box_I(F(3, 100), F(1, 10), F(1, 10), F(1, 10))),
                  mj_geom(q, cube, density(F(3, 100), F(1, 1000)))))
# The mesh in mm: the geom's density the one the author meant, 0.432 kg over the bar's 4.8e-4 m³ in metres.
mf.append(mj_body("mesh_scale", mj_inertial(q, "0.432", "0 0 0", mmI),
                  mj_geom(q, 'type="mesh" mesh="bar_mm"', density(F(432, 1000), Vbar))))
mf.append(mj_body("tensor_about_origin", mj_inertial(q, "2", "0 0 0.2", shift(bI, F(2), (0, 0, F(2, 10)))),
                  mj_geom(q, cube, rho2, "0 0 0.2")))
mf.append(mj_body("com_outside_geometry", mj_inertial(q, "2", "1 0 0", bI), mj_geom(q, cube, rho2)))
rho18 = density(F(18, 10), F(3, 1000))
mf.append(mj_body("tensor_mismatch", mj_inertial(q, "1.8", "0 0 0", [[rI[1][1], 0, 0], [0, rI[0][0], 0], [0, 0, rI[2][2]]]),
                  mj_geom(q, bar, rho18)))
# The box in the body's axes, its (diagonal) tensor written for them, and the inertial turned 0.5 rad about
# z all the same: diaginertia is in the inertial's frame, so the turn is one too many.
mf.append(mj_body("inertial_rotation", mj_inertial(q, "1.8", "0 0 0", rI, rotation=' euler="0 0 0.5"'),
                  mj_geom(q, bar, rho18)))
# The box turned 0.5 rad about z; its tensor in the body's axes (fullinertia) with ixy of the wrong sign.
mf.append(mj_body("product_sign", mj_inertial(q, "1.8", "0 0 0", flipped, full_tensor=True),
                  mj_geom(q, bar, rho18, rotation=' euler="0 0 0.5"')))
mf.append(mj_body("missing_mesh", mj_inertial(q, "2", "0 0 0", bI), mj_geom(q, 'type="mesh" mesh="no_such_mesh"', rho2)))
mf.append(mj_body("open_mesh", mj_inertial(q, "0.1", "0 0 0", box_I(F(1, 10), F(3, 10), F(4, 100), F(4, 100))),
                  mj_geom(q, 'type="mesh" mesh="open_bar"', density(F(1, 10), Vbar))))
mf.append('  </worldbody>\n</mujoco>\n')
open("arm_flawed.xml", "w").write("".join(mf))

# SDF ---------------------------------------------------------------------------------------------------
def sdf_inertial(m, pose, I):
    rows = "".join("          <%s>%s</%s>\n" % (k, num(I[i][j]), k)
                   for k, (i, j) in (("ixx", (0, 0)), ("ixy", (0, 1)), ("ixz", (0, 2)),
                                     ("iyy", (1, 1)), ("iyz", (1, 2)), ("izz", (2, 2))))
    return ('      <inertial>\n        <pose>%s</pose>\n        <mass>%s</mass>\n        <inertia>\n%s'
            '        </inertia>\n      </inertial>\n' % (pose, m, rows))

def sdf_collision(name, shape, pose="0 0 0 0 0 0"):
    return ('      <collision name="%s">\n        <pose>%s</pose>\n        <geometry>\n          %s\n'
            '        </geometry>\n      </collision>\n' % (name, pose, shape))

def sdf_link(name, inertial_text, collision_text, pose=None):
    at = "      <pose>%s</pose>\n" % pose if pose else ""
    return '    <link name="%s">\n%s%s%s    </link>\n' % (name, at, inertial_text, collision_text)

def sdf_box(a, b, c):
    return "<box><size>%s %s %s</size></box>" % (a, b, c)

def sdf_mesh(uri):
    return "<mesh><uri>%s</uri></mesh>" % uri

# The link poses in the model's frame: upper on base's joint, fore turned -π/2 about y on upper's, tool
# 0.355 m along fore's x and turned 0.5 rad about z (the joint origins of arm.urdf composed).
R_fore = rot_y(-1.5707963267948966)
p_fore = (0, 0, 0.5)
R_tool = matmul(R_fore, rot_z(0.5))
p_tool = tuple(sum(R_fore[i][k] * (0.355, 0, 0)[k] for k in range(3)) + p_fore[i] for i in range(3))
sd = ['<?xml version="1.0"?>\n<!-- The clean 4-link arm of arm.urdf in SDF (make_models.py): every inertial exact. -->\n'
      '<sdf version="1.9">\n  <model name="arm">\n']
sd.append(sdf_link("base", sdf_inertial("8", "0 0 0.05 0 0 0", base_I),
                   sdf_collision("base_collision", sdf_box(0.2, 0.2, 0.1), "0 0 0.05 0 0 0")))
sd.append(sdf_link("upper", sdf_inertial("2.5", "0 0 0.2 0 0 0", upper_I),
                   sdf_collision("upper_collision", "<cylinder><radius>0.05</radius><length>0.4</length></cylinder>",
                                 "0 0 0.2 0 0 0"), pose="0 0 0.1 0 0 0"))
sd.append(sdf_link("fore", sdf_inertial(num(fore_m), "%s 0 0 0 0 0" % num(fore_c), fore_I),
                   sdf_collision("bar", sdf_mesh("meshes/bar.obj"), "0.15 0 0 0 0 0") +
                   sdf_collision("knob", "<sphere><radius>0.03</radius></sphere>", "0.3 0 0 0 0 0"),
                   pose="0 0 0.5 0 -1.5707963267948966 0"))
sd.append(sdf_link("tool", sdf_inertial("0.3", "0 0 0 0 0 0", tool_I),
                   sdf_collision("tool_collision", sdf_box(0.05, 0.05, 0.05)),
                   pose="%s %s" % (nums(p_tool), nums(rpy_of(R_tool)))))
sd.append('    <joint name="shoulder" type="revolute">\n      <parent>base</parent>\n      <child>upper</child>\n'
          '      <axis>\n        <xyz>0 0 1</xyz>\n        <limit><lower>-3</lower><upper>3</upper><effort>10</effort>'
          '<velocity>1</velocity></limit>\n      </axis>\n    </joint>\n')
sd.append('    <joint name="elbow" type="revolute">\n      <parent>upper</parent>\n      <child>fore</child>\n'
          '      <axis>\n        <xyz>0 1 0</xyz>\n        <limit><lower>-3</lower><upper>3</upper><effort>10</effort>'
          '<velocity>1</velocity></limit>\n      </axis>\n    </joint>\n')
sd.append('    <joint name="flange" type="fixed">\n      <parent>fore</parent>\n      <child>tool</child>\n    </joint>\n')
sd.append('  </model>\n</sdf>\n')
open("arm.sdf", "w").write("".join(sd))

sbox = sdf_box(0.1, 0.1, 0.1)
sbar = sdf_box(0.3, 0.1, 0.1)
sf = ['<?xml version="1.0"?>\n<!-- Each defect of arm_flawed.urdf as SDF writes it (make_models.py). -->\n'
      '<sdf version="1.9">\n  <model name="flawed">\n']
sf.append(sdf_link("clean", sdf_inertial("2", "0 0 0 0 0 0", bI), sdf_collision("c", sbox)))
sf.append(sdf_link("not_positive_definite", sdf_inertial("2", "0 0 0 0 0 0", [[0.01, 0, 0], [0, -0.001, 0], [0, 0, 0.01]]),
                   sdf_collision("c", sbox)))
sf.append(sdf_link("triangle_inequality", sdf_inertial("2", "0 0 0 0 0 0", [[0.001, 0, 0], [0, 0.001, 0], [0, 0, 0.01]]),
                   sdf_collision("c", sbox)))
sf.append(sdf_link("zero_mass_with_geometry", sdf_inertial("0", "0 0 0 0 0 0", [[0] * 3] * 3), sdf_collision("c", sbox)))
sf.append(sdf_link("implied_density", sdf_inertial("0.03", "0 0 0 0 0 0", box_I(F(3, 100), F(1, 10), F(1, 10), F(1, 10))),
                   sdf_collision("c", sbox)))
sf.append(sdf_link("mesh_scale", sdf_inertial("0.432", "0 0 0 0 0 0", mmI), sdf_collision("c", sdf_mesh("meshes/bar_mm.obj"))))
sf.append(sdf_link("tensor_about_origin", sdf_inertial("2", "0 0 0.2 0 0 0", shift(bI, F(2), (0, 0, F(2, 10)))),
                   sdf_collision("c", sbox, "0 0 0.2 0 0 0")))
sf.append(sdf_link("com_outside_geometry", sdf_inertial("2", "1 0 0 0 0 0", bI), sdf_collision("c", sbox)))
sf.append(sdf_link("tensor_mismatch", sdf_inertial("1.8", "0 0 0 0 0 0", [[rI[1][1], 0, 0], [0, rI[0][0], 0], [0, 0, rI[2][2]]]),
                   sdf_collision("c", sbar)))
# As in arm_flawed.urdf: the box turned 0.5 rad about z, its link-axes tensor written in an inertial
# frame turned the same (the turn applied twice); then that tensor with ixy of the wrong sign.
sf.append(sdf_link("inertial_rotation", sdf_inertial("1.8", "0 0 0 0 0 0.5", turned), sdf_collision("c", sbar, "0 0 0 0 0 0.5")))
sf.append(sdf_link("product_sign", sdf_inertial("1.8", "0 0 0 0 0 0", flipped), sdf_collision("c", sbar, "0 0 0 0 0 0.5")))
sf.append(sdf_link("missing_mesh", sdf_inertial("2", "0 0 0 0 0 0", bI), sdf_collision("c", sdf_mesh("meshes/no_such_mesh.stl"))))
sf.append(sdf_link("open_mesh", sdf_inertial("0.1", "0 0 0 0 0 0", box_I(F(1, 10), F(3, 10), F(4, 100), F(4, 100))),
                   sdf_collision("c", sdf_mesh("meshes/open_bar.obj"))))
sf.append('  </model>\n</sdf>\n')
open("arm_flawed.sdf", "w").write("".join(sf))
