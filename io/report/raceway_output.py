#!/usr/bin/env python3
"""Read a raceway output file (docs/output_layout.md) into numpy arrays that carry their units.

    import sys; sys.path.insert(0, "RACEWAY_SOURCE/io/report")
    from raceway_output import RacewayOutput

    with RacewayOutput("run.h5") as out:          # also an interrupted run's run.h5.partial
        t = out["time"]                             # a Quantity: numpy array [T], t.units == "s"
        w = out["cage/angular_velocity"]            # [T x 3] (spatial) or [T] (planar), "rad/s"
        print(w.units, w.description, w[-1])
        pocket = out.segments("ball_pocket")        # {"names": [...], "normal_force": Quantity, ...}
        out.summary                                 # the run summary (dict, summary_json)
        out.build                                   # raceway version, commit, compiler, libraries
        out.series()                                # every time series' path

A Quantity is a numpy array with two attributes, `units` and `description`, as the file states
them. In an interrupted run's .partial file the series may stop at different samples (each at its
last whole chunk): the reader cuts every series to the shortest (`rows`), so rows still match. Arithmetic keeps the attributes of the left operand unchanged (this is not a units library):
read them, do not rely on them after computing. Files written before layout version 2 stored
scalar series as [T x 1]; the reader returns them as [T] like newer files.

Needs numpy and h5py (python3-numpy, python3-h5py).
"""
import json

import h5py
import numpy as np

#: The newest layout this reader knows (root attribute layout_version; files without it are 1).
LAYOUT_VERSION = 2

BUILD_ATTRIBUTES = ("raceway_version", "raceway_commit", "build_type", "compiler", "hdf5_version",
                    "sundials_version", "petsc_version", "mpi_library")


class Quantity(np.ndarray):
    """A numpy array with the units and description of the dataset it was read from."""

    def __new__(cls, values, units="", description=""):
        q = np.asarray(values).view(cls)
        q.units, q.description = units, description
        return q

    def __array_finalize__(self, obj):
        self.units = getattr(obj, "units", "")
        self.description = getattr(obj, "description", "")


def _text(value):
    return value.decode("utf-8", "replace") if isinstance(value, bytes) else str(value)


class RacewayOutput:
    """One output file, open for reading (use it in a with statement, or call close())."""

    def __init__(self, path):
        self.path = path
        self.file = h5py.File(path, "r")
        self.layout_version = int(self.file.attrs.get("layout_version", 1))
        lengths = [self.file[p.strip("/")].shape[0] for p in self.series()]
        #: Output times every series holds (the file's /time length unless a .partial cut them).
        self.rows = min(lengths) if lengths else 0
        if self.layout_version > LAYOUT_VERSION:
            raise ValueError(f"{path}: layout version {self.layout_version} is newer than this reader "
                             f"({LAYOUT_VERSION}); use the raceway_output.py of the raceway that wrote it")

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        self.file.close()

    def __contains__(self, path):
        return path.strip("/") in self.file

    def __getitem__(self, path):
        """A numeric dataset as a Quantity, a string table as a list of str."""
        ds = self.file[path.strip("/")]
        if not isinstance(ds, h5py.Dataset):
            raise KeyError(f"{self.path}: {path} is a group, not a dataset")
        if ds.dtype.kind in ("O", "S", "U"):
            return [_text(v) for v in ds[()]]
        values = ds[()]
        if self.is_series(path):
            values = values[:self.rows]
            if self.layout_version < 2 and values.ndim == 2 and values.shape[1] == 1:
                values = values[:, 0]
        return Quantity(values, _text(ds.attrs.get("units", "")), _text(ds.attrs.get("description", "")))

    def is_series(self, path):
        """Whether the dataset is a time series (one row per output time, extendible first dimension)."""
        ds = self.file[path.strip("/")]
        return isinstance(ds, h5py.Dataset) and ds.maxshape is not None and len(ds.maxshape) > 0 \
            and ds.maxshape[0] is None

    def datasets(self):
        """Every dataset's path ("/time", "/cage/position", ...), in file order."""
        found = []
        self.file.visititems(lambda name, obj: found.append("/" + name) if isinstance(obj, h5py.Dataset) else None)
        return found

    def series(self):
        """Every time series' path."""
        return [p for p in self.datasets() if self.is_series(p)]

    @property
    def time(self):
        return self["time"]

    @property
    def attrs(self):
        """The root attributes (str, int, float or numpy arrays)."""
        return {k: _text(v) if isinstance(v, (bytes, str)) else v for k, v in self.file.attrs.items()}

    @property
    def summary(self):
        """The run summary (summary_json), or {} while the run has not written it."""
        text = self.file.attrs.get("summary_json")
        return json.loads(_text(text)) if text is not None else {}

    @property
    def build(self):
        return {k: self.attrs[k] for k in BUILD_ATTRIBUTES if k in self.file.attrs}

    @property
    def scene_text(self):
        return _text(self.file.attrs.get("scene_text", ""))

    def segment_kinds(self):
        return sorted(self.file["segments"].keys()) if "segments" in self.file else []

    def segments(self, kind):
        """Every dataset of /segments/<kind>: names (list of str), per-segment columns and diagnostics."""
        return {name: self[f"segments/{kind}/{name}"] for name in self.file[f"segments/{kind}"].keys()}
