"""Synthetic gyro telemetry of a tumbling satellite, for `tumble fit` (docs/fit.md).

    PYTHONPATH=build/release/python /usr/bin/python3 examples/fit/make_telemetry.py gyro.csv

writes 10 minutes of 10 Hz gyro samples (6001 lines after the header t,wx,wy,wz) of a small satellite
tumbling freely: principal moments 12.5, 17 and 21 kg m^2, its gyro mounted turned against the principal
axes (so the inertia tensor in sensor axes is a full matrix), white noise of 1e-4 rad/s per component and
a constant bias of (3, -2, 1) x 1e-4 rad/s. The motion is tumble's exact torque-free solution
(tumble.euler_poinsot: Jacobi elliptic functions), independent of the fit's own integration. Prints the
truth the fit should find. Options: --minutes M, --rate HZ, --sigma S, --seed N.
"""
import argparse

import numpy as np

import tumble

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("out", help="the CSV file to write")
parser.add_argument("--minutes", type=float, default=10.0)
parser.add_argument("--rate", type=float, default=10.0, help="samples per second")
parser.add_argument("--sigma", type=float, default=1e-4, help="gyro noise per component (rad/s)")
parser.add_argument("--seed", type=int, default=25)
args = parser.parse_args()

moments = np.array([12.5, 17.0, 21.0])         # kg m^2, principal axes
omega_b0 = np.array([0.03, -0.02, 0.06])      # rad/s, principal axes: a tumble about the major axis
bias = np.array([3e-4, -2e-4, 1e-4])          # rad/s, sensor axes


def rotation(axis, angle):
    """The rotation matrix about a unit axis by an angle (Rodrigues)."""
    k = np.asarray(axis, float) / np.linalg.norm(axis)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


U = rotation([1, 2, 3], 0.7) @ rotation([1, 0, 0], -0.4)  # columns: the principal axes in sensor axes

t = np.arange(int(round(args.minutes * 60 * args.rate)) + 1) / args.rate
omega = tumble.euler_poinsot(moments, omega_b0, t).omega_body @ U.T  # sensor axes: U omega_b
rng = np.random.default_rng(args.seed)
y = omega + bias + args.sigma * rng.standard_normal(omega.shape)
np.savetxt(args.out, np.column_stack([t, y]), delimiter=",", header="t,wx,wy,wz", comments="", fmt="%.10g")

J = U @ np.diag(moments) @ U.T
np.set_printoptions(precision=6, suppress=True)
print(f"{args.out}: {len(t)} samples over {t[-1]:g} s, sigma {args.sigma:g} rad/s")
print("truth: J / trace J in sensor axes =\n", J / np.trace(J))
print("truth: principal moments / trace =", moments / moments.sum(), " ratios I1/I3, I2/I3 =",
      moments[:2] / moments[2])
print("truth: omega(0) =", U @ omega_b0, "rad/s, bias =", bias, "rad/s")
