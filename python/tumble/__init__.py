"""tumble: rigid-body dynamics after Jia's *Tutorial on Rigid Body Dynamics*, from Python.

Arrays are NumPy; quaternions are (w, x, y, z), **w first**, and rotate the body's frame into the
world; units are SI. The names mirror the C++ library and the tutorial: Lambda (principal moments),
omega_b (body angular velocity), R (orientation). docs/python.md has a tour.

    import tumble
    scene = tumble.load_scene("examples/t_handle.toml")
    traj = tumble.simulate(scene, integrator="rk4", formulation="mixed", timestep=1e-3,
                           duration=20.0, output_interval=0.1)
    traj.t, traj.quaternion, traj.omega_world      # (T,), (T, N, 4) w first, (T, N, 3)
    traj.omega_principal, traj.energy_drift, traj.events
    part = tumble.inertia("part.stl", density=2700, scale=0.001)
    part.mass, part.volume, part.center_of_mass, part.inertia, part.principal_moments, part.principal_axes
"""

from __future__ import annotations

import os as _os
from typing import Callable, Sequence

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
from . import _dict_toml, _tumble
from .model import (  # noqa: F401
    Body, Damping, Drag, Event, Gravity, GravityGradient, Part, Particle, PointForce, Rotor, Shape, Spring,
    Torque, make_scene, scene_dict, spring_end,
)
from .ensemble import EnsembleResult, ensemble, read_ensemble  # noqa: F401
from .trajectory import (  # noqa: F401
    EventCrossing, Interrupted, Trajectory, field_table, from_xyzw, read_trajectory, to_xyzw,
)

__all__ = [
    "Body", "Damping", "Drag", "EnsembleResult", "Event", "EventCrossing", "ensemble", "read_ensemble", "Gravity", "GravityGradient", "Interrupted",
    "MassProperties", "MeshMassProperties", "Part", "Particle", "PointForce", "Rotor", "Scene", "Shape", "Spring",
    "Torque", "Trajectory", "bodies", "box", "capsule", "cone", "cylinder", "ellipsoid", "euler_poinsot",
    "field_table", "fit", "from_xyzw", "inertia", "load_scene", "make_scene", "mesh_mass_properties", "model_check",
    "output_fields", "parse_scene", "read_trajectory", "save_scene", "scene_dict", "scene_from_dict",
    "simulate", "sphere", "spring_end", "to_xyzw", "torus",
]


