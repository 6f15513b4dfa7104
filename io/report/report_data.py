"""One run's series as `raceway report` uses them, for planar (roller) and spatial (ball) bearings.

Reads through the raceway package (docs/output_layout.md: one set of dataset names for both kinds,
the bearing's geometry in root attributes; never the model's prose) into one shape: the
cage's speed about the bearing axis and its kinematic references, the cage centre, the rolling
elements' positions and inner-race loads, the pocket forces split onto the front and rear bar (front:
the bar ahead in the cage's sense of rotation), the cage-land force, the driven ring's contact moment
and the per-contact diagnostics (pressure, film, contact angle) where the kind has them.

A file that cannot be used raises ReportInputError naming the file and the dataset.
"""
import math
from dataclasses import dataclass, field

import numpy as np

from raceway import RacewayOutput
from report_bridges import bridge_forces
from report_life import read_life_input
from report_power import read_power, read_thermal
from report_metrics import cage_direction, element_loads, split_bar_forces


class ReportInputError(Exception):
    """The input file cannot be used for a report (exit code 2)."""


@dataclass
class BearingRun:
    path: str
    kind: str                      # "planar" or "spatial"
    element: str                   # "roller" or "ball"
    scene_name: str
    time: np.ndarray               # [T] s
    cage_speed: np.ndarray         # [T] rad/s about z
    epicyclic_speed: np.ndarray    # [T] rad/s at the nominal contact angle
    rolling_speed: np.ndarray      # [T] rad/s at the loaded contact angle (None: not in the file)
    cage_xy: np.ndarray            # [T x 2] m
    cage_vxy: np.ndarray           # [T x 2] m/s
    cage_angle: np.ndarray         # [T] rad
    element_xy: np.ndarray         # [T x n x 2] m
    element_load: np.ndarray       # [T x n] N, inner race / groove (arcs added)
    bar_front: np.ndarray = None   # [T x n] N
    bar_rear: np.ndarray = None    # [T x n] N
    pocket_circumferential: np.ndarray = None  # [T x n] N (spatial)
    # The step-resolved pocket statistics (/cage/pocket_step_*, docs/output_layout.md), per output
    # interval ending at each sample, by bar: {"front"|"rear": {"onsets"|"peak_force"|"impulse"|
    # "contact_time": [T x n]}}; None when the file has none (written before them).
    pocket_steps: dict = None
    land_force: np.ndarray = None  # [T] N
    bridge_force: np.ndarray = None  # [T x n] N, signed (report_bridges.py)
    bridges_flexible: bool = False   # /segments/cage_bridge present
    driven_moment: np.ndarray = None  # [T] N m, net moment about z on the driven ring
    driven_speed: np.ndarray = None   # [T] rad/s
    contact: dict = field(default_factory=dict)  # kind -> {names, element, normal_force, ...} (spatial)
    power_loss: dict = field(default_factory=dict)  # segment kind -> [T] W (sum over its segments)
    power_balance: dict = None  # /power_balance/* (report_power.read_power), None in older files
    thermal: dict = None  # /thermal/* (report_power.read_thermal), None without a thermal network
    geometry: dict = field(default_factory=dict)     # pitch_radius, clearances, radii (m)
    roller_angles: np.ndarray = None  # [T x n x 2] rad, spatial rollers' Cardan angles (report_rollers.py)
    life_input: dict = None  # what the rating lives need (report_life.read_life_input)
    notes: list = field(default_factory=list)
    build: dict = field(default_factory=dict)
    scene_text: str = ""

    @property
    def elements(self):
        return self.element_xy.shape[1]

    @property
    def direction(self):
        return cage_direction(float(np.mean(self.cage_speed[len(self.cage_speed) // 2:])))


def _need(out, path):
    if path.strip("/") not in out:
        raise ReportInputError(f"{out.path}: dataset '/{path.strip('/')}' is missing")
    values = out[path]
    return np.asarray(values, dtype=float)


POCKET_STEP_QUANTITIES = ("onsets", "peak_force", "impulse", "contact_time")


def coarse_intervals(values, stride, rows, peak):
    """Per-interval statistics [T x ...] (row i: the output interval ending at sample i) onto the
    intervals between every stride-th sample: row j covers samples (j - 1) stride + 1 .. j stride
    (row 0 is sample 0's), `rows` rows; the largest value of them if `peak`, else their sum."""
    values = np.asarray(values, dtype=float)[:(rows - 1) * stride + 1]
    starts = np.concatenate([[0], 1 + stride * np.arange(rows - 1)]).astype(int)
    return (np.maximum if peak else np.add).reduceat(values, starts, axis=0)


def _step_rows(out, q):
    """One pocket statistic at the rows the report reads: at the segment rows (a file read there) the
    sum or largest value of the intervals between them, so that no step's contact is left out."""
    if not out.at_segment_rows:
        return _need(out, f"cage/pocket_step_{q}")
    every = np.asarray(out.dataset(f"cage/pocket_step_{q}")[:out.rows], dtype=float)
    return coarse_intervals(every, out.segment_stride, out.segment_rows, q == "peak_force")


def _pocket_steps(out, run):
    """/cage/pocket_step_* [T x n x 2] (side 0: the bar ahead in +z) onto the report's front and rear
    bars (front: ahead in the cage's sense of rotation)."""
    if not all(f"cage/pocket_step_{q}" in out for q in POCKET_STEP_QUANTITIES):
        return
    front, rear = (0, 1) if run.direction > 0 else (1, 0)
    data = {q: _step_rows(out, q) for q in POCKET_STEP_QUANTITIES}
    run.pocket_steps = {bar: {q: v[:, :, side] for q, v in data.items()} for bar, side in (("front", front),
                                                                                         ("rear", rear))}


def _sum_power(out, run):
    for kind in out.segment_kinds():
        if f"segments/{kind}/power_loss" in out:
            run.power_loss[kind] = np.sum(np.asarray(out[f"segments/{kind}/power_loss"], dtype=float), axis=1)


def _driven(out, run):
    """The driven ring: the one that turns (the larger mean |speed|); its net contact moment about z."""
    best = None
    for ring in ("inner_ring", "outer_ring"):
        if f"{ring}/angular_velocity" not in out:
            continue
        wz = np.asarray(out.component(f"{ring}/angular_velocity", "about z"), dtype=float)
        if best is None or abs(np.mean(wz)) > abs(np.mean(best[1])):
            best = (ring, wz)
    if best is None or abs(np.mean(best[1])) == 0 or f"{best[0]}/force" not in out:
        return
    run.driven_speed = best[1]
    run.driven_moment = np.asarray(out.component(f"{best[0]}/force", "about z"), dtype=float)
    run.geometry["driven_ring"] = best[0]


def _columns_element(out, kind, count):
    """The rolling element of each column of /segments/<kind> (its `element` dataset; in files of
    layout version 2 planar groups have none: one column per roller, in order)."""
    path = f"segments/{kind}/element"
    element = np.asarray(out[path], dtype=float).astype(int) if path in out else np.arange(count)
    if (element < 0).any() or (element >= count).any():
        raise ReportInputError(f"{out.path}: '/{path}' holds an index outside 0 .. {count - 1}")
    return element


def _contacts(out, run, n):
    """Spatial: every diagnostic of every segment kind, with the ball of each column."""
    for kind in out.segment_kinds():
        seg = {"names": out[f"segments/{kind}/names"]}
        for name, values in out.segments(kind).items():
            if name not in ("names", "element"):
                seg[name] = np.asarray(values, dtype=float)
        seg["element"] = np.asarray(out[f"segments/{kind}/element"], dtype=float).astype(int) \
            if f"segments/{kind}/element" in out else np.full(len(seg["names"]), -1)
        run.contact[kind] = seg


def _bars(out, run, n):
    """The pocket forces on the front and rear bars (front: ahead in the cage's sense of rotation)."""
    if "segments/cage_bar_front/normal_force" in out:  # roller pockets: one segment per bar
        front, rear = _need(out, "segments/cage_bar_front/normal_force"), _need(out, "segments/cage_bar_rear/normal_force")
        # The file's front is ahead in +z; the report's front is ahead in the cage's sense of rotation.
        run.bar_front, run.bar_rear = (front, rear) if run.direction > 0 else (rear, front)
    elif "segments/ball_pocket/normal_force" in out:  # ball pockets: the side from the force's sense
        if "segments/ball_pocket/circumferential_force" not in out:
            raise ReportInputError(f"{out.path}: dataset '/segments/ball_pocket/circumferential_force' is missing")
        element = _columns_element(out, "ball_pocket", n)
        fn, fc = _need(out, "segments/ball_pocket/normal_force"), _need(out, "segments/ball_pocket/circumferential_force")
        run.bar_front, run.bar_rear = split_bar_forces(fn, fc, element, n, run.direction)
        run.pocket_circumferential = element_loads(fc, element, n)


def read_bearing(out):
    """One reading for planar and spatial files (the same dataset names, layout version 3; older
    files through the reader's names): a BearingRun."""
    kind = out.model_kind
    group = out.element_group
    t = _need(out, "time")
    pos = _need(out, f"{group}/position")
    n = pos.shape[1]
    for path in ("cage/angular_velocity", "cage/epicyclic_speed", "cage/position", "cage/velocity"):
        _need(out, path)
    rolling = _need(out, "cage/rolling_speed") if "cage/rolling_speed" in out else None
    angle = np.asarray(out.component("cage/angles", "about z"), dtype=float) if "cage/angles" in out \
        else np.zeros_like(t)
    run = BearingRun(out.path, kind, "ball" if group == "balls" else "roller", out.scene_name, t,
                     np.asarray(out.component("cage/angular_velocity", "about z"), dtype=float),
                     _need(out, "cage/epicyclic_speed"), rolling,
                     _need(out, "cage/position")[:, :2], _need(out, "cage/velocity")[:, :2], angle, pos[:, :, :2], None)
    if rolling is None:
        run.notes.append("no /cage/rolling_speed (a file written before it existed): slip against the nominal "
                         "contact angle only")
    run.geometry.update({k: v for k, v in out.bearing.items() if isinstance(v, (int, float))})
    for key in ("pitch_radius", "pocket_clearance", "land_clearance"):
        run.geometry.setdefault(key, math.nan)
    # A rolling element's load: its inner contacts added (a spatial roller's slices, a four-point
    # ball's two arcs).
    groove = ("ball_inner_groove" if group == "balls" else
              "roller_inner_slice" if kind == "spatial" else "roller_inner_race")
    if f"segments/{groove}/normal_force" not in out:
        raise ReportInputError(f"{out.path}: dataset '/segments/{groove}/normal_force' is missing")
    run.element_load = element_loads(_need(out, f"segments/{groove}/normal_force"), _columns_element(out, groove, n), n)
    if kind == "spatial":
        _contacts(out, run, n)
        if group == "rollers" and "rollers/angles" in out:
            run.roller_angles = _need(out, "rollers/angles")
    _bars(out, run, n)
    if "segments/cage_land/normal_force" in out:
        run.land_force = np.sum(_need(out, "segments/cage_land/normal_force"), axis=1)
    if kind == "planar":
        run.bridge_force, run.bridges_flexible = bridge_forces(out)
    _pocket_steps(out, run)
    _driven(out, run)
    _sum_power(out, run)
    run.power_balance = read_power(out)
    run.thermal = read_thermal(out)
    run.life_input = read_life_input(out, n)
    return run


def read_run(path):
    """The run in `path` (an output file or an interrupted run's .partial)."""
    try:
        out = RacewayOutput(path, at_segment_rows=True)  # every series at the segment diagnostics' samples
    except FileNotFoundError:
        raise ReportInputError(f"{path}: no such file") from None
    except OSError as err:
        raise ReportInputError(f"{path}: not an HDF5 file ({err})") from None
    with out:
        run = read_bearing(out)
        if out.rows < out.file["time"].shape[0]:
            run.notes.append(f"series cut to their shortest length, {out.rows} samples (an interrupted run)")
        if out.at_segment_rows:
            run.notes.append(f"the segment diagnostics are stored once every {out.segment_stride} samples ([output] "
                             f"segment_every): the report reads every series there, {out.segment_rows} of "
                             f"{out.rows} samples")
        run.build = out.build
        run.scene_text = out.scene_text
    return run
