"""Trajectories as NumPy arrays: the result of `simulate`, and the reader of tumble's own CSV and HDF5
files, which gives the same object. What each array holds (name, unit, frame, CSV columns) comes from
the library's output-field table, the one the CSV and HDF5 writers use."""

from __future__ import annotations

import csv
import os
from typing import NamedTuple

import numpy as np

from . import _tumble

#: Spellings of the tutorial beside the field names: ω in world, in the body's own (reference) axes and
#: in its principal axes {b} (^bω, Euler's equations' ω₁ ω₂ ω₃), and the quaternion (w first).
ALIASES = {
    "quaternion": "orientation",
    "omega_world": "angular_velocity",
    "omega_body": "angular_velocity_reference",
    "omega_principal": "angular_velocity_principal",
}


def field_table():
    """The output-field table: (body_fields, system_fields), each a list of dicts with name, width,
    columns (CSV), unit, frame and meaning."""
    return _tumble._field_table()


class EventCrossing(NamedTuple):
    """One crossing of an event: its name, time (s) and the body or particle it watches (None for an
    event written in Python, which watches the whole state)."""
    name: str
    t: float
    body: str | None


class Trajectory:
    """The samples of a run: ``t`` (T,) in s and one array (T, N, width) per output field, N the bodies
    then the particles in file order (``names``). Fields are attributes by their names (``position``,
    ``orientation``, ``velocity``, ``angular_velocity``, ...) and by the tutorial's: ``quaternion``
    (w, x, y, z: reference frame -> world), ``omega_world`` (rad/s, world), ``omega_body`` (rad/s, the
    body's reference axes) and ``omega_principal`` (rad/s, principal axes, moments ascending).
    ``units`` and ``frames`` say what each holds.

    System quantities (``kinetic_energy``, ``potential_energy``, ``total_energy``, ``linear_momentum``,
    ``angular_momentum`` (world, about the origin), ``energy_drift``, ``linear_momentum_drift``,
    ``angular_momentum_drift``) are attributes too, arrays (T,) or (T, 3), NaN where undefined; all of
    them are in ``diagnostics``. ``events`` lists every event crossing in time order.

    Arrays from ``simulate`` are the library's own buffers handed to NumPy (no copy)."""

    def __init__(self, t, names, fields, units, frames, diagnostics, events=(), integrator=None,
                 formulation=None, timestep=None, warning=None, complete=True, rotor_names=()):
        self.t = t
        self.names = list(names)
        self.fields = dict(fields)
        self.units = dict(units)
        self.frames = dict(frames)
        self.diagnostics = dict(diagnostics)
        self.events = list(events)
        self.integrator = integrator
        self.formulation = formulation
        self.timestep = timestep
        self.warning = warning
        self.complete = complete
        #: The scene's [[rotors]] in order: the columns of diagnostics["rotor_speed"] (rad/s, relative
        #: to the body) and diagnostics["rotor_torque"] (N m, the motor torque held until the sample).
        self.rotor_names = list(rotor_names)
        self.sensitivities = None  # set by simulate(..., sensitivities=True): see stm

    @property
    def stm(self):
        """The state transition matrix at every sample, (T, 12 B, 12 B): d x(t_k) / d x(0) in the tangent
        space of docs/sensitivities.md (per body dp, dtheta, dv, domega, world axes, body-major). Bodies that
        do not interact give zeros off the diagonal blocks; ``stm_blocks`` holds those blocks alone."""
        return self._dense("stm")

    @property
    def parameter_sensitivity(self):
        """d x(t_k) / d p at every sample, (T, 12 B, P B): p each body's principal moments (I1, I2, I3), or
        its mass (simulate(..., sensitivity_parameters="mass")); or (T, 12 B, P) for the force models' P
        parameters, which every body shares (sensitivity_parameters="forces"). ``parameter_names`` names
        the columns."""
        return self._dense("parameter_sensitivity")

    @property
    def parameter_names(self):
        """The names of parameter_sensitivity's columns, e.g. "box: I1" or "force 0 (uniform gravity ...): g_z"."""
        return list(self._sensitivity("parameter_names"))

    @property
    def stm_blocks(self):
        """Each body's own block of the state transition matrix, (T, B, 12, 12), without the B x B layout of
        ``stm`` (bodies that do not interact). For coupled bodies (springs), ``stm`` itself."""
        return self._sensitivity("stm")

    def _sensitivity(self, name):
        if self.sensitivities is None:
            raise AttributeError(f"the trajectory has no {name}: run simulate(..., sensitivities=True)")
        return self.sensitivities[name]

    def _dense(self, name):
        blocks = self._sensitivity(name)
        if self.sensitivities["coupled"]:
            return blocks
        T, B, _, P = blocks.shape
        if name == "parameter_sensitivity" and self.sensitivities["sensitivity_parameters"] == "forces":
            return blocks.reshape(T, 12 * B, P)  # shared columns: every body's rows, one after the other
        dense = np.zeros((T, 12 * B, P * B))
        for b in range(B):
            dense[:, 12 * b:12 * b + 12, P * b:P * b + P] = blocks[:, b]
        return dense

    @classmethod
    def _from_run(cls, raw):
        rows = list(raw["names"])
        events = [EventCrossing(n, t, rows[r] if r >= 0 else None)
                  for n, t, r in zip(raw["event_names"], raw["event_t"], raw["event_rows"])]
        trajectory = cls(raw["t"], rows, raw["fields"], raw["units"], raw["frames"], raw["diagnostics"],
                         events, raw["integrator"], raw["formulation"], raw["timestep"], raw.get("warning"),
                         complete=not raw["interrupted"], rotor_names=raw["rotor_names"])
        if "stm" in raw:
            trajectory.sensitivities = {key: raw[key] for key in
                                        ("stm", "parameter_sensitivity", "coupled", "sensitivity_parameters",
                                         "parameter_names")}
        return trajectory

    def _from(self, k):
        """The samples from the k-th on (views of the same arrays); events and settings as they are."""
        later = Trajectory(self.t[k:], self.names, {n: a[k:] for n, a in self.fields.items()}, self.units,
                           self.frames, {n: a[k:] for n, a in self.diagnostics.items()}, self.events,
                           self.integrator, self.formulation, self.timestep, self.warning, self.complete,
                           self.rotor_names)
        if self.sensitivities is not None:
            later.sensitivities = dict(self.sensitivities, stm=self.sensitivities["stm"][k:],
                                       parameter_sensitivity=self.sensitivities["parameter_sensitivity"][k:])
        return later

    def __getattr__(self, name):
        fields = self.__dict__.get("fields", {})
        key = ALIASES.get(name, name)
        if key in fields:
            return fields[key]
        diagnostics = self.__dict__.get("diagnostics", {})
        if key in diagnostics:
            return diagnostics[key]
        raise AttributeError(
            f"the trajectory has no field '{name}'"
            + (f" ('{key}')" if key != name else "")
            + f": it holds {', '.join(fields)}; ask simulate(..., fields=[...]) for others: "
            + ", ".join(f["name"] for f in field_table()[0]))

    def body(self, name):
        """The index of a body or particle by name (its position along the N axis)."""
        try:
            return self.names.index(name)
        except ValueError:
            raise KeyError(f"no body or particle named '{name}'; the trajectory has {', '.join(self.names)}") from None

    def event_times(self, name, body=None):
        """The times (s) of the crossings of the event `name` (of one body if given), an array."""
        return np.array([e.t for e in self.events if e.name == name and (body is None or e.body == body)])

    def __repr__(self):
        return (f"Trajectory({len(self.t)} samples of {len(self.names)} bodies/particles, "
                f"fields {list(self.fields)}, {len(self.events)} event crossings"
                + ("" if self.complete else ", interrupted") + ")")


