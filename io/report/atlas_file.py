"""The atlas file (docs/atlas.md, "The atlas file"): read, checked, in SI where the atlas needs it.

Every error is an AtlasFileError naming the file, the line, the key and the reason (`raceway atlas`
prints it and exits 2 before any point runs). Scene values (the parameters' ranges with their
units, `set`, the realisations) are checked again by the scene itself: atlas_runner runs
`raceway check` on the range's corners before any point, and names this file's line when the
scene refuses one.
"""
import math
import os
import re
import tomllib

import numpy as np

from cage_motion import CLASSES, THRESHOLDS

ATLAS_KEYS = {"name", "scene", "end_time", "settling_time", "window_cage_revolutions", "settling_cage_revolutions",
              "metric", "classes", "budget_points", "budget_core_hours", "batch_size", "set", "stop_band_share"}
REVOLUTION_KEYS = ("settling_cage_revolutions", "window_cage_revolutions")
CERTIFY_KEYS = {"blocks", "block_tolerance", "growth_tolerance", "convergence_sample", "convergence_rtol", "convergence_tolerance",
                "realisation_key", "realisations", "threshold_realisations", "ci_target"}
PARAMETER_KEYS = {"key", "name", "range", "unit", "scale"}
METRICS = ("cage_dynamics_indicator", "orbit_ratio", "vortex_radius_ratio", "sigma_v", "impact_rate",
           "whirl_to_cage_frequency")
TIME_UNITS = {"s": 1.0, "ms": 1e-3, "us": 1e-6}


class AtlasFileError(Exception):
    """A bad atlas file: str() is 'FILE:LINE: key 'KEY': REASON'."""


class _Lines:
    """Line numbers of the file's keys: 'atlas.end_time', 'parameter[1].range', 'thresholds.x'."""

    def __init__(self, text):
        self.lines = {}
        table, counts = "", {}
        for number, line in enumerate(text.splitlines(), start=1):
            s = line.strip()
            if m := re.match(r"^\[\[\s*([A-Za-z0-9_.]+)\s*\]\]", s):
                counts[m[1]] = counts.get(m[1], -1) + 1
                table = f"{m[1]}[{counts[m[1]]}]"
                self.lines.setdefault(table, number)
            elif m := re.match(r"^\[\s*([A-Za-z0-9_.]+)\s*\]", s):
                table = m[1]
                self.lines.setdefault(table, number)
            elif m := re.match(r'^"?([A-Za-z0-9_.\-]+)"?\s*=', s):
                self.lines.setdefault(f"{table}.{m[1]}" if table else m[1], number)

    def of(self, key):
        while key:
            if key in self.lines:
                return self.lines[key]
            key = key.rsplit(".", 1)[0] if "." in key else ""
        return 1


class _Checker:
    def __init__(self, path, text):
        self.path, self.lines = path, _Lines(text)

    def fail(self, key, reason):
        raise AtlasFileError(f"{self.path}:{self.lines.of(key)}: key '{key}': {reason}")

    def number(self, table, key, value, low=None, high=None, integer=False, low_open=False):
        name = f"{table}.{key}"
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            self.fail(name, f"must be a finite number, not {value!r}")
        if integer and not isinstance(value, int):
            self.fail(name, f"must be a whole number, not {value!r}")
        if low is not None and (value < low or (low_open and value == low)):
            self.fail(name, f"must be {'greater than' if low_open else 'at least'} {low}, not {value}")
        if high is not None and value > high:
            self.fail(name, f"must be at most {high}, not {value}")
        return value

    def time(self, table, key, value):
        m = re.fullmatch(r"\s*([0-9.eE+\-]+)\s*(s|ms|us)\s*", value) if isinstance(value, str) else None
        try:
            seconds = float(m[1]) * TIME_UNITS[m[2]] if m else math.nan
        except ValueError:
            seconds = math.nan
        if not (math.isfinite(seconds) and seconds > 0):
            self.fail(f"{table}.{key}",
                      f"must be a positive time with its unit (s, ms, us), e.g. \"20 ms\", not {value!r}")
        return seconds

    def unknown(self, table, values, known):
        for key in values:
            if key not in known:
                self.fail(f"{table}.{key}" if table else key, f"unknown key (known: {', '.join(sorted(known))})")