def simulate(scene: Scene | str | _os.PathLike, integrator: str | None = None, formulation: str | None = None,
             timestep: float | None = None, duration: float | None = None, output_interval: float | None = None,
             rtol: float | None = None, atol: float | None = None, threads: int | None = None,
             fields: Sequence[str] | None = None, force: Callable | None = None,
             events: Sequence[Event | dict] | None = None, drift_threshold: float | None = None,
             t_eval: Sequence[float] | None = None, initial: Trajectory | dict | None = None,
             sensitivities: bool = False, sensitivity_parameters: str = "inertia",
             controller: Callable | None = None, control_interval: float | None = None) -> Trajectory:
    """Run a scene and return its Trajectory. Arguments left None take the scene's [simulation]
    values (as `tumble run` options do): integrator (e.g. "rk4", "splitting", "dopri45", "exact"),
    formulation ("world", "mixed", "body"), timestep and duration and output_interval (s; 0 = every
    step), rtol/atol for adaptive integrators, threads, drift_threshold (the relative drift of a
    conserved quantity past which the run's diagnostics warn; 0 = never), and fields (a list of output field names;
    default the scene's [output] fields, else position, orientation, velocity, angular_velocity and
    omega in the reference and principal axes).

    force: a force law in Python, added to the scene's forces, called once per block of bodies (not
    once per body) as force(t, index, position, orientation, velocity, omega) with the bodies' indices
    (n,) and world arrays (n, 3) and (n, 4) (centre of mass, w-first quaternion of the principal
    frame, centre-of-mass velocity, angular velocity); it returns (force, torque), two (n, 3) arrays
    in N and N m, world axes, the torque about the centre of mass. Such a run uses one thread and
    judges no drift (what the force conserves is unknown).

    events: Event objects (or dicts with the keys of [[events]]) watched besides the scene's own; their
    crossings are Trajectory.events. Ctrl-C stops the run and raises tumble.Interrupted (a
    KeyboardInterrupt) whose .trajectory holds the samples computed so far.

    t_eval: the times to sample at (s, ascending, from the start on), instead of every output_interval;
    the run ends at the last (duration, if given, must agree). Fixed steps land on each of them (the
    step before a sample is shortened), adaptive ones sample their dense output there.

    initial: where to start instead of the scene's initial state: a Trajectory (its last sample, e.g.
    to continue a run) or a dict with t (s) and, one row per body then particle, position (N, 3),
    orientation (N, 4, w first), velocity (N, 3) and angular_velocity (N, 3, world) as a Trajectory
    holds them. The run then starts at that t; its drifts are measured from there.

    sensitivities: also differentiate the run (docs/sensitivities.md): the Trajectory then holds ``stm``,
    (T, 12 B, 12 B) = d x(t_k) / d x(0), and ``parameter_sensitivity``, (T, 12 B, 3 B) = d x(t_k) / d(I1,
    I2, I3) of each body, or (T, 12 B, B) with respect to the masses with sensitivity_parameters="mass",
    or (T, 12 B, P) with respect to the force models' P parameters with "forces" (``parameter_names``).
    Forward-mode derivatives of the integrator's own steps (every integrator; dopri45's accepted steps,
    their lengths held fixed); no events are watched and no Python force is differentiated.

    controller: the motor torques of the scene's [[rotors]] from the state, as flight software sets them:
    controller(t, position, orientation, velocity, omega, speeds) with the bodies' arrays as a force
    gets them and the rotors' speeds relative to their bodies (R,) in rad/s, returning the R motor
    torques (N m), both in the scene's [[rotors]] order (Trajectory.rotor_names). It is called every
    control_interval seconds from the start (default: every step) and its torques are held until the
    next call (a zero-order hold; a rotor's max_torque clips them, its max_speed stops its motor); the
    steps end at its calls, so each integrator keeps its order. The speeds are carried from call to call:
    diagnostics["rotor_speed"] and ["rotor_torque"] hold them at every sample. Such a run uses one
    thread; sensitivities are refused (the controller's derivatives are unknown)."""
    if isinstance(scene, (str, bytes)) or hasattr(scene, "__fspath__"):
        scene = load_scene(scene)
    specs, python_events, every = [], [], []
    watched = {name: "the scene's [[events]]" for name in scene.events}
    for k, e in enumerate(events or ()):
        if isinstance(e, dict):
            e = Event(**e)
        if not isinstance(e, Event):
            raise TypeError(f"events must be tumble.Event objects or dicts; got {type(e).__name__}")
        # Two events of one name would count each crossing twice under that name.
        if e.name in watched:
            raise ValueError(f"events[{k}]: an event named '{e.name}' is already watched ({watched[e.name]}): "
                             f"its crossings would be counted twice; give this one another name, or leave it "
                             f"out to keep the scene's")
        watched[e.name] = f"events[{k}]"
        if e.g is not None:
            if not callable(e.g):
                raise TypeError(f"event '{e.name}': g must be a function g(t, position, orientation, velocity, omega)")
            direction = {"both": 0, None: 0, "rising": 1, "falling": -1}.get(e.direction)
            if direction is None:
                raise ValueError(f"event '{e.name}': direction {e.direction!r}: choose 'both', 'rising' or 'falling'")
            python_events.append((e.name, e.g, direction, bool(e.stop)))
        else:
            table = e.to_dict()
            every.append(table.get("body") == "*")
            if every[-1]:
                table["body"] = (scene.bodies or ["*"])[0]  # checked as an event on the first body
            specs.append(table)
    if specs:
        specs = _event_specs(scene, specs)
    if isinstance(fields, (str, bytes)):  # list("position") would be its letters
        raise ValueError(f"fields={fields!r} must be a list of field names, e.g. fields=[{fields!r}]")
    if controller is not None and not callable(controller):
        raise TypeError(f"controller must be a function controller(t, position, orientation, velocity, omega, "
                        f"speeds) returning the rotors' torques; got {type(controller).__name__}")
    if controller is None and control_interval is not None:
        raise ValueError("control_interval is the time between a controller's calls: give controller too")
    if force is not None and not callable(force):
        raise TypeError(f"force must be a function force(t, index, position, orientation, velocity, omega); "
                        f"got {type(force).__name__}")
    if fields is None and not scene.output_fields:
        fields = ["position", "orientation", "velocity", "angular_velocity", "angular_velocity_reference",
                  "angular_velocity_principal"]
    # The settings by their keys (sim/run_settings.hpp, as `tumble run --KEY` and [simulation] name them).
    start = None if initial is None else _initial_state(scene, initial)
    t0 = 0.0 if start is None else start[0]
    sample_times, drop_start = [], False
    if t_eval is not None:
        sample_times, duration, drop_start = _sample_times(t_eval, t0, duration, output_interval)
    settings = dict(integrator=integrator, formulation=formulation, timestep=timestep, duration=duration,
                    output_interval=output_interval, rtol=rtol, atol=atol, threads=threads,
                    drift_threshold=drift_threshold)
    raw = _tumble._simulate(scene, settings, None if fields is None else list(fields), force, specs,
                            python_events, every, sample_times, start,
                            sensitivity_parameters if sensitivities else None,
                            None if controller is None else (controller, control_interval))
    trajectory = Trajectory._from_run(raw)
    if drop_start:
        trajectory = trajectory._from(1)
    if not trajectory.complete:
        raise Interrupted(trajectory)
    return trajectory