class Interrupted(KeyboardInterrupt):
    """Ctrl-C during `simulate`: a KeyboardInterrupt that keeps what was computed, as ``trajectory``
    (the samples up to the moment of the interrupt, with the state reached as the last one; a Ctrl-C
    that lands inside a Python force abandons that step, and the last sample is the one before it)."""

    def __init__(self, trajectory):
        super().__init__(f"interrupted at t = {trajectory.t[-1]:g} s; the samples so far are in .trajectory")
        self.trajectory = trajectory


def to_xyzw(q):
    """Quaternions (..., 4) from tumble's order (w, x, y, z) to the scalar-last order of SciPy's
    Rotation.from_quat and of ROS/Eigen coefficients (x, y, z, w)."""
    q = np.asarray(q)
    _check_quaternions(q)
    return np.concatenate([q[..., 1:], q[..., :1]], axis=-1)


def from_xyzw(q):
    """Quaternions (..., 4) from scalar-last (x, y, z, w), e.g. Rotation.as_quat(), to tumble's (w, x, y, z)."""
    q = np.asarray(q)
    _check_quaternions(q)
    return np.concatenate([q[..., 3:], q[..., :3]], axis=-1)


def _check_quaternions(q):
    if q.ndim == 0 or q.shape[-1] != 4:
        raise ValueError(f"quaternions must be an array (..., 4); got shape {q.shape}")