def _parameters(c, raw):
    if not isinstance(raw, list) or not raw:
        c.fail("parameter", "at least two [[parameter]] tables are needed (the atlas maps two or more parameters)")
    if len(raw) < 2:
        c.fail("parameter[0]", "at least two [[parameter]] tables are needed (the atlas maps two or more parameters)")
    params, names = [], set()
    for i, p in enumerate(raw):
        t = f"parameter[{i}]"
        c.unknown(t, p, PARAMETER_KEYS)
        key = p.get("key")
        if not isinstance(key, str) or not re.fullmatch(r"[a-z_]+(\.[a-z_]+)+", key):
            c.fail(f"{t}.key", f"must be a scene key such as \"inner_ring.speed\", not {key!r}")
        name = p.get("name", key.split(".")[-1] if key.count(".") == 1 else key.replace(".", "_"))
        if not isinstance(name, str) or not re.fullmatch(r"[A-Za-z][A-Za-z0-9_]*", name) or name in names:
            c.fail(f"{t}.name", f"must be a new column name (letters, digits, _), not {name!r}")
        if any(q["key"] == key for q in params):
            c.fail(f"{t}.key", f"'{key}' is given by two parameters")
        r = p.get("range")
        if not isinstance(r, list) or len(r) != 2:
            c.fail(f"{t}.range", f"must be [from, to], not {r!r}")
        low, high = (c.number(t, "range", v) for v in r)
        if not low < high:
            c.fail(f"{t}.range", f"from must be below to, not {r!r}")
        unit = p.get("unit")
        if not isinstance(unit, str) or not unit.strip():
            c.fail(f"{t}.unit", "must name the range's unit (the scene's units: rpm, N, um, ...)")
        names.add(name)
        params.append({"key": key, "name": name, "range": [float(low), float(high)], "unit": unit.strip()})
        scale = p.get("scale", "linear")
        if scale not in ("linear", "log"):
            c.fail(f"{t}.scale", f"must be \"linear\" or \"log\", not {scale!r}")
        if scale == "log":  # only then in the parameter (a linear one's identity is as it was)
            if not low > 0:
                c.fail(f"{t}.scale", f"a log scale needs a range above 0, not {r!r}")
            params[-1]["scale"] = "log"
    return params


def parameter_value(p, u):
    """The value of parameter `p` at `u` in [0, 1] of its axis: linear in its range, or with
    scale = "log" linear in the logarithm (equal ratios per step: where a parameter acts at its
    small values, a log axis gives them as much of the search as its large ones)."""
    return float(parameter_values(p, u))


def parameter_values(p, units):
    """parameter_value over an array of axis coordinates."""
    low, high = p["range"]
    u = np.asarray(units, dtype=float)
    return low * (high / low) ** u if p.get("scale") == "log" else low + u * (high - low)


def style_axis(ax, p, which):
    """A map's x or y axis (`which`) for parameter `p`: logarithmic where its scale is, its range
    with a margin of 3 % of the axis."""
    low, high = p["range"]
    if p.get("scale") == "log":
        getattr(ax, f"set_{which}scale")("log")
        f = (high / low) ** 0.03
        getattr(ax, f"set_{which}lim")(low / f, high * f)
    else:
        pad = 0.03 * (high - low)
        getattr(ax, f"set_{which}lim")(low - pad, high + pad)


def parameter_unit(p, value):
    """The inverse of parameter_value: the axis coordinate in [0, 1] of `value`."""
    low, high = p["range"]
    if p.get("scale") == "log":
        return math.log(float(value) / low) / math.log(high / low)
    return (float(value) - low) / (high - low)


def _certify(c, raw):
    if not isinstance(raw, dict):
        c.fail("certify", "must be a table")
    c.unknown("certify", raw, CERTIFY_KEYS)
    out = {"blocks": c.number("certify", "blocks", raw.get("blocks", 3), 2, 20, integer=True),
           "block_tolerance": c.number("certify", "block_tolerance", raw.get("block_tolerance", 0.05), 0,
                                       low_open=True),
           "growth_tolerance": c.number("certify", "growth_tolerance", raw.get("growth_tolerance", 0.25), 0,
                                        low_open=True),
           "convergence_sample": c.number("certify", "convergence_sample", raw.get("convergence_sample", 0.25), 0, 1),
           "convergence_rtol": c.number("certify", "convergence_rtol", raw.get("convergence_rtol", 1e-7), 0, 0.01,
                                        low_open=True),
           "convergence_tolerance": c.number("certify", "convergence_tolerance",
                                             raw.get("convergence_tolerance", 0.05), 0, low_open=True),
           "ci_target": c.number("certify", "ci_target", raw.get("ci_target", 0.05), 0, low_open=True)}
    key, values = raw.get("realisation_key"), raw.get("realisations", [])
    if not isinstance(values, list) or any(not isinstance(v, (str, int, float)) for v in values):
        c.fail("certify.realisations", "must be a list of the realisation key's values, e.g. [\"10 um\", \"20 um\"]")
    if values and (not isinstance(key, str) or "." not in key):
        c.fail("certify.realisation_key", f"must name the scene key the realisations set, not {key!r}")
    if len(values) == 1:
        c.fail("certify.realisations", "one realisation bounds no confidence interval: give none or at least two")
    if len(set(map(str, values))) != len(values):
        c.fail("certify.realisations", "a value is given twice")
    out["realisation_key"], out["realisations"] = key, [str(v) for v in values]
    more = raw.get("threshold_realisations", [])
    if not isinstance(more, list) or any(not isinstance(v, (str, int, float)) for v in more):
        c.fail("certify.threshold_realisations", "must be a list of the realisation key's values, e.g. [\"50 um\"]")
    if more and not values:
        c.fail("certify.threshold_realisations", "needs the realisations (realisation_key, realisations) they add to")
    if len(set(map(str, values + more))) != len(values) + len(more):
        c.fail("certify.threshold_realisations", "a value is given twice (here or in certify.realisations)")
    out["threshold_realisations"] = [str(v) for v in more]
    return out


