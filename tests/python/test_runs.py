"""Runs from Python: events, scenes built from classes, the readers of tumble's own files, quaternion
order converters, zero-copy results and Ctrl-C."""
import os
import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest

import tumble
from tumble import Body, Damping, Drag, Event, Gravity, GravityGradient, Particle, PointForce, Shape, Spring, Torque

SOURCE = os.environ.get("TUMBLE_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
EXAMPLES = os.path.join(SOURCE, "examples")
T_HANDLE = os.path.join(EXAMPLES, "t_handle.toml")


def racket(**extra):
    """A box spun near its intermediate axis: omega_2 starts at its extreme (omega_3 = 0)."""
    return Body("racket", shape=Shape("box", size=[0.1, 0.2, 0.3]), mass=1.0,
                angular_velocity=[0.01, 5.0, 0.0], angular_velocity_frame="principal", **extra)


def test_events_find_every_flip_at_the_exact_solutions_times():
    # omega_2 changes sign at (k + 1/2) 2K/lambda. The exact integrator samples the closed form and the
    # crossing is located to 4 ulp of t: 1e-9 s allows for the rounding of the elliptic functions.
    scene = tumble.make_scene(bodies=[racket()], duration=10.0, timestep=0.01, integrator="exact")
    traj = tumble.simulate(scene, events=[Event("flip", body="racket", column="w2")])
    T = tumble.euler_poinsot(tumble.box([0.1, 0.2, 0.3], mass=1.0).principal_moments, [0.01, 5.0, 0.0],
                             [0.0]).flip_interval
    flips = traj.event_times("flip")
    assert len(flips) == int(10.0 / T + 0.5)
    np.testing.assert_allclose(flips, (np.arange(len(flips)) + 0.5) * T, rtol=0, atol=1e-9)
    assert all(e.body == "racket" and e.name == "flip" for e in traj.events)


def test_a_python_event_sees_every_body_and_can_stop_the_run():
    # A ball thrown up at 10 m/s from 2 m lands at t* = (v0 + sqrt(v0^2 + 2 g z0)) / g; the event is a
    # Python function of the whole state (centre-of-mass height of body 0), falling, stopping the run.
    # RK4 integrates the parabola exactly (a cubic in t is within its order), so only the event location's
    # 4 ulp and rounding remain.
    g, z0, v0 = 9.81, 2.0, 10.0
    scene = tumble.make_scene(bodies=[Body("ball", shape=Shape("sphere", radius=0.1), mass=1.0,
                                           position=[0, 0, z0], velocity=[0, 0, v0])],
                              forces=[Gravity([0, 0, -g])], duration=10.0, timestep=0.01)
    calls = []

    def height(t, position, orientation, velocity, omega):
        calls.append(position.shape)
        return position[0, 2]

    traj = tumble.simulate(scene, events=[Event("landing", g=height, direction="falling", stop=True)])
    t_star = (v0 + np.sqrt(v0 ** 2 + 2 * g * z0)) / g
    assert traj.event_times("landing") == pytest.approx([t_star], abs=1e-12)
    assert traj.t[-1] == pytest.approx(t_star, abs=1e-12), "the run ends at the crossing"
    assert traj.events[0].body is None and set(calls) == {(1, 3)}


def test_settings_are_the_tables_and_a_wrong_kind_is_named():
    # The keywords are the settings of sim/run_settings.hpp (tumble run's options, [simulation]'s keys).
    keys = {s["key"] for s in tumble._tumble._run_settings()}
    assert {"duration", "timestep", "integrator", "formulation", "output_interval", "rtol", "atol",
            "drift_threshold", "threads"} == keys
    scene = tumble.make_scene(bodies=[racket()], duration=0.1, timestep=0.01)
    traj = tumble.simulate(scene, duration=0.2, drift_threshold=0.0)
    assert traj.t[-1] == 0.2
    with pytest.raises(ValueError, match="timestep= takes a number, not a name"):
        tumble.simulate(scene, timestep="fast")
    with pytest.raises(ValueError, match="unknown integrator 'rk5'"):
        tumble.simulate(scene, integrator="rk5")


def test_an_event_on_every_body_gives_each_its_own_crossings_as_if_alone():
    # 40 boxes spun near the intermediate axis at different rates, as tumble.bodies arrays: each body is
    # a lane that locates its own flips, so its crossings are those of the body simulated alone, bit for
    # bit (the engine steps a body alike in any company).
    n = 40
    rng = np.random.default_rng(3)
    omega = np.column_stack([rng.uniform(0.01, 0.1, n), rng.uniform(5, 15, n), np.zeros(n)])
    moments = np.array([0.025, 0.05, 0.065])
    scene = tumble.bodies(np.full(n, 6.0), moments, omega=omega, omega_frame="principal", gravity=[0, 0, -9.81],
                          duration=3.0, timestep=1e-3, output_interval=0.1, integrator="rk4")
    traj = tumble.simulate(scene, events=[Event("flip", body="*", column="w2")])
    assert {e.body for e in traj.events} == {f"body_{i}" for i in range(n)}, "every body flips within 3 s"
    for i in (0, 17, 39):
        alone = tumble.bodies([6.0], moments, omega=omega[i:i + 1], omega_frame="principal", gravity=[0, 0, -9.81],
                              duration=3.0, timestep=1e-3, output_interval=0.1, integrator="rk4")
        one = tumble.simulate(alone, events=[Event("flip", body="body_0", column="w2")])
        assert list(traj.event_times("flip", f"body_{i}")) == list(one.event_times("flip"))
    # Bodies that do not move independently cannot be lanes: the message says why.
    coupled = tumble.make_scene(bodies=[racket()], forces=[Torque("racket", torque=[0, 0, 1e-3])], duration=0.1)
    with pytest.raises(ValueError, match="needs bodies that move independently"):
        tumble.simulate(coupled, events=[Event("flip", body="*", column="w2")])


def test_event_mistakes_raise_the_scene_files_message():
    scene = tumble.make_scene(bodies=[racket()], duration=1.0)
    with pytest.raises(ValueError, match=r"^events\[0\]: event 'e': no body or particle named \"rocket\"; did you mean \"racket\"\?"):
        tumble.simulate(scene, events=[Event("e", body="rocket", column="w2")])
    with pytest.raises(ValueError, match=r"^events\[0\]: event 'e': no output column \"w9\""):
        tumble.simulate(scene, events=[{"name": "e", "body": "racket", "column": "w9"}])
    with pytest.raises(TypeError, match="events must be tumble.Event objects or dicts"):
        tumble.simulate(scene, events=["flip"])
    with pytest.raises(ValueError, match="must return a number"):
        tumble.simulate(scene, events=[Event("e", g=lambda *a: "up")])
    with pytest.raises(ValueError, match="is a Python function: give it to simulate"):
        tumble.make_scene(bodies=[racket()], events=[Event("e", g=lambda *a: 0.0)], duration=1.0)
    # A name already watched would count each crossing twice under it: the scene's own, or one given twice.
    with pytest.raises(ValueError, match=r"^events\[0\]: an event named 'flip' is already watched \(the scene's \[\[events\]\]\)"):
        tumble.simulate(tumble.load_scene(T_HANDLE), duration=0.1, events=[Event("flip", body="handle", column="w2")])
    with pytest.raises(ValueError, match=r"^events\[1\]: an event named 'e' is already watched \(events\[0\]\)"):
        tumble.simulate(scene, events=[Event("e", body="racket", column="w2"), Event("e", g=lambda *a: 1.0)])


def test_a_scene_built_from_classes_is_the_scene_file_bit_for_bit(tmp_path):
    # Every force model as a class, against the same scene written as TOML by hand.
    bodies = [Body("a", shape=Shape("box", size=[0.1, 0.2, 0.3]), density=2700, position=[0, 0, 1],
                   angular_velocity=[1, 2, 3]),
              Body("b", mass=2.0, inertia=[0.1, 0.2, 0.25], position=[1, 0, 0], velocity=[0, 1, 0])]
    forces = [Gravity([0, 0, -9.81]), PointForce("a", [1, 0, 0], point=[0.05, 0, 0]), Torque("b", [0, 0, 0.1], frame="reference"),
              Damping("a", linear=0.1, angular=0.01), Drag(linear=0.01),
              Spring(tumble.spring_end(body="a", point=[0, 0, 0.15]), tumble.spring_end(particle="p"), stiffness=50.0,
                     rest_length=0.5),
              GravityGradient(mu=1.0, center=[0, 0, -10])]
    built = tumble.make_scene(bodies=bodies, particles=[Particle("p", 0.5, position=[0, 1, 1])], forces=forces,
                              duration=0.5, timestep=1e-3, output_interval=0.1)
    text = textwrap.dedent("""\
        [simulation]
        duration = 0.5
        timestep = 1e-3
        output_interval = 0.1
        [world]
        gravity = [0, 0, -9.81]
        [[bodies]]
        name = "a"
        shape = { type = "box", size = [0.1, 0.2, 0.3] }
        density = 2700
        position = [0, 0, 1]
        angular_velocity = [1, 2, 3]
        [[bodies]]
        name = "b"
        mass = 2.0
        inertia = [0.1, 0.2, 0.25]
        position = [1, 0, 0]
        velocity = [0, 1, 0]
        [[particles]]
        name = "p"
        mass = 0.5
        position = [0, 1, 1]
        [[forces]]
        type = "force"
        body = "a"
        force = [1, 0, 0]
        point = [0.05, 0, 0]
        [[forces]]
        type = "torque"
        body = "b"
        torque = [0, 0, 0.1]
        frame = "reference"
        [[forces]]
        type = "damping"
        body = "a"
        linear = 0.1
        angular = 0.01
        [[forces]]
        type = "drag"
        linear = 0.01
        [[forces]]
        type = "spring"
        a = { body = "a", point = [0, 0, 0.15] }
        b = { particle = "p" }
        stiffness = 50.0
        rest_length = 0.5
        [[forces]]
        type = "gravity_gradient"
        mu = 1.0
        center = [0, 0, -10]
        """)
    by_hand = tumble.parse_scene(text)
    one, two = tumble.simulate(built), tumble.simulate(by_hand)
    assert one.names == ["a", "b", "p"]
    for name in one.fields:
        np.testing.assert_array_equal(one.fields[name], two.fields[name], err_msg=name)
    # Saved and read back: the same scene again.
    tumble.save_scene(tumble.scene_dict(bodies=bodies, particles=[Particle("p", 0.5, position=[0, 1, 1])],
                                        forces=forces, duration=0.5, timestep=1e-3, output_interval=0.1),
                      tmp_path / "built.toml")
    three = tumble.simulate(tumble.load_scene(tmp_path / "built.toml"))
    np.testing.assert_array_equal(three.position, one.position)
    # A mistake is the file's message.
    with pytest.raises(ValueError, match=r"stiffness is -1 N/m: it must be positive"):
        tumble.make_scene(bodies=bodies[:1], forces=[Spring(tumble.spring_end(body="a"), tumble.spring_end(anchor=[0, 0, 0]),
                                                            stiffness=-1)], duration=1.0)
    with pytest.raises(TypeError, match="unknown \\[simulation\\] keys \\['step'\\]"):
        tumble.scene_dict(bodies=bodies, step=1e-3)


@pytest.mark.parametrize("suffix", [".csv", ".h5"])
def test_reading_the_command_lines_file_gives_the_same_trajectory(tmp_path, suffix):
    # CSV holds 17 significant digits and HDF5 the doubles themselves: every value reads back exactly.
    cli = os.environ.get("TUMBLE_CLI")
    if not cli:
        pytest.skip("TUMBLE_CLI (the program) not given")
    out = tmp_path / ("t" + suffix)
    fields = "position,orientation,angular_velocity_principal,com_position"
    subprocess.run([cli, "run", T_HANDLE, "-o", str(out), "--quiet", "--duration", "8", "--fields", fields], check=True)
    read = tumble.read_trajectory(out)
    run = tumble.simulate(T_HANDLE, duration=8.0, fields=fields.split(","))
    assert read.names == run.names == ["handle"]
    np.testing.assert_array_equal(read.t, run.t)
    for name in fields.split(","):
        np.testing.assert_array_equal(read.fields[name], run.fields[name], err_msg=name)
        assert read.units[name] == run.units[name] and read.frames[name] == run.frames[name]
    for name in ("kinetic_energy", "angular_momentum", "energy_drift"):
        np.testing.assert_array_equal(read.diagnostics[name], run.diagnostics[name], err_msg=name)
    assert read.events == run.events and [e.name for e in read.events] == ["flip", "flip"]
    assert read.omega_principal.shape == (len(run.t), 1, 3)


def test_reading_something_else_says_what_is_wrong(tmp_path):
    bad = tmp_path / "x.csv"
    bad.write_text("a,b,c\n1,2,3\n")
    with pytest.raises(ValueError, match=r"x.csv:1: the header starts with 'a,b', not 't,body'"):
        tumble.read_trajectory(bad)
    with pytest.raises(FileNotFoundError, match="no trajectory file"):
        tumble.read_trajectory(tmp_path / "missing.csv")


def test_quaternion_order_converters_match_the_rotation_they_stand_for():
    # Half-turn-free rotation about (1, 2, 3) by 0.7 rad: w = cos(0.35), (x, y, z) = sin(0.35) n.
    n = np.array([1.0, 2.0, 3.0]) / np.sqrt(14.0)
    q = np.concatenate([[np.cos(0.35)], np.sin(0.35) * n])
    xyzw = tumble.to_xyzw(q)
    assert xyzw[3] == q[0] and np.array_equal(xyzw[:3], q[1:])
    np.testing.assert_array_equal(tumble.from_xyzw(xyzw), q)
    batch = np.tile(q, (5, 2, 1))
    assert tumble.to_xyzw(batch).shape == (5, 2, 4)
    np.testing.assert_array_equal(tumble.from_xyzw(tumble.to_xyzw(batch)), batch)
    with pytest.raises(ValueError, match=r"quaternions must be an array \(\.\.\., 4\); got shape \(3,\)"):
        tumble.to_xyzw([1, 0, 0])


def test_results_are_the_librarys_buffers_and_name_the_tutorials_symbols():
    traj = tumble.simulate(T_HANDLE, duration=1.0)
    for a in (traj.t, traj.position, traj.omega_principal, traj.kinetic_energy):
        assert a.dtype == np.float64 and not a.flags.owndata and a.base is not None, "no copy"
    T = len(traj.t)
    assert traj.quaternion is traj.orientation and traj.omega_world is traj.angular_velocity
    assert traj.omega_body.shape == traj.omega_principal.shape == (T, 1, 3)
    assert traj.angular_momentum.shape == (T, 3) and traj.energy_drift.shape == (T,)
    # omega in principal axes = R^T omega_world with R from the principal-frame quaternion; the T-handle's
    # reference axes are its principal axes up to their order, so |omega| agrees in every frame.
    np.testing.assert_allclose(np.linalg.norm(traj.omega_body, axis=2), np.linalg.norm(traj.omega_world, axis=2),
                               rtol=1e-14)
    with pytest.raises(AttributeError, match="has no field 'euler_zyx'"):
        traj.euler_zyx


def test_arrays_of_the_wrong_shape_name_the_expected_shape():
    with pytest.raises(ValueError, match=r"orientation must be \(N, 4\) = \(3, 4\), quaternions w, x, y, z, "
                                         r"or \(4,\) for every body; got shape \(3, 3\)"):
        tumble.bodies(mass=np.ones(3), moments=np.ones((3, 3)), orientation=np.ones((3, 3)))
    with pytest.raises(ValueError, match=r"mass must be \(N,\)"):
        tumble.bodies(mass=np.ones((3, 1)), moments=np.ones((3, 3)))
    # One row stands for every body.
    scene = tumble.bodies(mass=np.ones(3), moments=[1.0, 2.0, 3.0], omega=[0, 1, 0], duration=0.01)
    assert tumble.simulate(scene).omega_world.shape == (2, 3, 3)


def test_ctrl_c_raises_keyboard_interrupt_with_the_samples_so_far(tmp_path):
    # A run of minutes, interrupted after it has started: the child catches tumble.Interrupted (a
    # KeyboardInterrupt) and reports what it kept.
    script = tmp_path / "long.py"
    script.write_text(textwrap.dedent(f"""
        import sys, numpy as np, tumble
        scene = tumble.bodies(mass=np.ones(1000), moments=np.tile([1.0, 2.0, 3.0], (1000, 1)),
                              omega=[0.1, 3.0, 0.0], duration=1e4, timestep=1e-3, output_interval=0.5)
        print("started", flush=True)
        try:
            tumble.simulate(scene, integrator="rk4", threads=1)
        except KeyboardInterrupt as e:
            t = e.trajectory
            assert isinstance(e, tumble.Interrupted) and not t.complete
            print(len(t.t), t.t[-1], t.position.shape[1], flush=True)
            sys.exit(0)
        sys.exit(3)
        """))
    child = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, text=True,
                             env=dict(os.environ))
    assert child.stdout.readline().strip() == "started"
    import time
    time.sleep(1.0)
    child.send_signal(signal.SIGINT)
    out, _ = child.communicate(timeout=60)
    assert child.returncode == 0, out
    samples, t_last, n = out.split()
    assert int(samples) >= 1 and 0 < float(t_last) < 1e4 and int(n) == 1000


