"""Scenes built in Python: bodies, particles, every force model and events as classes whose fields are
the keys of a scene file (docs/scene-format.md, the same names, units and frames). `make_scene` turns
them into a Scene through the scene-file reader itself, so every check and message is the file's, and
`scene_dict` gives the dict that `save_scene` writes as TOML.

    import tumble
    from tumble import Body, Shape, Gravity, Damping, Event
    scene = tumble.make_scene(
        bodies=[Body("racket", shape=Shape("box", size=[0.02, 0.2, 0.3]), density=700,
                     angular_velocity=[0.01, 10, 0], angular_velocity_frame="principal")],
        forces=[Gravity([0, 0, -9.81]), Damping("racket", angular=1e-5)],
        events=[Event("flip", body="racket", column="w2")],
        duration=5.0, timestep=1e-3)
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Any, Callable, Sequence

Vector = Sequence[float]


def _table(obj, skip=()):
    """The scene-file table of a dataclass: its fields without those left None, vectors as lists."""
    out = {}
    for f in dataclasses.fields(obj):
        if f.name in skip:
            continue
        value = getattr(obj, f.name)
        if value is None:
            continue
        if hasattr(value, "to_dict"):
            value = value.to_dict()
        elif hasattr(value, "tolist"):
            value = value.tolist()
        elif isinstance(value, (list, tuple)):
            value = [v.to_dict() if hasattr(v, "to_dict") else (v.tolist() if hasattr(v, "tolist") else v)
                     for v in value]
        out[f.name] = value
    return out


class Shape(dict):
    """A primitive, centred at the body's reference origin, symmetry axis z (m):
    Shape("box", size=[x, y, z]), Shape("sphere", radius=r), Shape("ellipsoid", semi_axes=[a, b, c]),
    Shape("cylinder", radius=r, length=l), Shape("capsule", radius=r, length=l) (cylindrical part),
    Shape("cone", radius=r, height=h) (base at the origin, apex at +z),
    Shape("torus", major_radius=R, minor_radius=r)."""

    def __init__(self, type: str, **keys: Any):
        super().__init__(type=type, **{k: (v.tolist() if hasattr(v, "tolist") else v) for k, v in keys.items()})

    def to_dict(self):
        return dict(self)


@dataclass
class Part:
    """A part of a composite body, placed in the body's reference frame: a shape, a mesh file (+ scale,
    thickness) or mass + inertia (+ center_of_mass); density or mass its own material (default the
    body's); hole=True removes it."""
    shape: Shape | dict | None = None
    mesh: str | None = None
    scale: float | None = None
    thickness: float | None = None
    mass: float | None = None
    inertia: Any = None
    center_of_mass: Vector | None = None
    density: Any = None
    position: Vector | None = None
    orientation: Any = None
    hole: bool | None = None

    def to_dict(self):
        return _table(self)


@dataclass
class Body:
    """A rigid body ([[bodies]]). Mass from one of: shape (+ density or mass, + thickness for a shell),
    mesh (a file path, relative to the scene's `path`; + scale), mass + inertia (about the centre of
    mass in reference axes: [Ixx, Iyy, Izz] or 3x3; + center_of_mass), or parts. Initial state of its
    reference frame: position (m, world), orientation (w, x, y, z, or {"euler_zyx": [...]}, ...),
    velocity (m/s, world, of the origin or with velocity_of="com" of the centre of mass),
    angular_velocity (rad/s) in angular_velocity_frame ("world", "reference", "principal" or "lvlh").
    Under a GravityGradient: orbit={"a": ..., "e": ..., "i": ..., "raan": ..., "argp": ..., "nu": ...}
    (m, rad) places it on that orbit, and orientation_frame="lvlh" takes the orientation relative to its
    orbit frame."""
    name: str
    shape: Shape | dict | None = None
    mesh: str | None = None
    scale: float | None = None
    thickness: float | None = None
    density: Any = None
    mass: float | None = None
    inertia: Any = None
    center_of_mass: Vector | None = None
    parts: list[Part] | None = None
    position: Vector | None = None
    orientation: Any = None
    velocity: Vector | None = None
    velocity_of: str | None = None
    angular_velocity: Vector | None = None
    angular_velocity_frame: str | None = None
    orbit: dict | None = None
    orientation_frame: str | None = None

    def to_dict(self):
        return _table(self)


@dataclass
class Particle:
    """A point mass ([[particles]]): mass (kg), position (m) and velocity (m/s), world."""
    name: str
    mass: float
    position: Vector | None = None
    velocity: Vector | None = None

    def to_dict(self):
        return _table(self)


@dataclass
class Gravity:
    """Uniform gravity g (m/s^2, world) on every body and particle ([world] gravity); potential -m g.x."""
    g: Vector

    def to_dict(self):
        return None  # not a [[forces]] table: make_scene puts it in [world]


@dataclass
class PointForce:
    """A constant force (N) on a body, in `frame` axes ("world", "reference", "principal"), applied at
    `point` (m; default the centre of mass) given in `point_frame` ("reference": body-fixed, "principal",
    or "world": a fixed world point); torque (x - o) x f."""
    body: str
    force: Vector
    frame: str | None = None
    point: Vector | None = None
    point_frame: str | None = None

    def to_dict(self):
        return {"type": "force", **_table(self)}


@dataclass
class Torque:
    """A pure couple (N m) on a body, in `frame` axes ("world", "reference" or "principal")."""
    body: str
    torque: Vector
    frame: str | None = None

    def to_dict(self):
        return {"type": "torque", **_table(self)}


@dataclass
class Damping:
    """Viscous damping f = -c_v v (linear, N s/m), tau = -c_w w (angular, N m s) on one body (or every
    body and particle when body is None)."""
    body: str | None = None
    linear: float | None = None
    angular: float | None = None

    def to_dict(self):
        return {"type": "damping", **_table(self)}


@dataclass
class Drag:
    """Quadratic drag f = -k_v |v| v (linear, kg/m; k_v = rho C_d A / 2), tau = -k_w |w| w (angular,
    kg m^2) on one body (or all when body is None)."""
    body: str | None = None
    linear: float | None = None
    angular: float | None = None

    def to_dict(self):
        return {"type": "drag", **_table(self)}


def spring_end(body: str | None = None, point: Vector | None = None, particle: str | None = None,
               anchor: Vector | None = None) -> dict:
    """One end of a Spring: a body (+ point in its reference frame, m; default its centre of mass), a
    particle, or a fixed world anchor (m)."""
    end = {"body": body, "point": point, "particle": particle, "anchor": anchor}
    return {k: (v.tolist() if hasattr(v, "tolist") else list(v) if isinstance(v, tuple) else v)
            for k, v in end.items() if v is not None}


@dataclass
class Spring:
    """A linear spring-damper between two ends (spring_end(...)): stiffness (N/m), rest_length (m),
    damping (N s/m); potential k(|d| - L0)^2 / 2."""
    a: dict
    b: dict
    stiffness: float
    rest_length: float | None = None
    damping: float | None = None

    def to_dict(self):
        return {"type": "spring", **_table(self)}


@dataclass
class GravityGradient:
    """Point-mass gravity of a central body, mu (m^3/s^2), at center (m, world), with the
    gravity-gradient torque 3 mu / r^5 r x (I r); torque_only keeps just the torque."""
    mu: float
    center: Vector | None = None
    torque_only: bool | None = None

    def to_dict(self):
        return {"type": "gravity_gradient", **_table(self)}


@dataclass
class Rotor:
    """A rotor spinning on a body ([[rotors]]: a reaction or momentum wheel, a dual-spin rotor). The
    body's mass properties include it as if locked; the rotor adds its spin relative to the body: `speed`
    (rad/s) about the unit `axis` (the body's reference frame), `moment` its axial moment (kg m^2).
    torque (N m): the motor's, a number or a table [[t, u], ...] (u linear between the rows); or set by
    simulate(controller=...). max_speed (rad/s) stops the motor, max_torque (N m) clips a controller."""
    name: str
    body: str
    axis: Vector
    moment: float
    speed: float | None = None
    torque: Any = None
    max_speed: float | None = None
    max_torque: float | None = None

    def to_dict(self):
        return _table(self)


@dataclass
class Event:
    """A moment to catch during a run ([[events]]), on one body or particle: a column of the output
    table crossing `value` (column="w2": omega_2 about the intermediate axis changes sign at each flip;
    "com_z": a height), or the angle between a body-fixed `axis` (reference frame) and a world direction
    `toward` crossing `angle_deg`. direction: "both", "rising" or "falling"; stop=True ends the run there.

    Or a function of the whole state, g(t, position, orientation, velocity, omega) -> float, given the
    world arrays (N, 3) / (N, 4) of every body (centre of mass, w-first quaternion of the principal
    frame, centre-of-mass velocity, angular velocity): the event is a sign change of g. Such an event is
    for simulate(events=[...]) only (it has no TOML form) and is evaluated in Python a few times per step.

    body="*": the event on every body of a scene whose bodies move independently (tumble.bodies(...);
    forces that act alike on every body: gravity, central gravity, damping of all bodies), each body's
    crossings its own (Trajectory.events' rows), for simulate(events=[...]) only. Each body then is a
    lane of the batched engine that locates its own crossings, so N bodies cost N, not N²."""
    name: str
    body: str | None = None
    column: str | None = None
    value: float | None = None
    axis: Vector | None = None
    toward: Vector | None = None
    angle_deg: float | None = None
    direction: str | None = None
    stop: bool | None = None
    g: Callable | None = field(default=None, repr=False)

    def to_dict(self):
        if self.g is not None:
            raise ValueError(f"event '{self.name}' is a Python function: give it to simulate(events=[...]), "
                             "not to a scene file")
        return _table(self, skip=("g",))


from . import _tumble  # noqa: E402

# The [simulation] keys: those of the table of run settings (include/tumble/sim/run_settings.hpp).
_SIMULATION_KEYS = tuple(s["key"] for s in _tumble._run_settings() if s["in_scene"])


def scene_dict(bodies=(), particles=(), forces=(), events=(), fields=None, rotors=(), **simulation) -> dict:
    """The dict of a scene file from Body, Particle, force, Event and Rotor objects (or dicts of the
    file's keys) and the [simulation] values as keywords (duration, timestep, integrator, formulation,
    output_interval, rtol, atol, drift_threshold); fields: the [output] fields."""
    unknown = set(simulation) - set(_SIMULATION_KEYS)
    if unknown:
        raise TypeError(f"unknown [simulation] keys {sorted(unknown)}; the keys are {', '.join(_SIMULATION_KEYS)}")
    as_table = lambda x: x.to_dict() if hasattr(x, "to_dict") else dict(x)
    d: dict = {"simulation": {k: v for k, v in simulation.items() if v is not None}}
    if fields is not None:
        d["output"] = {"fields": list(fields)}
    gravity = [f for f in forces if isinstance(f, Gravity)]
    if len(gravity) > 1:
        raise ValueError("more than one Gravity: a scene has one uniform gravity; add the vectors")
    if gravity:
        g = gravity[0].g
        d["world"] = {"gravity": g.tolist() if hasattr(g, "tolist") else list(g)}
    if bodies:
        d["bodies"] = [as_table(b) for b in bodies]
    if particles:
        d["particles"] = [as_table(p) for p in particles]
    tables = [as_table(f) for f in forces if not isinstance(f, Gravity)]
    if tables:
        d["forces"] = tables
    if events:
        d["events"] = [as_table(e) for e in events]
    if rotors:
        d["rotors"] = [as_table(r) for r in rotors]
    return d


def make_scene(bodies=(), particles=(), forces=(), events=(), fields=None, path="scene.toml", rotors=(),
               **simulation):
    """A Scene from Python objects (see scene_dict), read by the scene-file reader: a mistake raises
    ValueError with the file's message ("scene.toml:7:3: body 'a': ..."); `path` anchors mesh paths."""
    from . import scene_from_dict
    return scene_from_dict(scene_dict(bodies, particles, forces, events, fields, rotors, **simulation), path)