def read_trajectory(path):
    """Read a trajectory that `tumble run` wrote: an HDF5 file (.h5, .hdf5; needs h5py, Debian's
    python3-h5py) or a CSV file with its companions OUT.diagnostics.csv and OUT.events.csv when they
    exist. Returns the same Trajectory that `simulate` gives (arrays (T, N, width), names, units,
    frames, diagnostics, events)."""
    path = os.fspath(path)
    if not os.path.isfile(path):
        raise FileNotFoundError(f"no trajectory file {path}")
    with open(path, "rb") as f:
        hdf5 = f.read(8) == b"\x89HDF\r\n\x1a\n"
    return _read_hdf5(path) if hdf5 else _read_csv(path)


def _companion(path, suffix):
    stem, _ = os.path.splitext(path)
    return stem + suffix


def _read_csv(path):
    body_fields, system_fields = field_table()
    with open(path, newline="") as f:
        reader = csv.reader(f)
        try:
            header = next(reader)
        except StopIteration:
            raise ValueError(f"{path}: empty file; a tumble trajectory starts with the header t,body,...") from None
        if header[:2] != ["t", "body"]:
            raise ValueError(f"{path}:1: the header starts with {','.join(header[:2])!r}, not 't,body': "
                             "not a trajectory that tumble run wrote")
        rows = list(reader)
    # The header's columns, field by field, as the writer put them (one table, one order).
    fields, at = [], 2
    by_first = {f["columns"][0]: f for f in body_fields}
    while at < len(header):
        f = by_first.get(header[at])
        if f is None or header[at:at + f["width"]] != f["columns"]:
            raise ValueError(f"{path}:1: column {at + 1} ({header[at]!r}) begins no output field")
        fields.append(f)
        at += f["width"]
    names = []
    for r in rows:
        if r[1] in names:
            break
        names.append(r[1])
    N = len(names)
    if N == 0 or len(rows) % N != 0:
        raise ValueError(f"{path}: {len(rows)} rows are not whole samples of {N} bodies")
    T = len(rows) // N
    try:
        values = np.array([[float(x) for x in [r[0]] + r[2:]] for r in rows]).reshape(T, N, -1)
    except ValueError as e:
        raise ValueError(f"{path}: a value is not a number ({e}) or a row is short") from None
    t = values[:, 0, 0]
    arrays, at = {}, 1
    for f in fields:
        arrays[f["name"]] = np.ascontiguousarray(values[:, :, at:at + f["width"]])
        at += f["width"]
    diagnostics = {}
    dpath = _companion(path, ".diagnostics.csv")
    if os.path.isfile(dpath):
        with open(dpath, newline="") as f:
            dr = list(csv.reader(f))
        columns = dr[0]
        table = np.array([[float(x) if x != "" else np.nan for x in r] for r in dr[1:]]).reshape(-1, len(columns))
        at = 1
        for f in system_fields:
            block = table[:, at:at + f["width"]]
            diagnostics[f["name"]] = block[:, 0].copy() if f["width"] == 1 else block.copy()
            at += f["width"]
        # Then rotor_speed_<name> for each rotor and rotor_torque_<name> for each.
        rotor_names = [c[len("rotor_speed_"):] for c in columns[at:] if c.startswith("rotor_speed_")]
        if rotor_names:
            R = len(rotor_names)
            diagnostics["rotor_speed"] = table[:, at:at + R].copy()
            diagnostics["rotor_torque"] = table[:, at + R:at + 2 * R].copy()
    events = []
    epath = _companion(path, ".events.csv")
    if os.path.isfile(epath):
        with open(epath, newline="") as f:
            er = list(csv.reader(f))
        events = [EventCrossing(r[1], float(r[0]), r[2]) for r in er[1:]]
    return Trajectory(t, names, arrays, {f["name"]: f["unit"] for f in fields},
                      {f["name"]: f["frame"] for f in fields}, diagnostics, events, rotor_names=rotor_names)


