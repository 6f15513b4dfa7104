"""The time series of an output file as named columns: a table indexed by time.

    with raceway.RacewayOutput("run.h5") as out:
        t = out.table(["cage/angular_velocity", "rollers/position"])
        t.columns        # ["cage/angular_velocity[about z]", "rollers/position[0, x]", ...]
        t["cage/angular_velocity[about z]"], t.units["rollers/position[0, x]"], t.time
        df = t.to_pandas()   # a pandas.DataFrame indexed by time (s), units in df.attrs["units"]

Each series becomes one column per cell of its row: a scalar series keeps its name, a body series
gets its component names ("[x]", "[about z]"), a rolling element's or segment's its index or
segment name ("[3, x]", "[roller_2_inner]"). The table works without pandas (numpy only); only
to_pandas() needs it (python3-pandas), and says so when it is missing.
"""
import numpy as np


class Table:
    """Columns of equal length (one value per output time), in insertion order."""

    def __init__(self, time):
        self.time = np.asarray(time, dtype=float)
        self.columns, self.units, self.descriptions = [], {}, {}
        self._data = {}

    def add(self, name, values, units="", description=""):
        values = np.asarray(values, dtype=float)
        if values.shape != self.time.shape:
            raise ValueError(f"column {name}: {values.shape[0] if values.ndim else 0} values for "
                             f"{self.time.shape[0]} output times")
        self.columns.append(name)
        self._data[name], self.units[name], self.descriptions[name] = values, units, description

    def __getitem__(self, name):
        return self._data[name]

    def __contains__(self, name):
        return name in self._data

    def __len__(self):
        return len(self.time)

    def to_pandas(self):
        """A pandas.DataFrame indexed by time [s]; df.attrs["units"] maps each column to its unit."""
        try:
            import pandas as pd
        except ImportError as err:
            raise ImportError(f"Table.to_pandas needs pandas (Debian: apt install python3-pandas): {err}") from None
        df = pd.DataFrame({c: self._data[c] for c in self.columns}, index=pd.Index(self.time, name="time"))
        df.attrs["units"] = dict(self.units)
        df.attrs["units"]["time"] = "s"
        return df


def _labels(out, path, shape):
    """Column labels for the cells of one row of `path` (row shape `shape`)."""
    components = out.components(path)
    parts = path.strip("/").split("/")
    names = f"segments/{parts[1]}/names" if parts[0] == "segments" and len(parts) == 3 else None
    segments = out[names] if names is not None and names in out else None
    labels = []
    for index in np.ndindex(*shape):
        parts = []
        for axis, i in enumerate(index):
            if components and axis == len(shape) - 1 and len(components) == shape[-1]:
                parts.append(components[i])
            elif segments is not None and axis == 0 and len(segments) == shape[0]:
                parts.append(segments[i])
            else:
                parts.append(str(i))
        labels.append("[" + ", ".join(parts) + "]" if parts else "")
    if not shape and components:  # a body's scalar series: name its one component
        labels = [f"[{components[0]}]"]
    return labels


def series_table(out, paths=None):
    """A Table of the series `paths` (default: every series but /time) of an open RacewayOutput.
    Segment series stored at every N-th sample only ([output] segment_every) share a table with the
    others when the file is read at the segment rows (RacewayOutput(path, at_segment_rows=True));
    alone, their table is indexed by /segments/time."""
    if paths is None:
        paths = [p for p in out.series() if p not in ("/time", "/segments/time")]
    strided = [p for p in paths if out.is_strided(p)]
    if strided and not out.at_segment_rows and len(strided) < len(paths):
        raise ValueError(f"{out.path}: the segment diagnostics are stored once every {out.segment_stride} samples "
                         f"([output] segment_every) and the other series at every sample: table them apart, or open "
                         f"the file with RacewayOutput(path, at_segment_rows=True) to read every series there")
    table = Table(out.segment_time if strided and not out.at_segment_rows else out["time"])
    for path in paths:
        q = out[path]
        if q.ndim == 0 or q.shape[0] != len(table):
            raise ValueError(f"{out.path}: /{path.strip('/')} is not a time series")
        name = path.strip("/")
        cells = q.reshape(q.shape[0], -1)
        units = [u.strip() for u in q.units.split(",")]  # "N, N, N m": one per component
        for k, label in enumerate(_labels(out, path, q.shape[1:])):
            unit = units[k % len(units)] if len(units) > 1 and q.shape[-1] == len(units) else q.units
            table.add(name + label, cells[:, k], unit, q.description)
    return table
