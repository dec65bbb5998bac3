"""Rotors from Python: a controller written in Python (zero-order hold) against the constant torque it
gives, the rotors' speeds and torques in the diagnostics against their closed form Omega(t) = Omega(0) +
u t / J, the same columns read back from the files `tumble run` writes, and clear errors."""
import os
import subprocess

import numpy as np
import pytest

import tumble

SOURCE = os.environ.get("TUMBLE_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))

SCENE = """
[simulation]
duration = 2.0
timestep = 0.001
output_interval = 0.1
integrator = "rk4"

[[bodies]]
name = "sat"
mass = 20.0
inertia = [[2.0, 0.1, -0.05], [0.1, 3.0, 0.2], [-0.05, 0.2, 4.0]]
angular_velocity = [0.4, -0.3, 0.9]

[[rotors]]
name = "wheel_a"
body = "sat"
axis = [0.6, 0.8, 0.0]
moment = 0.01
speed = 5.0
torque = {u_a}

[[rotors]]
name = "wheel_b"
body = "sat"
axis = [0.0, 0.0, 1.0]
moment = 0.02
speed = -3.0
torque = {u_b}
"""


def scene(u_a=0.0, u_b=0.0):
    return tumble.parse_scene(SCENE.format(u_a=u_a, u_b=u_b))


def test_speeds_and_torques_are_in_the_diagnostics_as_their_closed_form():
    traj = tumble.simulate(scene(0.02, -0.01))
    assert traj.rotor_names == ["wheel_a", "wheel_b"]
    speed, torque = traj.diagnostics["rotor_speed"], traj.diagnostics["rotor_torque"]
    assert speed.shape == torque.shape == (21, 2)
    # Omega = Omega(0) + u t / J: one rounding of each product.
    assert np.allclose(speed[:, 0], 5.0 + 0.02 * traj.t / 0.01, rtol=0, atol=1e-13)
    assert np.allclose(speed[:, 1], -3.0 - 0.01 * traj.t / 0.02, rtol=0, atol=1e-13)
    assert (torque == [0.02, -0.01]).all()


def test_a_controller_giving_a_constant_torque_runs_the_constant_torques_motion():
    # Its pieces restart each speed's line at every call (every 0.05 s): rounding only, 1e-12.
    constant = tumble.simulate(scene(0.02, -0.01))
    calls = []

    def controller(t, position, orientation, velocity, omega, speeds):
        calls.append((t, speeds.copy()))
        return [0.02, -0.01]

    controlled = tumble.simulate(scene(), controller=controller, control_interval=0.05)
    assert np.allclose(controlled.angular_velocity, constant.angular_velocity, rtol=0, atol=1e-12)
    assert np.allclose(controlled.orientation, constant.orientation, rtol=0, atol=1e-12)
    assert np.allclose(controlled.diagnostics["rotor_speed"], constant.diagnostics["rotor_speed"], rtol=0,
                       atol=1e-12)
    # Called at 0, 0.05, ..., 1.95 (not at the end), with the speeds carried from call to call.
    assert len(calls) == 40 and calls[0][0] == 0.0 and np.isclose(calls[-1][0], 1.95)
    t, speeds = calls[20]
    assert np.allclose(speeds, [5.0 + 0.02 * t / 0.01, -3.0 - 0.01 * t / 0.02], rtol=0, atol=1e-12)
    # The total angular momentum stays as it was (no external torque): rk4 does not conserve it exactly,
    # but its error is fifth order in |omega| h = 1e-3 per step; 2e-15 relative is measured, with or
    # without the controller (the constant-torque run gives 2.5e-15), so 1e-13 is 40 times that.
    L = controlled.diagnostics["angular_momentum"]
    assert np.abs(L - L[0]).max() < 1e-13 * np.linalg.norm(L[0])


def test_a_controller_clipped_by_max_torque():
    text = SCENE.format(u_a=0.0, u_b=0.0).replace("speed = 5.0", "speed = 5.0\nmax_torque = 0.01")
    traj = tumble.simulate(tumble.parse_scene(text), controller=lambda *a: np.array([1.0, 0.0]),
                           control_interval=0.1)
    assert (traj.diagnostics["rotor_torque"][:, 0] == 0.01).all()
    assert np.isclose(traj.diagnostics["rotor_speed"][-1, 0], 5.0 + 0.01 * 2.0 / 0.01, rtol=0, atol=1e-12)


def test_what_a_controller_cannot_do_is_a_clear_error():
    with pytest.raises(ValueError, match="no \\[\\[rotors\\]\\]"):
        tumble.simulate(tumble.parse_scene('[simulation]\nduration = 1.0\n[[bodies]]\nname = "b"\nmass = 1.0\ninertia = [1.0, 2.0, 3.0]\n'),
                        controller=lambda *a: [])
    with pytest.raises(ValueError, match="return the 2 rotors' torques"):
        tumble.simulate(scene(), controller=lambda *a: [1.0])
    with pytest.raises(ValueError, match="give controller too"):
        tumble.simulate(scene(), control_interval=0.1)
    with pytest.raises(ZeroDivisionError):  # the controller's own exception reaches the caller
        tumble.simulate(scene(), controller=lambda *a: 1 / 0)
    with pytest.raises(ValueError, match="sensitivities cannot be carried through a rotor controller"):
        tumble.simulate(scene(), controller=lambda *a: [0.0, 0.0], sensitivities=True)


@pytest.mark.parametrize("suffix", [".csv", ".h5"])
def test_the_files_hold_the_rotors_columns(tmp_path, suffix):
    if suffix == ".h5":
        pytest.importorskip("h5py")
    cli = os.environ.get("TUMBLE_CLI")
    if not cli:
        pytest.skip("TUMBLE_CLI (the program) not given")
    path = tmp_path / "wheels.toml"
    path.write_text(SCENE.format(u_a=0.02, u_b=-0.01))
    out = tmp_path / ("wheels" + suffix)
    done = subprocess.run([cli, "run", str(path), "-o", str(out)], capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    read = tumble.read_trajectory(out)
    ran = tumble.simulate(tumble.load_scene(path))
    assert read.rotor_names == ["wheel_a", "wheel_b"]
    assert np.array_equal(read.diagnostics["rotor_speed"], ran.diagnostics["rotor_speed"])
    assert np.array_equal(read.diagnostics["rotor_torque"], ran.diagnostics["rotor_torque"])
    if suffix == ".csv":
        header = open(str(out).replace(".csv", ".diagnostics.csv")).readline().strip().split(",")
        assert header[-4:] == ["rotor_speed_wheel_a", "rotor_speed_wheel_b", "rotor_torque_wheel_a",
                               "rotor_torque_wheel_b"]


def test_a_scene_built_from_classes_is_the_scene_file():
    # examples/pd_slew.toml from Body and Rotor objects: the same run, bit for bit; and a torque table
    # through save_scene and back.
    from tumble import Body, Rotor
    wheels = [Rotor(f"wheel_{a}", "sat", axis=list(np.eye(3)[k]), moment=0.05, max_torque=0.2, max_speed=600.0)
              for k, a in enumerate("xyz")]
    built = tumble.make_scene(bodies=[Body("sat", mass=50.0, inertia=[10.0, 20.0, 30.0])], rotors=wheels,
                              duration=2.0, timestep=0.01, output_interval=0.1, integrator="rk4")
    read = tumble.load_scene(os.path.join(SOURCE, "examples", "pd_slew.toml"))
    law = lambda t, o, q, v, w, speeds: [0.01, -0.02, 0.03]
    a = tumble.simulate(built, controller=law, control_interval=0.1)
    b = tumble.simulate(read, controller=law, control_interval=0.1, duration=2.0)
    assert a.rotor_names == b.rotor_names == ["wheel_x", "wheel_y", "wheel_z"]
    assert np.array_equal(a.orientation, b.orientation)
    assert np.array_equal(a.diagnostics["rotor_speed"], b.diagnostics["rotor_speed"])
    tabled = Rotor("w", "sat", axis=[0.0, 0.0, 1.0], moment=0.1, torque=[[0.0, 0.0], [1.0, 0.02]])
    d = tumble.scene_dict(bodies=[Body("sat", mass=50.0, inertia=[10.0, 20.0, 30.0])], rotors=[tabled],
                          duration=1.0)
    assert d["rotors"] == [{"name": "w", "body": "sat", "axis": [0.0, 0.0, 1.0], "moment": 0.1,
                            "torque": [[0.0, 0.0], [1.0, 0.02]]}]
    traj = tumble.simulate(tumble.scene_from_dict(d))
    # Omega(1) = (1/J) * integral of the ramp = 0.5 * 0.02 * 1 / 0.1
    assert np.isclose(traj.diagnostics["rotor_speed"][-1, 0], 0.1, rtol=0, atol=1e-15)


def test_held_wheels_run_exactly_by_exact_and_the_splittings():
    # Motors holding the wheels' speeds (no torque): the torque-free gyrostat. `exact` evaluates its
    # closed form, the splittings drift by its own flow (exact without external torque at any step); rk4
    # at h = 1e-3 is within its error (~T |w|^5 h^4, about 1e-12 here) of both. The inertia is not
    # diagonal, so the wheels' axes are turned into the principal frame on the way.
    rk4 = tumble.simulate(scene(), integrator="rk4", timestep=1e-3)
    for integrator, h in (("exact", 0.5), ("splitting", 0.5), ("splitting4", 0.25)):
        traj = tumble.simulate(scene(), integrator=integrator, timestep=h)
        assert np.abs(traj.omega_world[-1] - rk4.omega_world[-1]).max() < 1e-10, integrator
        q, r = traj.quaternion[-1], rk4.quaternion[-1]
        assert min(np.abs(q - r).max(), np.abs(q + r).max()) < 1e-10, integrator  # q and -q: one attitude
    # A motor that works is refused by `exact`, naming what to use instead.
    with pytest.raises(Exception, match="splitting"):
        tumble.simulate(scene(0.01, 0.0), integrator="exact")
