"""tumble: rigid-body dynamics after Jia's *Tutorial on Rigid Body Dynamics*, from Python.

Arrays are NumPy; quaternions are (w, x, y, z), **w first**, and rotate the body's frame into the
world; units are SI. The names mirror the C++ library and the tutorial: Lambda (principal moments),
omega_b (body angular velocity), R (orientation). docs/python.md has a tour.

    import tumble
    scene = tumble.load_scene("examples/t_handle.toml")
    traj = tumble.simulate(scene, integrator="rk4", formulation="mixed", timestep=1e-3,
                           duration=20.0, output_interval=0.1)
    traj.t, traj.quaternion, traj.omega_world      # (T,), (T, N, 4) w first, (T, N, 3)
    part = tumble.inertia("part.stl", density=2700, scale=0.001)
    part.mass, part.volume, part.center_of_mass, part.inertia, part.principal_moments, part.principal_axes
"""

import numpy as _np

from ._tumble import (  # noqa: F401  (re-exported)
    MassProperties,
    MeshMassProperties,
    Scene,
    box,
    capsule,
    cone,
    cylinder,
    ellipsoid,
    load_scene,
    output_fields,
    parse_scene,
    sphere,
    torus,
)
from . import _tumble

__all__ = [
    "MassProperties", "MeshMassProperties", "Scene", "Trajectory", "bodies", "box", "capsule", "cone", "cylinder", "ellipsoid",
    "euler_poinsot", "inertia", "load_scene", "mesh_mass_properties", "output_fields", "parse_scene",
    "save_scene", "scene_from_dict", "simulate", "sphere", "torus",
]


class Trajectory:
    """The samples of a run: ``t`` (T,) in s and one array (T, N, width) per output field, N the
    bodies then the particles in file order (``names``). Fields are attributes by their names
    (``position``, ``orientation``, ``velocity``, ``angular_velocity``, and any others asked for);
    ``units`` and ``frames`` say what each holds. Aliases: ``quaternion`` = ``orientation`` (w first,
    reference frame -> world), ``omega_world`` = ``angular_velocity`` (rad/s, world).
    ``diagnostics`` maps each system quantity (kinetic_energy, angular_momentum, their drifts, ...)
    to an array (T,) or (T, 3), NaN where undefined."""

    _aliases = {"quaternion": "orientation", "omega_world": "angular_velocity"}

    def __init__(self, raw):
        self.t = raw["t"]
        self.names = list(raw["names"])
        self.fields = dict(raw["fields"])
        self.units = dict(raw["units"])
        self.frames = dict(raw["frames"])
        self.diagnostics = dict(raw["diagnostics"])
        self.integrator = raw["integrator"]
        self.formulation = raw["formulation"]
        self.timestep = raw["timestep"]
        self.warning = raw.get("warning")

    def __getattr__(self, name):
        fields = self.__dict__.get("fields", {})
        key = self._aliases.get(name, name)
        if key in fields:
            return fields[key]
        raise AttributeError(
            f"the trajectory has no field '{name}': it holds {', '.join(fields)} "
            f"(ask simulate(..., fields=[...]) for others: {', '.join(output_fields())})")

    def body(self, name):
        """The index of a body or particle by name."""
        return self.names.index(name)

    def __repr__(self):
        return (f"Trajectory({len(self.t)} samples of {len(self.names)} bodies/particles, "
                f"fields {list(self.fields)})")


def simulate(scene, integrator=None, formulation=None, timestep=None, duration=None,
             output_interval=None, rtol=None, atol=None, threads=None, fields=None, force=None):
    """Run a scene and return its Trajectory. Arguments left None take the scene's [simulation]
    values (as `tumble run` options do): integrator (e.g. "rk4", "splitting", "dopri45", "exact"),
    formulation ("world", "mixed", "body"), timestep and duration and output_interval (s; 0 = every
    step), rtol/atol for adaptive integrators, threads, and fields (a list of output field names,
    default the scene's [output] fields or position, orientation, velocity, angular_velocity).

    force: a force law in Python, added to the scene's forces, called once per block of bodies (not
    once per body) as force(t, index, position, orientation, velocity, omega) with the bodies' indices
    (n,) and world arrays (n, 3) and (n, 4) (centre of mass, w-first quaternion of the principal
    frame, centre-of-mass velocity, angular velocity); it returns (force, torque), two (n, 3) arrays
    in N and N m, world axes, the torque about the centre of mass. Such a run uses one thread and
    judges no drift (what the force conserves is unknown)."""
    if isinstance(scene, (str, bytes)) or hasattr(scene, "__fspath__"):
        scene = load_scene(scene)
    return Trajectory(_tumble._simulate(scene, integrator, formulation, timestep, duration,
                                        output_interval, rtol, atol, threads,
                                        None if fields is None else list(fields), force))


