"""The Python module against closed forms, the exact solution and the command-line program."""
import csv
import math
import os
import subprocess

import numpy as np
import pytest

import tumble

SOURCE = os.environ.get("TUMBLE_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
EXAMPLES = os.path.join(SOURCE, "examples")


def test_the_smallest_program_reads_as_documented():
    scene = tumble.load_scene(os.path.join(EXAMPLES, "t_handle.toml"))
    traj = tumble.simulate(scene, integrator="rk4", formulation="mixed", timestep=1e-3, duration=20.0,
                           output_interval=0.1)
    assert traj.t.shape == (201,)
    assert traj.quaternion.shape == (201, 1, 4) and traj.omega_world.shape == (201, 1, 3)
    # Unit quaternions, w first: the run starts at the identity.
    np.testing.assert_allclose(np.linalg.norm(traj.quaternion, axis=2), 1.0, rtol=0, atol=1e-14)
    assert traj.quaternion[0, 0].tolist() == [1.0, 0.0, 0.0, 0.0]
    part = tumble.inertia(os.path.join(EXAMPLES, "meshes", "t_handle.stl"), density=2700)
    assert part.mass == pytest.approx(2700 * part.volume, rel=1e-14)
    assert part.principal_axes.shape == (3, 3) and part.inertia.shape == (3, 3)
    np.testing.assert_allclose(part.principal_axes @ np.diag(part.principal_moments) @ part.principal_axes.T,
                               part.inertia, rtol=0, atol=1e-15 * np.abs(part.inertia).max())


def test_t_handle_flips_at_the_exact_interval():
    # The handle spins about its intermediate axis and flips every 2K(m)/λ (the Euler-Poinsot
    # solution). ω₂ in principal axes changes sign once per flip; the crossings, interpolated between
    # samples 1 ms apart, fall at multiples of the interval from the first one.
    scene = tumble.load_scene(os.path.join(EXAMPLES, "t_handle.toml"))
    traj = tumble.simulate(scene, integrator="rk4", timestep=1e-3, output_interval=1e-3,
                           fields=["angular_velocity_principal"])
    w = traj.angular_velocity_principal[:, 0, :]
    exact = tumble.euler_poinsot(scene_moments(traj), w[0], [0.0])
    w2 = w[:, 1]
    i = np.nonzero(np.sign(w2[1:]) != np.sign(w2[:-1]))[0]
    crossings = traj.t[i] - w2[i] * (traj.t[i + 1] - traj.t[i]) / (w2[i + 1] - w2[i])
    assert len(crossings) >= 3
    # rk4's phase error over 20 s at h = 1e-3 and the linear interpolation (1 ms samples, curvature
    # of ω₂ at its zero is small) stay below 1e-8 s (measured: 4e-10).
    np.testing.assert_allclose(np.diff(crossings), exact.flip_interval, rtol=0, atol=1e-8)


def scene_moments(traj):
    """The principal moments of the T-handle, from its mesh (the scene's material)."""
    part = tumble.inertia(os.path.join(EXAMPLES, "meshes", "t_handle.stl"), density=2700)
    return part.principal_moments


def test_exact_integrator_is_the_euler_poinsot_solution():
    # A box whose reference axes are its principal axes, spun near its minor axis: `exact` samples the
    # same analytic solution that tumble.euler_poinsot evaluates.
    text = ('[simulation]\nduration = 3\noutput_interval = 0.25\nintegrator = "exact"\n'
            '[[bodies]]\nname = "b"\nshape = { type = "box", size = [0.3, 0.2, 0.1] }\nmass = 2\n'
            'angular_velocity = [5, 0.5, 0.2]\nangular_velocity_frame = "principal"\n')
    traj = tumble.simulate(tumble.parse_scene(text), fields=["orientation_principal", "angular_velocity_principal"])
    m = tumble.box([0.3, 0.2, 0.1], mass=2)
    motion = tumble.euler_poinsot(m.principal_moments, traj.angular_velocity_principal[0, 0], traj.t)
    np.testing.assert_allclose(traj.angular_velocity_principal[:, 0], motion.omega_body, rtol=0, atol=1e-13)
    q, p = traj.orientation_principal[:, 0], motion.quaternion
    np.testing.assert_allclose(np.abs(np.sum(q * p, axis=1)), 1.0, rtol=0, atol=1e-13)


def test_trajectory_equals_the_command_lines_csv(tmp_path):
    # The same run through the program: its CSV holds every value with 17 digits, so the arrays must
    # be equal to the last bit.
    cli = os.environ.get("TUMBLE_CLI")
    if not cli:
        pytest.skip("TUMBLE_CLI (the program) not given")
    scene_path = os.path.join(EXAMPLES, "thrown_box.toml")
    out = tmp_path / "box.csv"
    subprocess.run([cli, "run", scene_path, "-o", str(out), "--quiet"], check=True)
    traj = tumble.simulate(tumble.load_scene(scene_path))
    with open(out) as f:
        rows = list(csv.reader(f))
    header, rows = rows[0], rows[1:]
    values = np.array([[float(x) for x in r[2:]] for r in rows])
    ours = np.concatenate([traj.position[:, 0], traj.quaternion[:, 0], traj.velocity[:, 0], traj.omega_world[:, 0]],
                          axis=1)
    assert header[2:] == ["px", "py", "pz", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx", "wy", "wz"]
    assert np.array_equal(np.array([float(r[0]) for r in rows]), traj.t)
    assert np.array_equal(values, ours)


def test_box_and_mesh_arrays_have_the_closed_form():
    # A box about its centre: I_x = m (b² + c²) / 12 (tutorial §IV).
    m, (a, b, c) = 6.0, (1.0, 2.0, 3.0)
    box = tumble.box([a, b, c], mass=m)
    np.testing.assert_allclose(np.diag(box.inertia), [m * (b * b + c * c) / 12, m * (a * a + c * c) / 12,
                                                      m * (a * a + b * b) / 12], rtol=1e-15)
    # The unit cube as arrays (12 triangles, outward): volume 1, centre (½, ½, ½), I = m/6 · 1.
    V = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], float)
    F = np.array([[0, 3, 2], [0, 2, 1], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4], [1, 2, 6], [1, 6, 5],
                  [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]])
    cube = tumble.mesh_mass_properties(V, F, density=1000)
    assert cube.mass == pytest.approx(1000, rel=1e-15)
    np.testing.assert_allclose(cube.center_of_mass, 0.5, rtol=1e-15)
    np.testing.assert_allclose(cube.inertia, np.eye(3) * 1000 / 6, rtol=0, atol=1e-12)
    # Parallel-axis theorem: about a corner, I_xx = m/6 + m (½² + ½²).
    assert cube.inertia_about([0, 0, 0])[0, 0] == pytest.approx(1000 / 6 + 1000 * 0.5, rel=1e-14)
    with pytest.raises(ValueError, match="faces\\[0, 1\\] = 9 is not a vertex index"):
        tumble.mesh_mass_properties(V, [[0, 9, 1]], density=1)
    # Whole indices given as floats are indices; a fraction is a mistake, not vertex 0 (a cast truncated).
    assert tumble.mesh_mass_properties(V, F.astype(float), density=1000).mass == pytest.approx(1000, rel=1e-15)
    with pytest.raises(ValueError, match="faces\\[0, 0\\] = 0.7 is not a whole vertex index"):
        tumble.mesh_mass_properties(V, F + 0.7, density=1)
    with pytest.raises(ValueError, match="integer vertex indices"):
        tumble.mesh_mass_properties(V, F.astype(str), density=1)