def _dataset(h5py, f, key, path, file_size):
    """The dataset at `key` (None if there is none), refusing what a received file could use to make its
    reader read other files or memory it does not hold: soft and external links on the way (checked one
    link at a time, since following one is already the read), external storage, virtual datasets, and a
    size claimed beyond the file's own (tumble's C++ reader refuses the same: report_reader.cpp)."""
    node, parts = f, key.split("/")
    for i, part in enumerate(parts):
        link = node.get(part, getlink=True)
        if link is None:
            return None
        if not isinstance(link, h5py.HardLink):
            raise ValueError(f"{path}: {'/'.join(parts[:i + 1])} is a {type(link).__name__}: a trajectory that "
                             "tumble wrote has no links to follow, and this reader follows none")
        node = node[part]
    if not isinstance(node, h5py.Dataset):
        raise ValueError(f"{path}: {key} is not a dataset: not a trajectory that tumble run wrote")
    if node.is_virtual or node.id.get_create_plist().get_external_count() > 0:
        raise ValueError(f"{path}: the dataset {key} keeps its data in other files (external storage or a "
                         "virtual dataset); this reader reads nothing outside the file it is given")
    claimed = node.size * node.dtype.itemsize
    if claimed > file_size + (8 << 20):
        raise ValueError(f"{path}: the dataset {key} claims {claimed} bytes, more than the file's {file_size}: "
                         "it is damaged or forged")
    return node


def _read_hdf5(path):
    try:
        import h5py
    except ImportError:
        raise ImportError("reading HDF5 trajectories needs h5py: apt-get install python3-h5py") from None
    body_fields, system_fields = field_table()
    file_size = os.path.getsize(path)
    with h5py.File(path, "r") as f:
        def get(key):
            return _dataset(h5py, f, key, path, file_size)

        def need(key):
            d = get(key)
            if d is None:
                raise ValueError(f"{path}: no dataset {key}: not a trajectory that tumble run wrote")
            return d
        names = [n.decode() if isinstance(n, bytes) else n for n in need("names")[:]]
        t = need("t")[:]
        arrays, units, frames = {}, {}, {}
        for field in body_fields:
            d = get(field["name"])
            if d is not None:
                arrays[field["name"]] = d[:]
                units[field["name"]] = field["unit"]
                frames[field["name"]] = field["frame"]
        diagnostics = {}
        for field in system_fields:
            d = get("diagnostics/" + field["name"])
            diagnostics[field["name"]] = d[:] if d is not None else np.full((len(t),) + (() if field["width"] == 1 else (field["width"],)), np.nan)
        stored = get("diagnostics/rotor_names")
        rotor_names = [] if stored is None else [n.decode() if isinstance(n, bytes) else n for n in stored[:]]
        if rotor_names:
            diagnostics["rotor_speed"] = need("diagnostics/rotor_speed")[:]
            diagnostics["rotor_torque"] = need("diagnostics/rotor_torque")[:]
        events = []
        if get("events/t") is not None:
            g = {k: need("events/" + k) for k in ("event", "t", "body")}
            for name, time, row in zip(g["event"][:], g["t"][:], g["body"][:]):
                events.append(EventCrossing(name.decode() if isinstance(name, bytes) else name, float(time), names[row]))
        attrs = f.attrs
        text = lambda key: (attrs[key].decode() if isinstance(attrs[key], bytes) else str(attrs[key])) if key in attrs else None
        trajectory = Trajectory(t, names, arrays, units, frames, diagnostics, events, text("integrator"),
                                text("formulation"), float(attrs["timestep"]) if "timestep" in attrs else None,
                                complete=bool(attrs.get("complete", 1)), rotor_names=rotor_names)
        if get("stm") is not None:  # tumble run --sensitivities (docs/sensitivities.md, "Files")
            stm, dp = need("stm"), need("parameter_sensitivity")
            layout = stm.attrs.get("layout", b"")
            layout = layout.decode() if isinstance(layout, bytes) else str(layout)
            parameters = dp.attrs.get("parameters", b"")
            parameters = parameters.decode() if isinstance(parameters, bytes) else str(parameters)
            B = len(names)
            rows = (B, 12, 12) if layout == "block_diagonal" else (12 * B, 12 * B) if layout == "dense" else None
            if rows is None or stm.shape != (len(t),) + rows or dp.shape[:-1] != (len(t),) + rows[:-1]:
                raise ValueError(f"{path}: datasets stm {stm.shape} and parameter_sensitivity {dp.shape} (layout "
                                 f"'{layout}') do not fit {len(t)} samples of {B} bodies: not as tumble run wrote them")
            kind = parameters.split(" ")[0] if parameters.split(" ")[0] in ("mass", "forces") else "inertia"
            names_text = dp.attrs.get("parameter_names", b"")
            names_text = names_text.decode() if isinstance(names_text, bytes) else str(names_text)
            trajectory.sensitivities = {"stm": stm[:], "parameter_sensitivity": dp[:], "coupled": layout == "dense",
                                        "sensitivity_parameters": kind,
                                        "parameter_names": names_text.split("\n") if names_text else []}
        return trajectory