def bodies(mass, moments, position=None, orientation=None, velocity=None, omega=None, omega_frame="world",
           gravity=None, duration=1.0, timestep=1e-3, output_interval=0.01, integrator="rk4"):
    """A scene of N rigid bodies from arrays, for the batched engine: mass (N,) kg; moments (N, 3)
    principal moments (kg m^2) about each body's reference axes, which are its principal axes at its
    centre of mass; position (N, 3) m, orientation (N, 4) w first, velocity (N, 3) m/s, omega (N, 3)
    rad/s in omega_frame ("world", "reference" or "principal"); optional uniform gravity (3,) m/s^2.
    Bodies are named body_0 ... body_N-1. Returns a Scene for simulate()."""
    def rows(a, width):
        return None if a is None else _np.ascontiguousarray(_np.reshape(a, (-1, width)), dtype=_np.float64)
    return _tumble._scene_from_arrays(
        _np.ascontiguousarray(_np.ravel(mass), dtype=_np.float64), rows(moments, 3), rows(position, 3),
        rows(orientation, 4), rows(velocity, 3), rows(omega, 3), omega_frame,
        None if gravity is None else _np.asarray(gravity, dtype=_np.float64),
        float(duration), float(timestep), float(output_interval), integrator)


class _MeshMass:
    """Mass properties of a mesh with its surface area and the warnings of reading it."""

    def __init__(self, result):
        self._result = result
        self.properties = result.properties
        self.surface_area = result.surface_area
        self.warnings = list(result.warnings)

    def __getattr__(self, name):
        return getattr(self.__dict__["properties"], name)

    def __repr__(self):
        return repr(self.properties)


def inertia(path, density=None, mass=None, scale=1.0, part=0, thickness=None):
    """Mass properties of a closed triangle mesh file (OBJ, OFF, PLY, STL, ...): give density
    (kg/m^3) or mass (kg) (default unit density); scale multiplies coordinates (0.001 for a file in
    millimetres); part picks one part of a multi-part file (1-based; 0 = all, merged); thickness (m)
    makes it a thin shell. The result has mass, volume, center_of_mass, inertia (about the centre of
    mass, the file's axes), principal_moments, principal_axes, surface_area and warnings. density may
    be a function of points: called once with every quadrature point, an (n, 3) array in the file's
    frame (m, after scaling), it returns the densities (n,) in kg/m^3."""
    return _MeshMass(_tumble._mesh_file(path, density, mass, float(scale), int(part), thickness))


def mesh_mass_properties(vertices, faces, density=None, mass=None, thickness=None):
    """Mass properties of a closed mesh given as arrays: vertices (V, 3) in m and faces (F, 3) of
    vertex indices from 0, counter-clockwise seen from outside."""
    V = _np.ascontiguousarray(vertices, dtype=_np.float64)
    F = _np.ascontiguousarray(faces, dtype=_np.int64)
    if V.ndim != 2 or V.shape[1] != 3 or F.ndim != 2 or F.shape[1] != 3:
        raise ValueError(f"vertices must be (V, 3) and faces (F, 3); got {V.shape} and {F.shape}")
    return _MeshMass(_tumble._mesh_arrays(V, F, density, mass, thickness))


class FreeMotion:
    """The analytic torque-free motion at the times asked for: quaternion (T, 4) w first (body ->
    world), omega_body (T, 3), omega_world (T, 3); regime, flip_interval (s between sign changes of
    the intermediate-axis component), period_omega, energy (J), angular_momentum (world, constant)."""

    def __init__(self, t, raw):
        self.t = t
        for key, value in raw.items():
            setattr(self, key, value)


def euler_poinsot(moments, omega_b0, t, q0=(1.0, 0.0, 0.0, 0.0)):
    """The exact Euler-Poinsot solution (Jacobi elliptic functions and the angle about L) for
    principal moments Lambda (kg m^2), initial body angular velocity omega_b0 (rad/s, principal
    axes) and orientation q0 (w first), evaluated at the times t (s, any array)."""
    times = _np.ascontiguousarray(_np.atleast_1d(t), dtype=_np.float64).ravel()
    raw = _tumble._euler_poinsot(_np.asarray(moments, dtype=float), _np.asarray(omega_b0, dtype=float),
                                 _np.asarray(q0, dtype=float), times)
    return FreeMotion(times, raw)


def scene_from_dict(scene, path="scene.toml"):
    """A scene built in Python: a dict with the keys of a scene file (docs/scene-format.md), e.g.
    {"simulation": {"duration": 10.0}, "bodies": [{"name": "a", "shape": {"type": "box", "size":
    [0.1, 0.2, 0.3]}, "density": 2700}]}. It is written as TOML (tomli_w) and read by the same
    reader as a file, so every check and message is the file's; `path` anchors mesh paths."""
    import tomli_w
    return parse_scene(tomli_w.dumps(scene), str(path))


def save_scene(scene, path):
    """Write a scene as TOML to `path`: a Scene read from a file or text (its TOML, as given), or a
    dict as scene_from_dict takes (validated first). Scenes made by bodies() from arrays have no TOML:
    give their bodies as a [[body_tables]] CSV file instead."""
    if isinstance(scene, dict):
        import tomli_w
        text = tomli_w.dumps(scene)
        parse_scene(text, str(path))  # refuse what could not be loaded back
    else:
        text = scene.text
        if not text:
            raise ValueError("this scene was made from arrays and has no TOML: write its bodies as a "
                             "[[body_tables]] CSV file (docs/scene-format.md) and a scene that names it")
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
