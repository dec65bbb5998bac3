"""Monte Carlo studies from Python: the [ensemble] of a scene (docs/ensembles.md) run on every core, its
table as NumPy columns; and the reader of the tables `tumble ensemble` writes (CSV or HDF5)."""

from __future__ import annotations

import csv
import os

import numpy as np

from . import _dict_toml, _tumble


class EnsembleResult:
    """A study's table: ``columns`` maps each column ("run", the drawn values by their paths, then the
    outputs such as "flip.first_t", "handle.w2_max", "energy_drift_max") to an array (R,), one value
    per run in run order, NaN where undefined; ``summary`` is a list of dicts (column, count, mean,
    std, min, q05, q25, q50, q75, q95, max, histogram of 20 bins). ``result["flip.first_t"]`` is a
    column."""

    def __init__(self, columns, summary):
        self.columns = dict(columns)
        self.summary = list(summary)

    def __getitem__(self, column):
        try:
            return self.columns[column]
        except KeyError:
            raise KeyError(f"no column '{column}'; the columns are: {', '.join(self.columns)}") from None

    def __len__(self):
        return len(self.columns.get("run", ()))

    def __repr__(self):
        return f"EnsembleResult({len(self)} runs, columns {list(self.columns)})"


def ensemble(scene, ensemble=None, threads=0):
    """Run a study: `scene` is a scene file (path) or a scene dict (as scene_from_dict takes); `ensemble`
    (a dict with the keys of [ensemble]: runs, seed, vary (a list of dicts: path, distribution and its
    parameters), outputs) adds or replaces the file's [ensemble] table. Runs on `threads` threads (0: one
    per core); run i's draws depend only on (seed, i), so the table does not depend on them. Ctrl-C
    stops it with KeyboardInterrupt. Returns an EnsembleResult."""
    path = "scene.toml"
    if isinstance(scene, dict):
        table = dict(scene)
    else:
        import tomllib
        path = os.fspath(scene)
        with open(path, "rb") as f:
            table = tomllib.load(f)
    if ensemble is not None:
        table["ensemble"] = ensemble
    if "ensemble" not in table:
        raise ValueError("the scene has no [ensemble] table: give ensemble={'runs': N, 'vary': [...]}")
    if ensemble is None and not isinstance(scene, dict):
        with open(path, encoding="utf-8") as f:
            raw = _tumble._ensemble(f.read(), path, int(threads))  # the file as written: messages cite its lines
    else:
        text = _dict_toml.dumps(table)
        try:
            raw = _tumble._ensemble(text, path, int(threads))
        except ValueError as e:
            raise ValueError(_dict_toml.located(str(e), text, path)) from None
    return EnsembleResult(raw["columns"], raw["summary"])


def _check_runs(path, columns):
    """A table tumble ensemble wrote has the runs 0, 1, …, R − 1 in order: anything else was edited or
    is another file, and its rows would be taken for runs they are not."""
    if "run" not in columns:
        raise ValueError(f"{path}: no 'run' column: not a table that tumble ensemble wrote")
    run = columns["run"]
    expected = np.arange(len(run))
    wrong = np.flatnonzero(run != expected)
    if wrong.size:
        k = int(wrong[0])
        raise ValueError(f"{path}: row {k} holds run {run[k]:g} where run {k} belongs (the runs are 0, 1, 2, … "
                         "in order): the table was edited or is not one tumble ensemble wrote")


def read_ensemble(path):
    """Read a table that `tumble ensemble` wrote: CSV (with PATH.summary.csv beside it when present) or
    HDF5 (needs h5py). Returns an EnsembleResult; ValueError if its run column is not 0, 1, 2, …"""
    path = os.fspath(path)
    with open(path, "rb") as f:
        hdf5 = f.read(8) == b"\x89HDF\r\n\x1a\n"
    if hdf5:
        import h5py
        from .trajectory import _dataset
        size = os.path.getsize(path)
        with h5py.File(path, "r") as f:
            def need(key):  # links, external storage and oversized claims refused, as for trajectories
                d = _dataset(h5py, f, key, path, size)
                if d is None:
                    raise ValueError(f"{path}: no dataset {key}: not a table that tumble ensemble wrote")
                return d[:]
            order = [c.decode() if isinstance(c, bytes) else c for c in need("columns")]
            columns = {c: need(f"runs/{c}") for c in order}
            _check_runs(path, columns)
            keys = ("count", "mean", "std", "min", "q05", "q25", "q50", "q75", "q95", "max")
            s = {k: need(f"summary/{k}") for k in keys + ("column", "histogram")}
            names = [n.decode() if isinstance(n, bytes) else n for n in s["column"]]
            summary = [{"column": n, **{k: float(s[k][i]) for k in keys}, "histogram": s["histogram"][i].tolist()}
                       for i, n in enumerate(names)]
        return EnsembleResult(columns, summary)
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header = rows[0]
    data = np.array([[float(x) if x != "" else np.nan for x in r] for r in rows[1:]]).reshape(-1, len(header))
    columns = {name: data[:, k].copy() for k, name in enumerate(header)}
    _check_runs(path, columns)
    summary = []
    stem, _ = os.path.splitext(path)
    if os.path.isfile(stem + ".summary.csv"):
        with open(stem + ".summary.csv", newline="") as f:
            for r in csv.DictReader(f):
                d = {k: (float(v) if v != "" else np.nan) for k, v in r.items() if k not in ("column", "histogram")}
                d["column"] = r["column"]
                d["histogram"] = [int(x) for x in r["histogram"].split()]
                summary.append(d)
    return EnsembleResult(columns, summary)
