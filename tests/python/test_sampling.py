"""Where a run samples and where it starts: simulate's t_eval and initial, and errors in scenes built as
dicts named by their place in the dict."""
import os

import numpy as np
import pytest

import tumble
from tumble import Body, Shape

SOURCE = os.environ.get("TUMBLE_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
T_HANDLE = os.path.join(SOURCE, "examples", "t_handle.toml")


def free_box(**simulation):
    """A box spun near its intermediate axis: Jacobi's closed form (tumble.euler_poinsot) is exact."""
    body = Body("box", shape=Shape("box", size=[0.1, 0.2, 0.3]), mass=1.0, velocity=[1.0, 0.0, 0.0],
                angular_velocity=[0.3, 5.0, 0.1], angular_velocity_frame="principal")
    return tumble.make_scene(bodies=[body], **simulation)


def test_t_eval_samples_exactly_there_on_the_closed_form():
    scene = free_box(duration=1.0, timestep=1e-3, integrator="rk4")
    rng = np.random.default_rng(5)
    t_eval = np.sort(rng.uniform(0.0, 2.0, 50))
    exact = tumble.euler_poinsot(tumble.box([0.1, 0.2, 0.3], mass=1.0).principal_moments, [0.3, 5.0, 0.1], t_eval)
    for integrator, tol in (("rk4", 1e-10), ("dopri45", 1e-7)):
        # RK4's global error, O((|omega| h)^4) per unit time, is 6e-12 here; dopri45 keeps each step's
        # error within rtol = 1e-9 and its dense output between steps, 1.4e-9 here. A sample a step
        # (1e-3 s) off its time would be off by |d omega/dt| 1e-3 ~ 1e-2.
        traj = tumble.simulate(scene, integrator=integrator, t_eval=t_eval)
        assert np.array_equal(traj.t, t_eval), integrator  # the start (0) is not in t_eval: not sampled
        assert np.abs(traj.omega_principal[:, 0] - exact.omega_body).max() < tol, integrator
        assert np.abs(traj.position[:, 0, 0] - t_eval).max() < tol, integrator
        assert len(traj.energy_drift) == len(t_eval)
    # t_eval from the start keeps it; the run ends at the last time whatever the scene's duration.
    traj = tumble.simulate(scene, t_eval=[0.0, 0.5, 3.0])
    assert traj.t.tolist() == [0.0, 0.5, 3.0]
    # Times on the output grid give the grid's samples, bit for bit.
    grid = tumble.simulate(scene, output_interval=0.1)
    assert np.array_equal(tumble.simulate(scene, t_eval=grid.t).omega_world, grid.omega_world)


def test_t_eval_refuses_what_cannot_be_sampled():
    scene = free_box(duration=1.0)
    with pytest.raises(ValueError, match=r"t_eval\[2\] = 0.1: give finite times in increasing order"):
        tumble.simulate(scene, t_eval=[0.0, 0.2, 0.1])
    with pytest.raises(ValueError, match=r"t_eval\[1\] = nan"):
        tumble.simulate(scene, t_eval=[0.1, float("nan")])
    with pytest.raises(ValueError, match="not both"):
        tumble.simulate(scene, t_eval=[0.5], output_interval=0.1)
    with pytest.raises(ValueError, match="duration=2.0 but t_eval ends 0.5 s after the start"):
        tumble.simulate(scene, t_eval=[0.5], duration=2.0)
    with pytest.raises(ValueError, match="before the start"):
        tumble.simulate(scene, t_eval=[-1.0, 0.5])
    with pytest.raises(ValueError, match="non-empty"):
        tumble.simulate(scene, t_eval=[])


def test_a_run_continued_from_its_last_sample_is_the_run_in_one_go():
    # The T-handle (a mesh: its reference frame is not its principal one) under gravity with a particle
    # on a spring, 1 s then 1 s more, against 2 s at once. The restart converts the state to the reference
    # frame and back (a few roundings, 1e-16 relative), which 1e3 steps of this motion grow to ~4e-14 of
    # each field's size: 1e-12 of it leaves room, and is still far below any step error (RK4 at
    # |omega| h = 0.03: 1e-7 a step) that a wrong restart would show.
    d = {"simulation": {"duration": 2.0, "timestep": 1e-3, "output_interval": 0.1},
         "world": {"gravity": [0.0, 0.0, -9.81]},
         "bodies": [{"name": "handle", "mesh": "meshes/t_handle.stl", "density": 2700.0,
                     "angular_velocity": [0.1, 0.0, 20.0], "angular_velocity_frame": "reference"}],
         "particles": [{"name": "bob", "mass": 0.1, "position": [0.3, 0.0, 0.0]}],
         "forces": [{"type": "spring", "a": {"body": "handle", "point": [0.0, 0.0, 0.06]},
                     "b": {"particle": "bob"}, "stiffness": 50.0, "rest_length": 0.2}]}
    scene = tumble.scene_from_dict(d, os.path.join(SOURCE, "examples", "scene.toml"))
    whole = tumble.simulate(scene)
    first = tumble.simulate(scene, duration=1.0)
    rest = tumble.simulate(scene, duration=1.0, initial=first)
    assert rest.t[0] == first.t[-1] == 1.0 and np.allclose(rest.t, whole.t[10:], rtol=0, atol=1e-15)
    for f in ("position", "orientation", "velocity", "angular_velocity"):
        assert np.abs(rest.fields[f] - whole.fields[f][10:]).max() < 1e-12 * np.abs(whole.fields[f]).max(), f
    # The same state as a dict (the tutorial's names accepted), and a one-body dict given as vectors.
    as_dict = {"t": 1.0, "position": first.position[-1], "quaternion": first.quaternion[-1],
               "velocity": first.velocity[-1], "omega_world": first.omega_world[-1]}
    assert np.array_equal(tumble.simulate(scene, duration=1.0, initial=as_dict).omega_world, rest.omega_world)
    box = free_box(duration=0.5)
    state = {"t": 2.0, "position": [0, 0, 1], "orientation": [1, 0, 0, 0], "velocity": [0, 0, 0],
             "angular_velocity": [0, 0, 3.0]}
    spin = tumble.simulate(box, initial=state)
    assert spin.t[0] == 2.0 and spin.t[-1] == 2.5
    # About a principal axis (the box's z, its largest moment) the spin stays put: rounding only.
    assert np.abs(spin.omega_world[:, 0] - [0, 0, 3.0]).max() < 1e-13
    assert np.abs(spin.position[:, 0] - [0, 0, 1]).max() == 0


def test_a_start_that_is_not_a_state_is_refused_with_its_row():
    box = free_box(duration=0.5)
    good = {"t": 0.0, "position": [0, 0, 0], "orientation": [1, 0, 0, 0], "velocity": [0, 0, 0],
            "angular_velocity": [0, 0, 1]}
    with pytest.raises(ValueError, match=r"orientation of body 'box' \(row 0\) has norm 2"):
        tumble.simulate(box, initial={**good, "orientation": [2, 0, 0, 0]})
    with pytest.raises(ValueError, match=r"initial state of body 'box' \(row 0\) is not finite"):
        tumble.simulate(box, initial={**good, "velocity": [0, float("inf"), 0]})
    with pytest.raises(ValueError, match=r"position has shape \(1, 2\); the scene needs \(1, 3\)"):
        tumble.simulate(box, initial={**good, "position": [0, 0]})
    with pytest.raises(ValueError, match="give angular_velocity"):
        tumble.simulate(box, initial={k: v for k, v in good.items() if k != "angular_velocity"})
    with pytest.raises(ValueError, match=r"unknown key\(s\) \['omega'\]"):
        tumble.simulate(box, initial={**good, "omega": [0, 0, 1]})
    other = tumble.simulate(tumble.make_scene(bodies=[Body("other", mass=1.0, inertia=[1, 2, 3])], duration=0.1))
    with pytest.raises(ValueError, match=r"bodies and particles \['other'\] are not the scene's \['box'\]"):
        tumble.simulate(box, initial=other)
    no_pose = tumble.simulate(box, fields=["angular_velocity"])
    with pytest.raises(ValueError, match="holds no position, orientation, velocity"):
        tumble.simulate(box, initial=no_pose)


def test_errors_in_a_dict_scene_name_the_place_in_the_dict():
    d = {"simulation": {"duration": 1.0},
         "bodies": [{"name": "a", "shape": {"type": "box", "size": [0.1, 0.2, 0.3]}, "density": 2700},
                    {"name": "b", "shape": {"type": "box", "size": [0.1, -0.2, 0.3]}, "density": 2700}]}
    with pytest.raises(ValueError) as e:
        tumble.scene_from_dict(d)
    message = str(e.value)
    assert "scene dict at bodies[1].shape.size" in message and "scene.toml:" not in message, message
    d["bodies"][1]["shape"]["size"][1] = 0.2
    d["bodies"][0]["densty"] = 1
    with pytest.raises(ValueError, match=r"scene dict at bodies\[0\]\.densty: .*did you mean 'density'"):
        tumble.scene_from_dict(d)
    del d["bodies"][0]["densty"]
    del d["bodies"][1]["shape"], d["bodies"][1]["density"]
    d["bodies"][1]["parts"] = [{"shape": {"type": "sphere", "radius": 0.1}, "mass": 1.0},
                               {"shape": {"type": "sphere", "radius": 0.1}, "mass": -1.0}]
    with pytest.raises(ValueError, match=r"scene dict at bodies\[1\]\.parts\[1\]"):
        tumble.scene_from_dict(d)
    # A study given as a dict: the same.
    with pytest.raises(ValueError, match=r"scene dict at ensemble\.runs"):
        tumble.ensemble({"simulation": {"duration": 1.0}, "bodies": [d["bodies"][0]]}, {"runs": -3, "vary": []})