def _sample_times(t_eval, t0, duration, output_interval):
    """t_eval as the run's sample times after the start, its duration, and whether the start (sampled
    by every run) is to be dropped because t_eval does not hold it."""
    if output_interval is not None:
        raise ValueError("give t_eval or output_interval, not both: t_eval says where every sample is")
    times = _np.asarray(t_eval, dtype=float)
    if times.ndim != 1 or times.size == 0:
        raise ValueError(f"t_eval must be a non-empty list of times; got an array of shape {times.shape}")
    bad = _np.flatnonzero(~_np.isfinite(times) | (_np.diff(times, prepend=-_np.inf) <= 0))
    if bad.size:
        k = int(bad[0])
        raise ValueError(f"t_eval[{k}] = {times[k]!r}: give finite times in increasing order")
    if times[0] < t0:
        raise ValueError(f"t_eval[0] = {times[0]!r} s is before the start of the run ({t0!r} s)")
    end = float(times[-1]) - t0
    if duration is not None and abs(duration - end) > 4e-16 * max(abs(times[-1]), abs(t0), 1.0):
        raise ValueError(f"duration={duration!r} but t_eval ends {end!r} s after the start: the run ends at "
                         f"the last of t_eval; leave duration out")
    drop_start = times[0] != t0
    return [float(x) for x in times[0 if drop_start else 1:]], end, drop_start


