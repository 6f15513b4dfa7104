"""Read a raceway output file (docs/output_layout.md) into numpy arrays that carry their units.

    import raceway

    with raceway.RacewayOutput("run.h5") as out:   # also an interrupted run's run.h5.partial
        t = out["time"]                             # a Quantity: numpy array [T], t.units == "s"
        w = out["cage/angular_velocity"]            # [T x 3] (spatial) or [T] (planar), "rad/s"
        wz = out.component("cage/angular_velocity", "about z")   # [T] in both
        print(w.units, w.description, w[-1])
        pocket = out.segments("ball_pocket")        # {"names": [...], "normal_force": Quantity, ...}
        out.bearing                                 # geometry: radii, clearances, contact angle (SI)
        out.summary                                 # the run summary (dict, summary_json)
        out.build                                   # raceway version, commit, compiler, libraries
        out.series()                                # every time series' path
        out.table(["cage/angular_velocity"])        # columns by name (raceway.table; pandas: .to_pandas())

Segment diagnostics at a coarser sampling ([output] segment_every = N > 1): /segments/* hold a row
at every N-th output sample only (samples 0, N, 2N, ...; `segment_stride`, their times
`segment_time`). `RacewayOutput(path, at_segment_rows=True)` reads every other series at those
samples too, so that every series has the same rows (what the report reads); by default the other
series keep every sample.

A Quantity is a numpy array with two attributes, `units` and `description`, as the file states
them. In an interrupted run's .partial file the series may stop at different samples (each at its
last whole chunk): the reader cuts every series to the shortest (`rows`), so rows still match.
Arithmetic keeps the attributes of the left operand unchanged (this is not a units library):
read them, do not rely on them after computing.

One dialect for every file: the reader speaks layout version 3 (the same dataset names in planar
and spatial runs) and reads files of versions 1 and 2 under the same names. Older files' datasets
are found under their new names (OLD_NAMES), `ball_count` is `element_count`, the bearing
attributes are derived from the run summary's resolved scene parameters (never from the model's
prose), planar `/cage/epicyclic_speed` and `/cage/rolling_speed` are computed from the rings'
speeds and race radii, and version 1's scalar series ([T x 1]) come back as [T].

Needs numpy and h5py (python3-numpy, python3-h5py).
"""
import json
import math
import tomllib

import h5py
import numpy as np

#: The newest layout this reader knows (root attribute layout_version; files without it are 1).
LAYOUT_VERSION = 3

BUILD_ATTRIBUTES = ("raceway_version", "raceway_commit", "build_type", "compiler", "hdf5_version",
                    "sundials_version", "petsc_version", "mpi_library")

#: Version 3 name -> the name in files of versions 1 and 2 (docs/output_layout.md, "Earlier layouts").
#: `<body>` is inner_ring, outer_ring or cage; `<kind>` a segment kind.
OLD_NAMES = {
    "<body>/angles": "<body>/angle",            # planar: the rotation about z
    "rollers/angular_velocity": "rollers/spin",  # planar: roller rotation rate about its axis
    "segments/<kind>/element": "segments/<kind>/ball",  # spatial only in version 2
}
OLD_ATTRIBUTES = {"element_count": "ball_count"}

#: The bearing attributes of the root (layout version 3; derived for older files).
BEARING_ATTRIBUTES = ("model_kind", "bearing_type", "rolling_element", "element_group", "element_count",
                      "pitch_radius", "element_radius", "inner_race_radius", "outer_race_radius",
                      "diametral_clearance", "nominal_contact_angle", "arcs_per_ring", "inner_groove_radius",
                      "outer_groove_radius", "roller_length", "cage_guidance", "pocket_clearance", "land_clearance",
                      "element_position_tolerance", "relative_tolerance")

BODIES = ("inner_ring", "outer_ring", "cage")
_LINEAR = ["x", "y", "z"]
_ANGULAR = ["about x", "about y", "about z"]


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


def _old_name(path):
    """The version 1/2 name of a version 3 path, or None when it was not renamed."""
    parts = path.split("/")
    if len(parts) == 2 and parts[0] in BODIES and parts[1] == "angles":
        return f"{parts[0]}/angle"
    if path == "rollers/angular_velocity":
        return "rollers/spin"
    if len(parts) == 3 and parts[0] == "segments" and parts[2] == "element":
        return f"segments/{parts[1]}/ball"
    return None