def _window(c, raw):
    """The window: end_time and settling_time (every point), or settling_cage_revolutions and
    window_cage_revolutions (each point's times from its kinematic cage speed: atlas_models)."""
    given = [k for k in REVOLUTION_KEYS if k in raw]
    if not given:
        w = {"end_time_s": c.time("atlas", "end_time", raw.get("end_time")),
             "settling_time_s": c.time("atlas", "settling_time", raw.get("settling_time")),
             "settling_cage_revolutions": None, "window_cage_revolutions": None}
        if not w["settling_time_s"] < w["end_time_s"]:
            c.fail("atlas.settling_time", "must be shorter than end_time (the window is what follows it)")
        return w
    for key in REVOLUTION_KEYS:
        if key not in raw:
            c.fail(f"atlas.{given[0]}", f"needs {key} too (the window in cage revolutions needs both)")
    for key in ("end_time", "settling_time"):
        if key in raw:
            c.fail(f"atlas.{key}", "not with the window in cage revolutions: each point's end time follows "
                   "from its kinematic cage speed")
    return {"end_time_s": None, "settling_time_s": None,
            "settling_cage_revolutions": c.number("atlas", "settling_cage_revolutions",
                                                  raw["settling_cage_revolutions"], 0),
            "window_cage_revolutions": c.number("atlas", "window_cage_revolutions", raw["window_cage_revolutions"],
                                                0, low_open=True)}


def _atlas(c, raw, path):
    if not isinstance(raw, dict):
        c.fail("atlas", "the [atlas] table is missing")
    c.unknown("atlas", raw, ATLAS_KEYS)
    scene = raw.get("scene")
    if not isinstance(scene, str):
        c.fail("atlas.scene", "must name the base scene file (relative to this file)")
    scene = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(path)), scene))
    if not os.path.isfile(scene):
        c.fail("atlas.scene", f"no such file: {scene}")
    a = {"name": raw.get("name", os.path.splitext(os.path.basename(path))[0]), "scene": scene}
    a.update(_window(c, raw))
    a["metric"] = raw.get("metric", "cage_dynamics_indicator")
    if a["metric"] not in METRICS:
        c.fail("atlas.metric", f"must be one of {', '.join(METRICS)}, not {a['metric']!r}")
    classes = raw.get("classes", list(CLASSES))
    if not isinstance(classes, list) or len(classes) < 2 or any(k not in CLASSES for k in classes):
        c.fail("atlas.classes", f"must list two or more of {', '.join(CLASSES)}, not {classes!r}")
    a["classes"] = classes
    a["budget_points"] = c.number("atlas", "budget_points", raw.get("budget_points"), 1, 100000, integer=True)
    a["budget_core_hours"] = c.number("atlas", "budget_core_hours", raw.get("budget_core_hours", 1e9), 0,
                                      low_open=True)
    a["batch_size"] = c.number("atlas", "batch_size", raw.get("batch_size", 0), 0, 4096, integer=True)
    a["stop_band_share"] = c.number("atlas", "stop_band_share", raw.get("stop_band_share", 0.0), 0, 1)
    a["set"] = raw.get("set", {})
    if not isinstance(a["set"], dict) or any(not isinstance(v, (str, int, float, bool)) for v in a["set"].values()):
        c.fail("atlas.set", "must be a table of scene keys and values, e.g. { \"inner_ring.load.fy\" = \"0 N\" }")
    for reserved in ("scene.end_time", "solver.rtol"):
        if reserved in a["set"]:
            c.fail("atlas.set", f"'{reserved}' is set by the atlas itself (end_time, certify.convergence_rtol)")
    return a


def read_atlas_file(path):
    """The atlas file `path` as a dict (atlas keys, 'parameters', 'certify', 'thresholds')."""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as err:
        raise AtlasFileError(f"{path}:1: key 'atlas': cannot read the file: {err.strerror}") from err
    text = data.decode("utf-8", errors="replace")
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        line = re.search(r"line (\d+)", str(err))
        raise AtlasFileError(f"{path}:{line[1] if line else 1}: key '(syntax)': not TOML: {err}") from err
    c = _Checker(path, text)
    c.unknown("", {k: 1 for k in raw}, {"atlas", "parameter", "certify", "thresholds"})
    atlas = _atlas(c, raw.get("atlas"), path)
    atlas["parameters"] = _parameters(c, raw.get("parameter"))
    atlas["certify"] = _certify(c, raw.get("certify", {}))
    thresholds = raw.get("thresholds", {})
    c.unknown("thresholds", thresholds, set(THRESHOLDS))
    atlas["thresholds"] = {k: c.number("thresholds", k, v, 0) for k, v in thresholds.items()}
    for key in atlas["set"]:
        if any(p["key"] == key or p["key"].startswith(key + ".") or key.startswith(p["key"] + ".")
               for p in atlas["parameters"]):
            c.fail("atlas.set", f"'{key}' is also a parameter of the atlas")
    atlas["text"] = text
    atlas["lines"] = c.lines
    atlas["path"] = path
    return atlas
