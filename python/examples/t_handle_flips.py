"""The T-handle flipping, from Python: simulate it, catch each flip as an event (omega_2, its angular
velocity about the intermediate principal axis, changes sign), compare their spacing with the exact
2K(m)/lambda, and plot omega in principal axes with the flips marked.

    PYTHONPATH=build/release/python /usr/bin/python3 python/examples/t_handle_flips.py [out/t_handle_omega.png]
"""
import os
import sys

import numpy as np

import tumble

here = os.path.dirname(os.path.abspath(__file__))
examples = os.path.join(here, "..", "..", "examples")
plot_path = sys.argv[1] if len(sys.argv) > 1 else os.path.join("out", "t_handle_omega.png")

scene = tumble.load_scene(os.path.join(examples, "t_handle.toml"))  # its [[events]] watch the flips
traj = tumble.simulate(scene, integrator="rk4", timestep=1e-3, output_interval=0.01)
w = traj.omega_principal[:, 0, :]  # (T, 3): omega_1, omega_2, omega_3 about the principal axes (rad/s)
flips = traj.event_times("flip")

part = tumble.inertia(os.path.join(examples, "meshes", "t_handle.stl"), density=2700)
exact = tumble.euler_poinsot(part.principal_moments, w[0], [0.0])
print(f"T-handle: {part.mass * 1000:.1f} g, principal moments {part.principal_moments} kg m^2")
print(f"flips at t = {np.array2string(flips, precision=4)} s")
print(f"spacing {np.diff(flips).mean():.9f} s; exact 2K(m)/lambda = {exact.flip_interval:.9f} s "
      f"({exact.regime.replace('_', ' ')})")
print(f"energy drift over {traj.t[-1]:g} s with rk4: {np.nanmax(np.abs(traj.energy_drift)):.1e}")

from example_plots import plt, save  # noqa: E402  (after the physics: the numbers print without matplotlib)

fig, ax = plt.subplots(figsize=(11, 4), constrained_layout=True)
for k, label in enumerate(["$\\omega_1$ (minor axis)", "$\\omega_2$ (intermediate: the stem)", "$\\omega_3$ (major axis)"]):
    ax.plot(traj.t, w[:, k], label=label)
for t in flips:
    ax.axvline(t, color="0.6", linestyle="--", linewidth=0.8)
ax.set_xlabel("t (s)")
ax.set_ylabel("angular velocity, principal axes (rad/s)")
ax.set_title(f"T-handle: a flip every {exact.flip_interval:.3f} s (dashed: tumble's flip events)")
save(fig, [ax], plot_path)