def test_energy_is_conserved_and_reported():
    traj = tumble.simulate(os.path.join(EXAMPLES, "t_handle.toml"), integrator="rk4", timestep=1e-3)
    assert np.nanmax(np.abs(traj.diagnostics["energy_drift"])) < 1e-9
    assert traj.diagnostics["angular_momentum"].shape == (len(traj.t), 3)
    assert traj.units["position"] == "m" and traj.frames["angular_velocity"] == "world"


def test_errors_say_where_and_what():
    with pytest.raises(ValueError, match=r"^bad.toml:2:12: \[simulation\]: duration is -1 s"):
        tumble.parse_scene("[simulation]\nduration = -1\n", "bad.toml")
    with pytest.raises(OSError, match="no such file"):
        tumble.load_scene("does/not/exist.toml")
    with pytest.raises(ValueError, match="unknown output field 'spin'"):
        tumble.simulate(os.path.join(EXAMPLES, "t_handle.toml"), duration=0.01, fields=["spin"])
    with pytest.raises(AttributeError, match="no field 'euler_zyx'"):
        tumble.simulate(os.path.join(EXAMPLES, "t_handle.toml"), duration=0.01).euler_zyx


def random_bodies(n, seed=7):
    rng = np.random.default_rng(seed)
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1)[:, None]
    # Box-like moments: each at most the sum of the other two.
    a, b, c = rng.uniform(0.05, 0.3, size=(3, n))
    m = rng.uniform(1, 10, size=n)
    moments = np.stack([m * (b * b + c * c), m * (a * a + c * c), m * (a * a + b * b)], axis=1) / 12
    return m, moments, q, rng.normal(scale=5.0, size=(n, 3))