def _initial_state(scene, initial):
    """(t, position, orientation, velocity, angular_velocity) from a Trajectory's last sample or a dict,
    one row per body then particle."""
    rows = list(scene.bodies) + list(scene.particles)
    keys = ("position", "orientation", "velocity", "angular_velocity")
    if isinstance(initial, Trajectory):
        if len(initial.t) == 0:
            raise ValueError("initial: the trajectory has no samples to start from")
        missing = [k for k in keys if k not in initial.fields]
        if missing:
            raise ValueError(f"initial: the trajectory holds no {', '.join(missing)}: run it with these fields "
                             f"(the defaults hold them) to continue from it")
        if list(initial.names) != rows:
            raise ValueError(f"initial: the trajectory's bodies and particles {list(initial.names)} are not the "
                             f"scene's {rows}")
        return (float(initial.t[-1]),) + tuple(_np.ascontiguousarray(initial.fields[k][-1]) for k in keys)
    if not isinstance(initial, dict):
        raise TypeError(f"initial must be a Trajectory or a dict; got {type(initial).__name__}")
    from .trajectory import ALIASES
    given = {ALIASES.get(k, k): v for k, v in initial.items()}
    unknown = sorted(set(given) - set(keys) - {"t"})
    if unknown:
        raise ValueError(f"initial: unknown key(s) {unknown}; give t, {', '.join(keys)}")
    if "t" not in given:
        raise ValueError("initial: give t, the time the state is at (s)")
    arrays = []
    for k, width in zip(keys, (3, 4, 3, 3)):
        if k not in given:
            raise ValueError(f"initial: give {k}, one row of {width} per body then particle ({len(rows)} rows)")
        a = _np.atleast_2d(_np.asarray(given[k], dtype=float))
        if a.shape != (len(rows), width):
            raise ValueError(f"initial: {k} has shape {a.shape}; the scene needs ({len(rows)}, {width}): one row "
                             f"per body then particle ({', '.join(rows)})")
        arrays.append(_np.ascontiguousarray(a))
    return (float(given["t"]),) + tuple(arrays)


def _event_specs(scene, tables):
    """The events given as tables, checked by the scene-file reader against the scene; a mistake names
    the event as events[i] (the TOML made here has no lines worth citing)."""
    import re
    import tomli_w
    specs = []
    for i, table in enumerate(tables):
        where = f"events[{i}]"
        try:
            specs += _tumble._parse_events(scene, tomli_w.dumps({"events": [table]}), where)
        except ValueError as e:
            raise ValueError(re.sub(r"^(events\[\d+\]):\d+:\d+:", r"\1:", str(e))) from None
    return specs


