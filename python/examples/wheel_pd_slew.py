"""A three-axis slew by reaction wheels under a PD controller written in Python (examples/pd_slew.toml).

The controller is flight software: called every 0.1 s with the state and the wheels' speeds, it returns
the three motor torques, which are held until its next call. It is Wie's quaternion feedback
(Space Vehicle Dynamics and Control, 7.3): with q_e the attitude error (target to body) and omega_b the
body rates, the torque on the body is tau = -K q_e_vec - C omega_b; a wheel's motor torque u acts on the
body as -u along its axis, so each wheel is asked u = -tau along its axis. K = 2 wn^2 I, C = 2 zeta wn I
(per axis the closed loop is I theta'' = -(K/2) theta - C theta' near the target).

    PYTHONPATH=build/release/python /usr/bin/python3 python/examples/wheel_pd_slew.py [out/pd_slew.png]
"""
import os
import sys

import numpy as np

import tumble

here = os.path.dirname(os.path.abspath(__file__))
examples = os.path.join(here, "..", "..", "examples")
plot_path = sys.argv[1] if len(sys.argv) > 1 else os.path.join("out", "pd_slew.png")

I = np.array([10.0, 20.0, 30.0])   # kg m^2, the scene's (principal axes = the body's axes)
J = 0.05                           # each wheel's axial moment
wn, zeta = 0.2, 0.9                # rad/s, the closed loop's natural frequency and damping
K, C = 2 * wn**2 * I, 2 * zeta * wn * I
axis = np.array([1.0, 1.0, 1.0]) / np.sqrt(3.0)
angle = np.radians(60.0)
q_target = np.concatenate([[np.cos(angle / 2)], np.sin(angle / 2) * axis])  # w first


def q_mul(a, b):
    """The Hamilton product a b of w-first quaternions."""
    w1, v1, w2, v2 = a[0], a[1:], b[0], b[1:]
    return np.concatenate([[w1 * w2 - v1 @ v2], w1 * v2 + w2 * v1 + np.cross(v1, v2)])


def conj(q):
    return np.concatenate([[q[0]], -q[1:]])


def rotate_back(q, v):
    """R^T v for the rotation of the w-first quaternion q."""
    return q_mul(q_mul(conj(q), np.concatenate([[0.0], v])), q)[1:]


def error_quaternion(q):
    """The attitude error q_target^-1 q, its scalar part made >= 0 (the shorter way round)."""
    e = q_mul(conj(q_target), q)
    return e if e[0] >= 0 else -e


def controller(t, position, orientation, velocity, omega, speeds):
    q = orientation[0]                       # the body's attitude (w, x, y, z)
    omega_b = rotate_back(q, omega[0])       # its rates in its own axes
    tau = -K * error_quaternion(q)[1:] - C * omega_b
    return -tau                              # the wheels' motor torques (their axes are x, y, z)


scene = tumble.load_scene(os.path.join(examples, "pd_slew.toml"))
traj = tumble.simulate(scene, controller=controller, control_interval=0.1,
                       fields=["orientation", "angular_velocity_principal"])
q = traj.orientation[:, 0, :]
errors = np.array([2 * np.arccos(min(1.0, error_quaternion(qk)[0])) for qk in q])   # rad
speeds, torques = traj.diagnostics["rotor_speed"], traj.diagnostics["rotor_torque"]
L = np.linalg.norm(traj.diagnostics["angular_momentum"], axis=1)

print(f"slew of {np.degrees(angle):.0f} deg about {np.round(axis, 3)}: error {np.degrees(errors[0]):.1f} deg "
      f"at t = 0, {np.degrees(errors[-1]):.2e} deg at t = {traj.t[-1]:g} s")
print(f"wheels {traj.rotor_names}: peak speeds {np.round(np.abs(speeds).max(axis=0), 2)} rad/s, "
      f"peak torques {np.round(np.abs(torques).max(axis=0), 3)} N m")
print(f"total angular momentum |R(I omega + h)| at most {L.max():.1e} kg m^2/s (it starts at 0)")

# The physics, checked: the slew ends at the target, at rest, with the wheels stopped again (the total
# angular momentum is zero throughout: the motors' torques are internal); each wheel's speed is its
# held torques summed, J (Omega_k - Omega_k-1) = u_k 0.1 s, as the zero-order hold says.
assert errors[-1] < 1e-3, errors[-1]
assert np.abs(traj.angular_velocity_principal[-1, 0]).max() < 1e-4
assert np.abs(speeds[-1]).max() < 1e-2
assert L.max() < 1e-12, L.max()
assert np.allclose(J * np.diff(speeds, axis=0), torques[1:] * 0.1, rtol=0, atol=1e-12)

from example_plots import plt, save  # noqa: E402  (after the physics: the numbers print without matplotlib)

fig, ax = plt.subplots(4, 1, figsize=(9, 10), sharex=True, constrained_layout=True)
ax[0].semilogy(traj.t, np.degrees(np.maximum(errors, 1e-12)))
ax[0].set_ylabel("attitude error (deg)")
for k, name in enumerate("xyz"):
    ax[1].plot(traj.t, traj.angular_velocity_principal[:, 0, k], label=f"$\\omega_{name}$")
    ax[2].plot(traj.t, speeds[:, k], label=traj.rotor_names[k])
    ax[3].step(traj.t, torques[:, k], where="pre", label=traj.rotor_names[k])
ax[1].set_ylabel("body rates (rad/s)")
ax[2].set_ylabel("wheel speeds (rad/s)")
ax[3].set_ylabel("motor torques (N m)")
ax[3].set_xlabel("t (s)")
fig.suptitle("A 60 deg slew by three reaction wheels, PD controller at 10 Hz (tumble)")
save(fig, ax[1:], plot_path)