def test_bodies_from_arrays_follow_the_exact_solution():
    # 64 free bodies from arrays, one rk4 run; each must follow its own Euler-Poinsot solution. rk4's
    # global error at h = 1e-3 over 1 s with |ω| ~ 10 rad/s is ~ (ω h)⁴ ω t ~ 1e-11; 1e-9 leaves room.
    m, moments, q, omega = random_bodies(64)
    scene = tumble.bodies(mass=m, moments=moments, orientation=q, omega=omega, omega_frame="principal",
                          duration=1.0, timestep=1e-3, output_interval=0.5)
    traj = tumble.simulate(scene, fields=["orientation", "angular_velocity_principal"])
    assert traj.orientation.shape == (3, 64, 4) and traj.names[63] == "body_63"
    for i in range(64):
        # The body's principal axes sorted ascending may permute its reference axes; the exact solution
        # is evaluated in the principal frame from the run's own initial principal state.
        w0 = traj.angular_velocity_principal[0, i]
        exact = tumble.euler_poinsot(np.sort(moments[i]), w0, traj.t)
        np.testing.assert_allclose(traj.angular_velocity_principal[:, i], exact.omega_body, rtol=0,
                                   atol=1e-9 * np.linalg.norm(w0))
    assert np.nanmax(np.abs(traj.diagnostics["energy_drift"])) < 1e-12


def test_a_force_in_python_is_called_per_block_and_equals_the_built_in():
    # Gravity written in Python (m g through each centre of mass) gives the same trajectories, bit for
    # bit, as the built-in uniform gravity: the same products, added to the same zero loads.
    m, moments, q, omega = random_bodies(300, seed=3)
    g = np.array([0.0, -1.62, -9.81])
    calls = []

    def gravity(t, index, position, orientation, velocity, omega_w):
        calls.append(len(index))
        return m[index, None] * g, np.zeros((len(index), 3))

    free = tumble.bodies(mass=m, moments=moments, orientation=q, omega=omega, duration=0.05)
    heavy = tumble.bodies(mass=m, moments=moments, orientation=q, omega=omega, gravity=g, duration=0.05)
    ours = tumble.simulate(free, force=gravity)
    built_in = tumble.simulate(heavy)
    for name in ("position", "orientation", "velocity", "angular_velocity"):
        assert np.array_equal(getattr(ours, name), getattr(built_in, name)), name
    assert sum(calls) % 300 == 0  # every evaluation covers the 300 bodies once, block by block
    assert max(calls) > 1  # whole blocks of bodies, not one call per body

    def wrong(t, index, *state):
        return np.zeros((len(index), 2)), np.zeros((len(index), 3))

    with pytest.raises(ValueError, match=r"returned an array of shape \(\d+, 2\); force and torque must be"):
        tumble.simulate(free, force=wrong)

    def broken(t, index, *state):
        raise ZeroDivisionError("a bug in the user's force")

    with pytest.raises(ZeroDivisionError, match="a bug in the user's force"):
        tumble.simulate(free, force=broken)


