"""Sensitivities from Python and the command line: simulate(sensitivities=True) gives traj.stm and
traj.parameter_sensitivity, checked against rerunning the scene from a perturbed start (central
differences) and against their conventions; tumble run --sensitivities writes them to HDF5."""
import os
import subprocess

import numpy as np
import pytest

import tumble
from tumble import Body, Gravity, Shape, Spring

SOURCE = os.environ.get("TUMBLE_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))


def scene(**simulation):
    """A box spun near its intermediate axis under gravity, and a second one apart from it."""
    bodies = [Body("box", shape=Shape("box", size=[0.1, 0.2, 0.3]), mass=1.0, velocity=[1.0, 0.0, 0.0],
                   angular_velocity=[0.3, 5.0, 0.1], angular_velocity_frame="principal"),
              Body("plate", shape=Shape("box", size=[0.3, 0.2, 0.02]), mass=0.5, position=[1.0, 0.0, 0.0],
                   angular_velocity=[2.0, 0.1, 0.3])]
    return tumble.make_scene(bodies=bodies, forces=[Gravity([0.0, 0.0, -9.81])], **simulation)


def h5py_and_cli():
    """h5py and the tumble program (TUMBLE_CLI) for the tests of `tumble run --sensitivities`, or a skip."""
    h5py = pytest.importorskip("h5py")
    cli = os.environ.get("TUMBLE_CLI")
    if not cli:
        pytest.skip("TUMBLE_CLI (the program) not given")
    return h5py, cli


def test_stm_is_the_derivative_of_the_run_with_respect_to_its_start():
    s = scene(duration=0.5, timestep=1e-3, integrator="rk4", output_interval=0.25)
    traj = tumble.simulate(s, sensitivities=True)
    assert traj.stm.shape == (3, 24, 24) and traj.parameter_sensitivity.shape == (3, 24, 6)
    assert traj.stm_blocks.shape == (3, 2, 12, 12)
    assert np.array_equal(traj.stm[0], np.eye(24)) and not traj.parameter_sensitivity[0].any()
    assert not traj.stm[:, :12, 12:].any(), "bodies apart: zero off the diagonal blocks"
    # Column 9 + k of the box: its angular velocity (world) moved by eps along axis k, all else fixed.
    eps = 1e-6
    start = tumble.simulate(s, duration=0.0)
    for k in range(3):
        ends = []
        for sign in (1, -1):
            initial = dict(t=0.0, position=start.position[0], orientation=start.orientation[0],
                           velocity=start.velocity[0], angular_velocity=start.angular_velocity[0].copy())
            initial["angular_velocity"][0, k] += sign * eps
            ends.append(tumble.simulate(s, initial=initial))
        # dp and dv rows (reference-frame origin, world) and domega: plain differences of the samples.
        column = traj.stm[-1, :, 9 + k]
        for rows, field in ((slice(0, 3), "position"), (slice(6, 9), "velocity"), (slice(9, 12), "angular_velocity")):
            fd = (getattr(ends[0], field)[-1, 0] - getattr(ends[1], field)[-1, 0]) / (2 * eps)
            # Central differences err by eps^2 |x'''| ~ 1e-11 and round by 1e-16 |x| / eps ~ 1e-10.
            np.testing.assert_allclose(column[rows], fd, atol=1e-7, err_msg=f"{field} column {9 + k}")


def test_masses_and_coupling():
    s = scene(duration=0.2, timestep=1e-3, integrator="lie_rk4")
    traj = tumble.simulate(s, sensitivities=True, sensitivity_parameters="mass")
    assert traj.parameter_sensitivity.shape == (len(traj.t), 24, 2)
    # Under gravity alone the mass moves nothing (every mass falls alike): zero to rounding.
    assert np.abs(traj.parameter_sensitivity).max() < 1e-12
    with pytest.raises(ValueError, match="choose inertia"):
        tumble.simulate(s, sensitivities=True, sensitivity_parameters="moments")
    # splitting differentiates the exact free flow (its closed form on dual numbers): under gravity
    # alone it agrees with lie_rk4's STM to lie_rk4's error, (|w| h)^4 ~ 1e-12 a step.
    split = tumble.simulate(s, sensitivities=True, integrator="splitting")
    lie = tumble.simulate(s, sensitivities=True)
    np.testing.assert_allclose(split.stm, lie.stm, atol=1e-9)


def test_run_writes_stm_to_hdf5_and_refuses_csv(tmp_path):
    h5py, cli = h5py_and_cli()
    satellite = os.path.join(SOURCE, "examples", "satellite.toml")
    out = tmp_path / "satellite.h5"
    subprocess.run([cli, "run", satellite, "-o", str(out), "--sensitivities", "--duration", "100", "--quiet"],
                   check=True)
    with h5py.File(out, "r") as f:
        stm, dp = f["stm"], f["parameter_sensitivity"]
        assert stm.attrs["layout"] == "block_diagonal"
        assert stm.shape == (11, 1, 12, 12) and dp.shape == (11, 1, 12, 3)
        assert np.array_equal(stm[0, 0], np.eye(12))
        # Over 100 s of a 5828 s orbit the position responds to the velocity by ~t (ballistic).
        assert 90 < stm[-1, 0, 0, 6] < 110
    # The file reads back as the Trajectory simulate() gives, sensitivities included.
    read = tumble.read_trajectory(out)
    same = tumble.simulate(satellite, duration=100, sensitivities=True)
    np.testing.assert_array_equal(read.stm, same.stm)
    np.testing.assert_array_equal(read.parameter_sensitivity, same.parameter_sensitivity)
    done = subprocess.run([cli, "run", satellite, "-o", str(tmp_path / "s.csv"), "--sensitivities"],
                          capture_output=True, text=True)
    assert done.returncode != 0 and "give an HDF5 output" in done.stderr, done.stderr
    assert not (tmp_path / "s.csv").exists()


def test_force_parameters_closed_form_and_file(tmp_path):
    # Under uniform gravity alone (no torque) the attitude and the spin do not depend on g, and the
    # reference origin moves as o0 + v0 t + g t^2 / 2 (plus a rotation that g does not touch): so
    # d p / d g = t^2/2 I and d v / d g = t I, which rk4 keeps exactly (constant acceleration is a
    # polynomial of degree 2 in t, integrated to rounding).
    s = scene(duration=0.2, timestep=1e-3, integrator="rk4", output_interval=0.1)
    traj = tumble.simulate(s, sensitivities=True, sensitivity_parameters="forces")
    assert traj.parameter_sensitivity.shape == (3, 24, 3)
    assert [n.split(": ")[-1] for n in traj.parameter_names] == ["g_x", "g_y", "g_z"]
    for k, t in enumerate(traj.t):
        for b in range(2):
            rows = slice(12 * b, 12 * b + 12)
            np.testing.assert_allclose(traj.parameter_sensitivity[k, rows][0:3], 0.5 * t * t * np.eye(3), atol=1e-14)
            np.testing.assert_allclose(traj.parameter_sensitivity[k, rows][6:9], t * np.eye(3), atol=1e-13)
            np.testing.assert_allclose(traj.parameter_sensitivity[k, rows][3:6], 0.0, atol=1e-14)
            np.testing.assert_allclose(traj.parameter_sensitivity[k, rows][9:12], 0.0, atol=1e-14)
    _, cli = h5py_and_cli()  # read_trajectory reads the file with h5py
    satellite = os.path.join(SOURCE, "examples", "satellite.toml")
    out = tmp_path / "forces.h5"
    subprocess.run([cli, "run", satellite, "-o", str(out), "--sensitivities", "--sensitivity-parameters", "forces",
                    "--duration", "10", "--quiet"], check=True)
    read = tumble.read_trajectory(out)
    same = tumble.simulate(satellite, duration=10, sensitivities=True, sensitivity_parameters="forces")
    assert read.parameter_names == same.parameter_names and len(read.parameter_names) >= 1
    np.testing.assert_array_equal(read.parameter_sensitivity, same.parameter_sensitivity)