@pytest.mark.parametrize("example,args", [("t_handle_flips.py", ["{tmp}/omega.png"]),
                                          ("mesh_inertia.py", ["{tmp}/bracket_mm.stl"]),
                                          ("monte_carlo_flips.py", ["2000", "{tmp}/flips.png"]),
                                          ("wheel_pd_slew.py", ["{tmp}/pd_slew.png"]),
                                          ("dual_spin_flip.py", ["{tmp}/dual_spin.png"])])
def test_every_python_example_runs(tmp_path, example, args):
    # Each example checks its own physics (the flip spacing, the bracket against two boxes, the first
    # flips against K(m)/lambda) with asserts; here they run as a user runs them.
    path = os.path.join(SOURCE, "python", "examples", example)
    done = subprocess.run([sys.executable, path] + [a.format(tmp=tmp_path) for a in args], capture_output=True,
                          text=True, timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr
    for a in args:
        if a.endswith((".png", ".stl")):
            assert os.path.getsize(a.format(tmp=tmp_path)) > 1000


@pytest.mark.parametrize("suffix", [".csv", ".h5"])
def test_an_ensemble_from_python_is_the_command_lines_table(tmp_path, suffix):
    # The study of examples/t_handle_ensemble.toml cut to 30 runs, from Python (threads 1 and 2) and from
    # `tumble ensemble`, read back with read_ensemble: the same numbers, bit for bit.
    cli = os.environ.get("TUMBLE_CLI")
    if not cli:
        pytest.skip("TUMBLE_CLI (the program) not given")
    import tomllib
    import tomli_w
    with open(os.path.join(EXAMPLES, "t_handle_ensemble.toml"), "rb") as f:
        d = tomllib.load(f)
    d["ensemble"]["runs"] = 30
    d["ensemble"]["outputs"].pop("trajectories")
    d["bodies"][0]["mesh"] = os.path.join(EXAMPLES, "meshes", "t_handle.stl")
    scene = tmp_path / "study.toml"
    scene.write_text(tomli_w.dumps(d))
    one = tumble.ensemble(scene, threads=1)
    two = tumble.ensemble(d, threads=2)
    out = tmp_path / ("t" + suffix)
    subprocess.run([cli, "ensemble", str(scene), "-o", str(out), "--quiet"], check=True)
    read = tumble.read_ensemble(out)
    assert len(one) == 30 and list(one.columns) == list(read.columns)
    for name in one.columns:
        np.testing.assert_array_equal(one[name], two[name], err_msg=name)
        np.testing.assert_array_equal(one[name], read[name], err_msg=name)
    # Physics: each run's mean interval between flips is 2K(m)/lambda for its own drawn spin.
    part = tumble.inertia(os.path.join(EXAMPLES, "meshes", "t_handle.stl"), density=2700)
    for k in range(30):
        w_ref = np.array([one["bodies.handle.angular_velocity[0]"][k], 0.0, one["bodies.handle.angular_velocity[2]"][k]])
        w_principal = part.principal_axes.T @ w_ref  # reference axes -> principal axes
        T = tumble.euler_poinsot(part.principal_moments, w_principal, [0.0]).flip_interval
        if one["flip.count"][k] >= 2:
            assert one["flip.mean_interval"][k] == pytest.approx(T, abs=1e-6)
    assert {s["column"] for s in read.summary} >= {"flip.first_t", "energy_drift_max"}
    # A CSV table whose run column is not 0, 1, 2, … (edited, or another file) is refused by name.
    if suffix == ".csv":
        lines = out.read_text().splitlines()
        lines[3] = "0" + lines[3][lines[3].index(","):]  # row 2 says run 0
        edited = tmp_path / "edited.csv"
        edited.write_text("\n".join(lines) + "\n")
        with pytest.raises(ValueError, match="row 2 holds run 0 where run 2 belongs"):
            tumble.read_ensemble(edited)


def test_a_report_of_a_tampered_file_is_an_error_not_a_crash(tmp_path):
    # Geometry offsets that would make `tumble report` read past its arrays are refused by name.
    cli = os.environ.get("TUMBLE_CLI")
    if not cli:
        pytest.skip("TUMBLE_CLI (the program) not given")
    import h5py
    scene = tmp_path / "two.toml"
    scene.write_text(textwrap.dedent("""\
        [simulation]
        duration = 0.1
        [[bodies]]
        name = "a"
        shape = { type = "box", size = [0.1, 0.2, 0.3] }
        mass = 1.0
        [[bodies]]
        name = "b"
        shape = { type = "sphere", radius = 0.1 }
        mass = 1.0
        """))
    out = tmp_path / "two.h5"
    subprocess.run([cli, "run", str(scene), "-o", str(out), "--quiet"], check=True)
    with h5py.File(out, "r+") as f:
        offsets = f["geometry/vertex_offsets"]
        offsets[1] = 10 ** 9  # beyond every vertex, while the last offset still counts them all
    done = subprocess.run([cli, "report", str(out)], capture_output=True, text=True)
    assert done.returncode == 1, done.stdout + done.stderr
    assert "offsets are not ascending whole numbers from 0" in done.stderr


def test_a_process_forked_after_threaded_runs_still_runs_threaded_scenes():
    # multiprocessing's default start method on Linux forks. libgomp's threads do not survive a fork and
    # its next parallel region in the child waited for them forever; the engine now steps the child on
    # one thread. The child's trajectory must be the parent's, bit for bit (a body's step does not
    # depend on the thread count); a hang fails by the timeout.
    n = 2000
    rng = np.random.default_rng(1)
    scene = tumble.bodies(mass=np.ones(n), moments=np.tile([1.0, 2.0, 3.0], (n, 1)),
                          omega=rng.normal(size=(n, 3)), duration=0.05, timestep=1e-3, output_interval=0.05)
    parent = tumble.simulate(scene, integrator="rk4", threads=2)
    pid = os.fork()
    if pid == 0:  # the child: no pytest machinery, only an exit status
        same = False
        try:
            child = tumble.simulate(scene, integrator="rk4", threads=2)
            same = np.array_equal(child.orientation, parent.orientation)
        finally:
            os._exit(0 if same else 1)
    deadline = time.monotonic() + 30.0
    while time.monotonic() < deadline:
        done, status = os.waitpid(pid, os.WNOHANG)
        if done == pid:
            assert os.waitstatus_to_exitcode(status) == 0, "the child's trajectory differs from the parent's"
            return
        time.sleep(0.02)
    os.kill(pid, signal.SIGKILL)
    os.waitpid(pid, 0)
    pytest.fail("a threaded run in a forked child hangs")


def test_a_forged_hdf5_trajectory_reads_nothing_outside_itself(tmp_path):
    # A received .h5 could point read_trajectory at any local file: an external link, external storage
    # (raw bytes of another file as a dataset) or a dataset claiming far more than the file holds. Each
    # is refused by name; the secret's bytes never reach the arrays.
    cli = os.environ.get("TUMBLE_CLI")
    if not cli:
        pytest.skip("TUMBLE_CLI (the program) not given")
    import h5py
    secret = tmp_path / "secret.bin"
    secret.write_bytes(np.arange(64, dtype=np.float64).tobytes())
    scene = tmp_path / "s.toml"
    scene.write_text('[simulation]\nduration = 0.1\n[[bodies]]\nname = "a"\nshape = { type = "box", size = [1, 2, 3] }\n'
                     'mass = 1.0\n')
    good = tmp_path / "good.h5"
    subprocess.run([cli, "run", str(scene), "-o", str(good), "--quiet"], check=True)
    assert len(tumble.read_trajectory(good).t) == 11

    def forged(name, change):
        path = tmp_path / name
        path.write_bytes(good.read_bytes())
        with h5py.File(path, "r+") as f:
            change(f)
        return path

    def external_link(f):
        del f["t"]
        f["t"] = h5py.ExternalLink(str(secret), "/anything")

    def external_storage(f):
        n = len(f["t"])
        del f["t"]
        f.create_dataset("t", shape=(n,), dtype="f8", external=[(str(secret), 0, 8 * n)])

    def huge_claim(f):
        del f["t"]
        f.create_dataset("t", shape=(10 ** 9,), dtype="f8", chunks=(1024,))  # no chunk written

    for name, change, message in [("link.h5", external_link, "t is a ExternalLink"),
                                  ("storage.h5", external_storage, "keeps its data in other files"),
                                  ("claim.h5", huge_claim, "claims 8000000000 bytes")]:
        with pytest.raises(ValueError, match=message):
            tumble.read_trajectory(forged(name, change))


def test_mistaken_arguments_are_named():
    # Each was an error about something else (a letter 'p' as a field, "'NoneType' object is not
    # iterable", RecursionError): now the argument and the fix.
    scene = tumble.make_scene(bodies=[racket()], duration=0.01)
    with pytest.raises(ValueError, match=r"fields='position' must be a list of field names, e.g. fields=\['position'\]"):
        tumble.simulate(scene, fields="position")
    with pytest.raises(ValueError, match="timestep= takes a number"):
        tumble.simulate(scene, timestep="abc")
    with pytest.raises(ValueError, match=r"the force function returned None \(a NoneType\); it must return \(force, torque\)"):
        tumble.simulate(scene, force=lambda *args: None)
    with pytest.raises(ValueError, match="returned 3 values"):
        tumble.simulate(scene, force=lambda t, i, *rest: (np.zeros((len(i), 3)),) * 3)
    with pytest.raises(TypeError, match="force must be a function"):
        tumble.simulate(scene, force=3.0)
    d = {"simulation": {"duration": 1.0}}
    d["simulation"]["again"] = d
    with pytest.raises(ValueError, match="the scene dict contains itself"):
        tumble.scene_from_dict(d)


def test_a_deeply_nested_scene_in_a_small_thread_is_an_error_not_a_crash():
    # A thread's stack is small (here 256 KiB); toml++ recursed once per nesting level (to 256) and
    # crashed the interpreter. Nesting past 32 is refused before it parses.
    import threading
    text = "[simulation]\nduration = 1\nx = " + "{a = " * 250 + "1" + "}" * 250 + "\n"
    result = []

    def parse():
        try:
            tumble.parse_scene(text, "deep.toml")
        except ValueError as e:
            result.append(str(e))

    previous = threading.stack_size(256 * 1024)
    try:
        worker = threading.Thread(target=parse)
        worker.start()
        worker.join()
    finally:
        threading.stack_size(previous)
    assert result and "nested more than 32 deep" in result[0], result


def test_ctrl_c_inside_a_python_force_keeps_the_samples_so_far():
    # Python raises KeyboardInterrupt in whatever Python code runs when Ctrl-C arrives: during a run
    # with a force written in Python, that is the force. It was a plain KeyboardInterrupt without the
    # samples; it is tumble.Interrupted, whose trajectory ends at the last sample before the step.
    scene = tumble.make_scene(bodies=[racket()], duration=10.0, timestep=1e-3, output_interval=0.1,
                              integrator="rk4")
    calls = [0]

    def force(t, index, position, orientation, velocity, omega):
        calls[0] += 1
        if calls[0] == 4000:  # rk4: 4 evaluations a step, so in the step from t = 0.999 s to 1 s
            raise KeyboardInterrupt
        return np.zeros((len(index), 3)), np.zeros((len(index), 3))

    with pytest.raises(tumble.Interrupted) as caught:
        tumble.simulate(scene, force=force)
    t = caught.value.trajectory
    assert not t.complete and len(t.t) == 10 and t.t[-1] == pytest.approx(0.9)
    free = tumble.simulate(scene)  # the same motion without the (zero) force: the samples agree
    np.testing.assert_array_equal(t.orientation, free.orientation[:10])
