"""Euler angles near gimbal lock against an mpmath reference: the rotation rebuilt from the angles tumble
writes is the rotation it holds, to a few ulps, however close to the lock (docs/scene-format.md defines
euler_zyx as R = Rz(yaw) Ry(pitch) Rx(roll) and euler_zxz as R = Rz(phi) Rx(theta) Rz(psi))."""
import mpmath
import numpy as np

import tumble
from tumble import Body

mpmath.mp.dps = 50  # 166 bits: the reference's own rounding is 1e-50, far below a double's 1e-16
EPS = 2.0 ** -52


def rz(a):
    c, s = mpmath.cos(a), mpmath.sin(a)
    return mpmath.matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def ry(a):
    c, s = mpmath.cos(a), mpmath.sin(a)
    return mpmath.matrix([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def rx(a):
    c, s = mpmath.cos(a), mpmath.sin(a)
    return mpmath.matrix([[1, 0, 0], [0, c, -s], [0, s, c]])


def from_quaternion(q):
    """R of the unit quaternion (w, x, y, z), taken as given (each double exactly) and normalised."""
    w, x, y, z = (mpmath.mpf(float(c)) for c in q)
    n = mpmath.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    return mpmath.matrix([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                          [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                          [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def to_quaternion(R):
    """The unit quaternion (w, x, y, z) of R (w > 0.1 for the rotations used here), rounded to doubles."""
    w = mpmath.sqrt(1 + R[0, 0] + R[1, 1] + R[2, 2]) / 2
    return [float(w), float((R[2, 1] - R[1, 2]) / (4 * w)), float((R[0, 2] - R[2, 0]) / (4 * w)),
            float((R[1, 0] - R[0, 1]) / (4 * w))]


def largest_difference(A, B):
    return max(abs(A[i, j] - B[i, j]) for i in range(3) for j in range(3))


def angles_of(quaternions):
    """tumble's euler_zyx and euler_zxz, and the orientation it holds, for each quaternion (one body each)."""
    bodies = [Body(f"b{k}", mass=1.0, inertia=[1.0, 2.0, 3.0], orientation=q) for k, q in enumerate(quaternions)]
    traj = tumble.simulate(tumble.make_scene(bodies=bodies, duration=0.0),
                           fields=["orientation", "euler_zyx", "euler_zxz"])
    return traj.orientation[0], traj.euler_zyx[0], traj.euler_zxz[0]


def test_angles_approaching_gimbal_lock_rebuild_the_rotation_to_a_few_ulps():
    rng = np.random.default_rng(23)
    gaps = [10.0 ** -k for k in range(3, 17)]  # how far short of the lock: 1e-3 … 1e-16 rad
    cases = []  # (convention, the rotation as angles in mpmath)
    for gap in gaps:
        for sign in (1, -1):
            a, b = (mpmath.mpf(float(x)) for x in rng.uniform(-3.0, 3.0, 2))
            cases.append(("zyx", rz(a) * ry(sign * (mpmath.pi / 2 - gap)) * rx(b)))
            cases.append(("zxz", rz(a) * rx(gap if sign > 0 else mpmath.pi - gap) * rz(b)))
    quaternions = [to_quaternion(R) for _, R in cases]
    q_held, zyx, zxz = angles_of(quaternions)
    worst = {"zyx": 0.0, "zxz": 0.0}
    for k, (convention, _) in enumerate(cases):
        R = from_quaternion(q_held[k])
        if convention == "zyx":
            yaw, pitch, roll = (mpmath.mpf(float(x)) for x in zyx[k])
            rebuilt = rz(yaw) * ry(pitch) * rx(roll)
        else:
            phi, theta, psi = (mpmath.mpf(float(x)) for x in zxz[k])
            rebuilt = rz(phi) * rx(theta) * rz(psi)
        worst[convention] = max(worst[convention], float(largest_difference(rebuilt, R)))
    # Each angle rounded once (half an ulp of up to pi) moves R by at most that much per angle; atan2 of
    # correctly rounded arguments adds about as much: 8 eps covers three angles. Before the fix euler_zyx
    # was off by 5e-16 / cos(pitch), up to 4.8e-4 at 1e-12 from the lock.
    assert worst["zyx"] < 8 * EPS, worst
    assert worst["zxz"] < 8 * EPS, worst


def test_unwrapped_angles_follow_a_spin_past_every_half_turn(tmp_path):
    """[output] unwrap_angles: a sphere spinning at 3 rad/s about world z has yaw = 3t through 30 rad (rk4 on a
    constant rotation: ~1e-13 rad), where the wrapped angle jumps by 2 pi at each half turn."""
    scene = tmp_path / "spin.toml"
    scene.write_text('[simulation]\nduration = 10.0\ntimestep = 0.001\noutput_interval = 0.1\n'
                     '[output]\nfields = ["euler_zyx"]\nunwrap_angles = true\n'
                     '[[bodies]]\nname = "ball"\nshape = { type = "sphere", radius = 0.5 }\ndensity = 1000\n'
                     'angular_velocity = [0.0, 0.0, 3.0]\n')
    traj = tumble.simulate(str(scene))
    yaw = traj.euler_zyx[:, 0, 0]
    np.testing.assert_allclose(yaw, 3.0 * traj.t, rtol=0, atol=1e-11)
    assert yaw[-1] > 29.99