def bodies(mass, moments, position=None, orientation=None, velocity=None, omega=None, omega_frame: str = "world",
           gravity=None, duration: float = 1.0, timestep: float = 1e-3, output_interval: float = 0.01,
           integrator: str = "rk4") -> Scene:
    """A scene of N rigid bodies from arrays, for the batched engine: mass (N,) kg; moments (N, 3)
    principal moments (kg m^2) about each body's reference axes, which are its principal axes at its
    centre of mass; position (N, 3) m, orientation (N, 4) w first, velocity (N, 3) m/s, omega (N, 3)
    rad/s in omega_frame ("world", "reference" or "principal"); optional uniform gravity (3,) m/s^2.
    Bodies are named body_0 ... body_N-1. Returns a Scene for simulate()."""
    m = _np.ascontiguousarray(mass, dtype=_np.float64)
    if m.ndim != 1:
        raise ValueError(f"mass must be (N,), one per body, in kg; got shape {m.shape}")
    n = m.shape[0]

    def rows(name, a, width, what):
        if a is None:
            return None
        a = _np.asarray(a, dtype=_np.float64)
        if a.shape == (width,):
            a = _np.broadcast_to(a, (n, width))  # one row for every body
        if a.shape != (n, width):
            raise ValueError(f"{name} must be (N, {width}) = ({n}, {width}), {what}, or ({width},) for every "
                             f"body; got shape {a.shape}")
        return _np.ascontiguousarray(a)
    return _tumble._scene_from_arrays(
        m, rows("moments", moments, 3, "principal moments in kg m^2"),
        rows("position", position, 3, "m, world"), rows("orientation", orientation, 4, "quaternions w, x, y, z"),
        rows("velocity", velocity, 3, "m/s, world"), rows("omega", omega, 3, f"rad/s, {omega_frame} axes"),
        omega_frame, None if gravity is None else _np.asarray(gravity, dtype=_np.float64),
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


def inertia(path: str | _os.PathLike, density: float | Callable | None = None, mass: float | None = None,
            scale: float = 1.0, part: int = 0, thickness: float | None = None) -> _MeshMass:
    """Mass properties of a closed triangle mesh file (OBJ, OFF, PLY, STL, ...): give density
    (kg/m^3) or mass (kg) (default unit density); scale multiplies coordinates (0.001 for a file in
    millimetres); part picks one part of a multi-part file (1-based; 0 = all, merged); thickness (m)
    makes it a thin shell. The result has mass, volume, center_of_mass, inertia (about the centre of
    mass, the file's axes), principal_moments, principal_axes, surface_area and warnings. density may
    be a function of points: called once with every quadrature point, an (n, 3) array in the file's
    frame (m, after scaling), it returns the densities (n,) in kg/m^3."""
    return _MeshMass(_tumble._mesh_file(path, density, mass, float(scale), int(part), thickness))


def mesh_mass_properties(vertices, faces, density: float | Callable | None = None, mass: float | None = None,
                         thickness: float | None = None) -> _MeshMass:
    """Mass properties of a closed mesh given as arrays: vertices (V, 3) in m and faces (F, 3) of
    vertex indices from 0, counter-clockwise seen from outside."""
    V = _np.ascontiguousarray(vertices, dtype=_np.float64)
    faces = _np.asarray(faces)
    # Indices given as floats must be whole: a cast would truncate 0.7 to vertex 0 without a word.
    if faces.dtype.kind == "f":
        bad = ~_np.isfinite(faces) | (faces != _np.floor(faces))
        if bad.any():
            where = tuple(int(k) for k in _np.argwhere(bad)[0])
            raise ValueError(f"faces{list(where)} = {faces[where]!r} is not a whole vertex index: faces hold "
                             "indices into vertices, from 0")
    elif faces.dtype.kind not in "iu":
        raise ValueError(f"faces must hold integer vertex indices; got an array of {faces.dtype}")
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


def euler_poinsot(moments, omega_b0, t, q0=(1.0, 0.0, 0.0, 0.0)) -> FreeMotion:
    """The exact Euler-Poinsot solution (Jacobi elliptic functions and the angle about L) for
    principal moments Lambda (kg m^2), initial body angular velocity omega_b0 (rad/s, principal
    axes) and orientation q0 (w first), evaluated at the times t (s, any array)."""
    times = _np.ascontiguousarray(_np.atleast_1d(t), dtype=_np.float64).ravel()
    raw = _tumble._euler_poinsot(_np.asarray(moments, dtype=float), _np.asarray(omega_b0, dtype=float),
                                 _np.asarray(q0, dtype=float), times)
    return FreeMotion(times, raw)


def scene_from_dict(scene: dict, path: str | _os.PathLike = "scene.toml") -> Scene:
    """A scene built in Python: a dict with the keys of a scene file (docs/scene-format.md), e.g.
    {"simulation": {"duration": 10.0}, "bodies": [{"name": "a", "shape": {"type": "box", "size":
    [0.1, 0.2, 0.3]}, "density": 2700}]}. It is written as TOML (tomli_w) and read by the same
    reader as a file, so every check is the file's; a mistake is named by its place in the dict
    ("scene dict at bodies[0].shape.size[2]"). `path` anchors mesh paths."""
    return _parse_dict(scene, path)


def _parse_dict(scene: dict, path: str | _os.PathLike) -> Scene:
    text = _dict_toml.dumps(scene)
    try:
        return parse_scene(text, str(path))
    except ValueError as e:
        raise ValueError(_dict_toml.located(str(e), text, str(path))) from None


def model_check(path: str | _os.PathLike, package_path: Sequence[str | _os.PathLike] = (),
                geometry: str = "collision", density: float | None = None, lump_fixed: bool = False) -> dict:
    """The audit of a robot description (URDF, MJCF or SDF) that `tumble model check --json` prints, as a
    dict: {"model", "format", "path", "links": [{"name", "line", "authored": {mass, com, inertia, ...} or
    None, "computed": {volume, mass, com, inertia, geometry, mass_from} or None, "findings": [{"code",
    "severity", "message"}]}], "notes", "errors", "warnings"}. package_path: directories where package://
    and model:// meshes are; geometry: "collision" or "visual" (URDF, SDF); density (kg/m^3): every link's
    mass from it; lump_fixed: also the bodies fixed joints weld together. docs/robot-models.md lists the
    finding codes and their thresholds."""
    import json
    if isinstance(package_path, (str, bytes)) or hasattr(package_path, "__fspath__"):
        package_path = [package_path]
    return json.loads(_tumble._model_check(_os.fspath(path), [_os.fspath(p) for p in package_path], geometry,
                                           density, bool(lump_fixed)))


def fit(telemetry, sigma: float, bias: bool = False, substep: float | None = None, max_iterations: int = 100,
        torque=None, wheel_momentum=None) -> dict:
    """A rigid body's inertia identified from its gyro telemetry, as the dict of the JSON `tumble fit`
    prints (docs/fit.md): {"verdict": "determined" or "not determined", "reason", "samples", "t0",
    "duration", "sigma", "scale": "trace" (J / trace J: no known torque) or "absolute" (kg m^2),
    "unit", "inertia": {"J", "J_sigma", "principal_moments", "principal_moments_sigma", "principal_axes"
    (one row per axis), "principal_axes_sigma_rad", "ratios", "ratios_sigma", "positive_definite",
    "triangle_inequality"}, "omega0", "omega0_sigma", "bias", "bias_sigma", "residuals", "covariance",
    "solver", "notes"}; quantities the data do not determine are None.

    telemetry: a CSV file (columns t, wx, wy, wz, optionally tau_x, tau_y, tau_z and h_x, h_y, h_z), or
    arrays: a pair (t, omega) with t of shape (n,) in s and omega (n, 3) in rad/s, sensor axes, or a dict
    with keys "t", "omega" and optionally "torque" and "wheel_momentum"; torque (N m) and wheel_momentum
    (N m s), (n, 3) in sensor axes, may also be given as keywords. sigma: the gyro's noise per component
    (rad/s). bias: also estimate a constant gyro bias. substep: the longest RK4 step (s; default chosen
    from sigma). max_iterations: of Levenberg-Marquardt, per start."""
    import json
    if isinstance(telemetry, (str, bytes)) or hasattr(telemetry, "__fspath__"):
        if torque is not None or wheel_momentum is not None:
            raise ValueError("torque and wheel_momentum go with arrays; a telemetry file has them as columns "
                             "tau_x, tau_y, tau_z and h_x, h_y, h_z")
        return json.loads(_tumble._fit_file(_os.fspath(telemetry), float(sigma), bool(bias), substep,
                                            int(max_iterations)))
    if isinstance(telemetry, dict):
        unknown = set(telemetry) - {"t", "omega", "torque", "wheel_momentum"}
        if unknown or "t" not in telemetry or "omega" not in telemetry:
            raise ValueError(f"telemetry has keys {sorted(telemetry)}: give 't' and 'omega', and optionally "
                             "'torque' and 'wheel_momentum'")
        t, omega = telemetry["t"], telemetry["omega"]
        torque = telemetry.get("torque", torque)
        wheel_momentum = telemetry.get("wheel_momentum", wheel_momentum)
    else:
        try:
            t, omega = telemetry
        except (TypeError, ValueError):
            raise ValueError("telemetry: give a CSV file's path, a pair (t, omega) of arrays, or a dict with 't' "
                             "and 'omega'") from None

    def array(a):
        return None if a is None else _np.asarray(a, dtype=float)
    return json.loads(_tumble._fit_arrays(array(t), array(omega), array(torque), array(wheel_momentum), float(sigma),
                                          bool(bias), substep, int(max_iterations)))


def save_scene(scene: Scene | dict, path: str | _os.PathLike) -> None:
    """Write a scene as TOML to `path`: a Scene read from a file or text (its TOML, as given), or a
    dict as scene_from_dict takes (validated first). Scenes made by bodies() from arrays have no TOML:
    give their bodies as a [[body_tables]] CSV file instead."""
    if isinstance(scene, dict):
        text = _parse_dict(scene, path).text  # refuse what could not be loaded back
    else:
        text = scene.text
        if not text:
            raise ValueError("this scene was made from arrays and has no TOML: write its bodies as a "
                             "[[body_tables]] CSV file (docs/scene-format.md) and a scene that names it")
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