def test_a_scene_built_as_a_dict_is_the_scene_file(tmp_path):
    # The same box as a dict and as TOML: the same run, bit for bit; saved and loaded back, again.
    d = {"simulation": {"duration": 0.5, "output_interval": 0.1},
         "bodies": [{"name": "a", "shape": {"type": "box", "size": [0.1, 0.2, 0.3]}, "density": 2700,
                     "angular_velocity": [0, 10, 0.01], "angular_velocity_frame": "principal"}]}
    text = ('[simulation]\nduration = 0.5\noutput_interval = 0.1\n[[bodies]]\nname = "a"\n'
            'shape = { type = "box", size = [0.1, 0.2, 0.3] }\ndensity = 2700\n'
            'angular_velocity = [0, 10, 0.01]\nangular_velocity_frame = "principal"\n')
    a = tumble.simulate(tumble.scene_from_dict(d))
    b = tumble.simulate(tumble.parse_scene(text))
    assert np.array_equal(a.orientation, b.orientation) and np.array_equal(a.omega_world, b.omega_world)
    tumble.save_scene(d, tmp_path / "box.toml")
    c = tumble.simulate(tumble.load_scene(str(tmp_path / "box.toml")))
    assert np.array_equal(a.orientation, c.orientation)
    # Written as a person would: each vector on its line, a polynomial's terms on one line too.
    saved = (tmp_path / "box.toml").read_text()
    assert "size = [0.1, 0.2, 0.3]\n" in saved and "angular_velocity = [0, 10, 0.01]\n" in saved, saved
    poly = {"simulation": {"duration": 0.1}, "bodies": [{"name": "p", "shape": {"type": "sphere", "radius": 0.5},
                                                         "density": {"polynomial": [[2500.0, 0, 0, 0], [-0.016, 2, 0, 0]]}}]}
    tumble.save_scene(poly, tmp_path / "poly.toml")
    assert "polynomial = [[2500.0, 0, 0, 0], [-0.016, 2, 0, 0]]\n" in (tmp_path / "poly.toml").read_text()
    poly["bodies"][0]["angular_velocity"] = [1.0, 2.0, 3.0]  # the moments (from the polynomial) matter
    tumble.save_scene(poly, tmp_path / "poly.toml")
    assert np.array_equal(tumble.simulate(tumble.load_scene(str(tmp_path / "poly.toml"))).omega_world,
                          tumble.simulate(tumble.scene_from_dict(poly)).omega_world)
    # The file's checks and messages, for a dict too.
    d["bodies"][0]["densty"] = 1
    with pytest.raises(ValueError, match="unknown key 'densty'; did you mean 'density'"):
        tumble.scene_from_dict(d)
    with pytest.raises(ValueError, match="made from arrays and has no TOML"):
        tumble.save_scene(tumble.bodies(mass=[1.0], moments=[[1.0, 1.0, 1.0]]), tmp_path / "x.toml")


def test_a_density_function_is_called_once_with_every_point():
    # ρ(x) = 1000 (1 + x/m) on a box a x b x c centred at the origin: the odd term leaves the mass at
    # 1000 abc and moves the centre of mass to x = ∫x ρ dV / m = a²/12 (∫x² dV = a³bc/12). The rule is
    # exact for this linear density; rounding only.
    a, b, c = 0.4, 0.2, 0.1
    calls = []

    def rho(x):
        calls.append(x.shape)
        return 1000.0 * (1.0 + x[:, 0])

    m = tumble.box([a, b, c], density=rho)
    assert len(calls) == 1 and calls[0][1] == 3 and calls[0][0] > 100
    assert m.mass == pytest.approx(1000 * a * b * c, rel=1e-14)
    np.testing.assert_allclose(m.center_of_mass, [a * a / 12, 0, 0], rtol=0, atol=1e-16)
    # The same field on the box as a mesh file's arrays agrees with the shape's rule.
    V = np.array([[x, y, z] for z in (-c / 2, c / 2) for y in (-b / 2, b / 2) for x in (-a / 2, a / 2)])
    F = np.array([[0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6], [0, 1, 5], [0, 5, 4], [1, 3, 7], [1, 7, 5],
                  [3, 2, 6], [3, 6, 7], [2, 0, 4], [2, 4, 6]])
    mesh = tumble.mesh_mass_properties(V, F, density=rho)
    assert mesh.mass == pytest.approx(m.mass, rel=1e-13)
    np.testing.assert_allclose(mesh.inertia, m.inertia, rtol=0, atol=1e-13 * np.abs(m.inertia).max())
    with pytest.raises(ValueError, match=r"returned shape \(1,\) for \d+ points"):
        tumble.box([a, b, c], density=lambda x: np.ones(1))


def test_every_primitive_is_there_with_its_closed_form():
    m, r, h = 3.0, 0.5, 2.0
    # Cone about its apex axis: I_z = 3/10 m r²; the centre of mass a quarter of the height up.
    cone = tumble.cone(r, h, mass=m)
    assert cone.center_of_mass[2] == pytest.approx(h / 4, rel=1e-14)
    assert cone.inertia[2, 2] == pytest.approx(0.3 * m * r * r, rel=1e-14)
    # Torus: I_z = m (R² + 3/4 r²).
    R, t = 1.0, 0.25
    assert tumble.torus(R, t, mass=m).inertia[2, 2] == pytest.approx(m * (R * R + 0.75 * t * t), rel=1e-14)
    # A capsule whose cylinder has (almost) no length is its two hemispheres: a sphere, I = 2/5 m r².
    cap = tumble.capsule(r, 1e-9, mass=m)
    assert cap.inertia[0, 0] == pytest.approx(0.4 * m * r * r, rel=1e-8)