def _new_name(path):
    """The version 3 name of a version 1/2 path (itself when it was not renamed)."""
    parts = path.split("/")
    if len(parts) == 2 and parts[0] in BODIES and parts[1] == "angle":
        return f"{parts[0]}/angles"
    if path == "rollers/spin":
        return "rollers/angular_velocity"
    if len(parts) == 3 and parts[0] == "segments" and parts[2] == "ball":
        return f"segments/{parts[1]}/element"
    return path


class RacewayOutput:
    """One output file, open for reading (use it in a with statement, or call close())."""

    def __init__(self, path, at_segment_rows=False):
        self.path = path
        self.file = h5py.File(path, "r")
        self.layout_version = int(self.file.attrs.get("layout_version", 1))
        if self.layout_version > LAYOUT_VERSION:
            self.file.close()
            raise ValueError(f"{path}: layout version {self.layout_version} is newer than this reader "
                             f"({LAYOUT_VERSION}); use the raceway package of the raceway that wrote it")
        segments = self.file.get("segments")
        #: The segment diagnostics' rows are every segment_stride-th output sample ([output] segment_every).
        self.segment_stride = int(segments.attrs.get("sample_stride", 1)) if segments is not None else 1
        series = [p for p in self._file_paths() if self._is_series_ds(self.file[p])]
        lengths = [self.file[p].shape[0] for p in series if not self._strided(p)]
        #: Output times every series holds (the file's /time length unless a .partial cut them).
        self.rows = min(lengths) if lengths else 0
        strided = [self.file[p].shape[0] for p in series if self._strided(p)]
        #: Rows every segment series holds (rows when segment_stride is 1).
        self.segment_rows = min(strided + [-(-self.rows // self.segment_stride)])
        self._coarse = at_segment_rows and self.segment_stride > 1
        self._derived = self._derived_series() if self.layout_version < 3 else {}

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        self.file.close()

    # ---- names ---------------------------------------------------------------------------------

    def _file_paths(self):
        found = []
        self.file.visititems(lambda name, obj: found.append(name) if isinstance(obj, h5py.Dataset) else None)
        return found

    def _in_file(self, path):
        """The dataset's path in this file for a (version 3) path, or None."""
        p = path.strip("/")
        if p in self.file:
            return p
        if self.layout_version < 3:
            old = _old_name(p)
            if old is not None and old in self.file:
                return old
        return None

    def __contains__(self, path):
        p = path.strip("/")
        return self._in_file(p) is not None or p in self._derived

    def _strided(self, path):
        """Whether the file's series at `path` has a row at every segment_stride-th sample only."""
        return self.segment_stride > 1 and path.strip("/").startswith("segments/")

    def is_strided(self, path):
        """Whether the series at `path` holds a row at every segment_stride-th sample only (a segment
        diagnostic with [output] segment_every > 1, and /segments/time)."""
        return self._strided(path)

    @property
    def at_segment_rows(self):
        """Whether every series is read at the segment rows' samples (at_segment_rows=True, stride > 1)."""
        return self._coarse

    @staticmethod
    def _is_series_ds(ds):
        return isinstance(ds, h5py.Dataset) and ds.maxshape is not None and len(ds.maxshape) > 0 \
            and ds.maxshape[0] is None

    def dataset(self, path):
        """The h5py dataset of a (version 3) path; KeyError naming the file when it has none."""
        found = self._in_file(path)
        if found is None:
            raise KeyError(f"{self.path}: no dataset '/{path.strip('/')}'")
        return self.file[found]

    def __getitem__(self, path):
        """A numeric dataset as a Quantity, a string table as a list of str."""
        p = path.strip("/")
        if p in self._derived and self._in_file(p) is None:
            return self._derived[p]()
        found = self._in_file(p)
        if found is None:
            if p in self.file:
                raise KeyError(f"{self.path}: {path} is a group, not a dataset")
            raise KeyError(f"{self.path}: no dataset '/{p}'")
        ds = self.file[found]
        if ds.dtype.kind in ("O", "S", "U"):
            return [_text(v) for v in ds[()]]
        values = ds[()]
        if self._is_series_ds(ds):
            if self._strided(found):
                values = values[:self.segment_rows]
            elif self._coarse:  # at the segment rows' samples
                values = values[:self.rows:self.segment_stride][:self.segment_rows]
            else:
                values = values[:self.rows]
            if self.layout_version < 2 and values.ndim == 2 and values.shape[1] == 1:
                values = values[:, 0]
        return Quantity(values, _text(ds.attrs.get("units", "")), _text(ds.attrs.get("description", "")))

    def is_series(self, path):
        """Whether the dataset is a time series (one row per output time, extendible first dimension)."""
        p = path.strip("/")
        if p in self._derived and self._in_file(p) is None:
            return True
        return self._is_series_ds(self.dataset(p))

    def datasets(self):
        """Every dataset's path ("/time", "/cage/position", ...) in this reader's names, in file order."""
        names = ["/" + (_new_name(p) if self.layout_version < 3 else p) for p in self._file_paths()]
        return names + ["/" + p for p in self._derived if self._in_file(p) is None]

    def series(self):
        """Every time series' path."""
        return [p for p in self.datasets() if self.is_series(p)]

    def components(self, path):
        """What each column of a body series is ("x", "y", "about z", ...): its `components`
        attribute (version 3), inferred from the name and shape in older files; [] for others."""
        if self._in_file(path) is None and path.strip("/") in self._derived:
            return []
        ds = self.dataset(path)
        if "components" in ds.attrs:
            return [_text(c) for c in ds.attrs["components"]]
        name = path.strip("/").rsplit("/", 1)[-1]
        group = path.strip("/").split("/")[0]
        if group not in BODIES + ("rollers", "balls"):
            return []
        shape = ds.shape[1:] if group in BODIES else ds.shape[2:]
        if self.layout_version < 2 and shape == (1,):
            shape = ()
        width = shape[0] if shape else 1
        if name in ("position", "velocity"):
            return _LINEAR[:width]
        if name in ("angle", "angles", "angular_velocity", "spin"):
            return ["about z"] if width == 1 else _ANGULAR[:width]
        if name in ("acceleration", "force"):
            return ["x", "y", "about z"] if width == 3 else _LINEAR + _ANGULAR
        return []

    def component(self, path, which):
        """One column of a body series by what it is: component("cage/angular_velocity", "about z")
        is [T] in planar and spatial runs alike (rolling elements: [T x n])."""
        names = self.components(path)
        if which not in names:
            raise KeyError(f"{self.path}: /{path.strip('/')} has no component '{which}' (it has {names})")
        q = self[path]
        return q if len(names) == 1 else q[..., names.index(which)]

    # ---- attributes ------------------------------------------------------------------------------

    @property
    def time(self):
        return self["time"]

    @property
    def segment_time(self):
        """The output times of the /segments rows: /segments/time (segment_stride > 1), else /time."""
        return self["segments/time"] if self.segment_stride > 1 else self.time

    @property
    def attrs(self):
        """The root attributes (str, int, float or numpy arrays); in older files also the bearing
        attributes derived from the run summary (see `bearing`) and ball_count as element_count."""
        a = {k: _text(v) if isinstance(v, (bytes, str)) else v for k, v in self.file.attrs.items()}
        if self.layout_version < 3:
            for new, old in OLD_ATTRIBUTES.items():
                if old in a:
                    a.setdefault(new, a.pop(old))
            for k, v in self._derived_bearing().items():
                a.setdefault(k, v)
        return a

    @property
    def bearing(self):
        """The bearing attributes (BEARING_ATTRIBUTES present in the file; SI units)."""
        a = self.attrs
        return {k: a[k] for k in BEARING_ATTRIBUTES if k in a}

    @property
    def model_kind(self):
        return self.attrs.get("model_kind", "planar")

    @property
    def element_group(self):
        """The group of the rolling elements: "rollers" or "balls"."""
        return self.attrs.get("element_group", "balls" if self.model_kind == "spatial" else "rollers")

    @property
    def summary(self):
        """The run summary (summary_json), or {} while the run has not written it."""
        text = self.file.attrs.get("summary_json")
        return json.loads(_text(text)) if text is not None else {}

    @property
    def build(self):
        return {k: _text(self.file.attrs[k]) for k in BUILD_ATTRIBUTES if k in self.file.attrs}

    @property
    def scene_text(self):
        return _text(self.file.attrs.get("scene_text", ""))

    @property
    def scene_name(self):
        """The scene's [scene] name (the resolved parameter of the run summary; the scene text's
        while the run has no summary); the scene file's path when it has neither."""
        name = self.summary.get("scene_parameters", {}).get("scene.name", {}).get("value")
        if not name:
            try:
                name = tomllib.loads(self.scene_text).get("scene", {}).get("name", "")
            except tomllib.TOMLDecodeError:
                name = ""
        return name or _text(self.file.attrs.get("scene_source", self.path))

    def segment_kinds(self):
        if "segments" not in self.file:
            return []
        return sorted(k for k, v in self.file["segments"].items() if isinstance(v, h5py.Group))

    def segments(self, kind):
        """Every dataset of /segments/<kind>: names (list of str), per-segment columns and diagnostics."""
        return {_new_name(f"segments/{kind}/{name}").rsplit("/", 1)[-1]: self[f"segments/{kind}/{name}"]
                for name in self.file[f"segments/{kind}"].keys()}

    def table(self, paths=None):
        """The series as named columns (raceway.table.Table; .to_pandas() for a DataFrame)."""
        from raceway.table import series_table
        return series_table(self, paths)

    # ---- older layouts ---------------------------------------------------------------------------

    def _derived_bearing(self):
        """Versions 1 and 2: the bearing attributes of version 3 from the resolved scene parameters
        of the run summary (and the file's own ball_count, pitch_radius, clearances); {} without a
        summary (an interrupted run's .partial)."""
        p = self.summary.get("scene_parameters", {})
        if not p:
            return {}
        value = lambda key, default=None: p.get(key, {}).get("value", default)
        kind = "spatial" if _text(self.file.attrs.get("model_kind", "planar")) == "spatial" else "planar"
        btype = value("bearing.type", "cylindrical_roller")
        ball = btype not in ("cylindrical_roller", "tapered_roller")
        d = value("bearing.ball_diameter") if ball else value("bearing.roller_diameter")
        dm, pd = value("bearing.pitch_diameter"), value("bearing.radial_clearance", 0.0)
        if d is None or dm is None:
            return {}
        guidance = value("cage.guidance", "")
        rtol = value("solver.rtol", 1e-6)
        atol = value("solver.atol.position", 0.0)
        b = {"model_kind": kind, "bearing_type": btype, "rolling_element": "ball" if ball else "roller",
             "element_group": "balls" if kind == "spatial" else "rollers",
             "element_count": int(value("bearing.rolling_elements", 0)),
             "pitch_radius": 0.5 * dm, "element_radius": 0.5 * d,
             "inner_race_radius": 0.5 * (dm - d - 0.5 * pd), "outer_race_radius": 0.5 * (dm + d + 0.5 * pd),
             "diametral_clearance": pd, "cage_guidance": guidance,
             "pocket_clearance": value("cage.pocket_clearance", math.nan),
             "land_clearance": value("cage.land_clearance", 0.0) if guidance.endswith("_land") else 0.0,
             # as the integrator's physical default (solver/bearing/model.cpp)
             "element_position_tolerance": atol if atol > 0 else rtol * 0.5 * dm, "relative_tolerance": rtol}
        if ball:
            four = btype == "four_point_contact_ball"
            b["nominal_contact_angle"] = value("bearing.arc_contact_angle", 0.0) if four else \
                value("bearing.contact_angle", 0.0) if btype == "angular_contact_ball" else 0.0
            b["arcs_per_ring"] = 2 if four else 1
            b["inner_groove_radius"] = value("bearing.inner_conformity", math.nan) * d
            b["outer_groove_radius"] = value("bearing.outer_conformity", math.nan) * d
        else:
            b.update({"nominal_contact_angle": 0.0, "arcs_per_ring": 1,
                      "roller_length": value("bearing.roller_length", math.nan)})
        return b

    def _derived_series(self):
        """Versions 1 and 2, planar: /cage/epicyclic_speed and /cage/rolling_speed (line contacts roll
        at 0 deg: both the epicyclic speed) from the rings' angular velocities and race radii."""
        b = self._derived_bearing()
        if _text(self.file.attrs.get("model_kind", "planar")) == "spatial" or "inner_race_radius" not in b:
            return {}
        ri, ro = b["inner_race_radius"], b["outer_race_radius"]

        def epicyclic():
            wi, wo = (np.asarray(self[f"{r}/angular_velocity"], dtype=float) for r in ("inner_ring", "outer_ring"))
            return Quantity((wi * ri + wo * ro) / (ri + ro), "rad/s",
                            "kinematic cage speed from the rings' speeds and race radii (computed by the reader "
                            f"for a layout version {self.layout_version} file)")
        return {"cage/epicyclic_speed": epicyclic, "cage/rolling_speed": epicyclic}


def open_output(path):
    """RacewayOutput(path): `with raceway.open_output("run.h5") as out: ...`."""
    return RacewayOutput(path)
