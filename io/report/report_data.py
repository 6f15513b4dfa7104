"""One run's series as `raceway report` uses them, for planar (roller) and spatial (ball) bearings.

Reads through raceway_output.py (docs/output_layout.md) and puts both kinds into one shape: the
cage's speed about the bearing axis and its kinematic references, the cage centre, the rolling
elements' positions and inner-race loads, the pocket forces split onto the front and rear bar (front:
the bar ahead in the cage's sense of rotation), the cage-land force, the driven ring's contact moment
and the per-contact diagnostics (pressure, film, contact angle) where the kind has them.

A file that cannot be used raises ReportInputError naming the file and the dataset.
"""
import math
import re
from dataclasses import dataclass, field

import numpy as np

from raceway_output import RacewayOutput
from report_bridges import bridge_forces
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
    geometry: dict = field(default_factory=dict)     # pitch_radius, clearances, radii (m)
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


def _pocket_steps(out, run):
    """/cage/pocket_step_* [T x n x 2] (side 0: the bar ahead in +z) onto the report's front and rear
    bars (front: ahead in the cage's sense of rotation)."""
    if not all(f"cage/pocket_step_{q}" in out for q in POCKET_STEP_QUANTITIES):
        return
    front, rear = (0, 1) if run.direction > 0 else (1, 0)
    data = {q: _need(out, f"cage/pocket_step_{q}") for q in POCKET_STEP_QUANTITIES}
    run.pocket_steps = {bar: {q: v[:, :, side] for q, v in data.items()} for bar, side in (("front", front),
                                                                                         ("rear", rear))}


def _scene_name(out):
    m = re.search(r"^\s*name\s*=\s*\"([^\"]*)\"", out.scene_text, re.M)
    return m.group(1) if m else out.attrs.get("scene_source", out.path)


def _sum_power(out, run):
    for kind in out.segment_kinds():
        if f"segments/{kind}/power_loss" in out:
            run.power_loss[kind] = np.sum(np.asarray(out[f"segments/{kind}/power_loss"], dtype=float), axis=1)


def _driven(out, run, ring_moment_column):
    """The driven ring: the one that turns (the larger mean |speed|); its net contact moment."""
    best = None
    for ring in ("inner_ring", "outer_ring"):
        w = out[f"{ring}/angular_velocity"] if f"{ring}/angular_velocity" in out else None
        if w is None:
            continue
        wz = np.asarray(w, dtype=float)
        wz = wz[:, 2] if wz.ndim == 2 else wz
        if best is None or abs(np.mean(wz)) > abs(np.mean(best[1])):
            best = (ring, wz)
    if best is None or abs(np.mean(best[1])) == 0 or f"{best[0]}/force" not in out:
        return
    run.driven_speed = best[1]
    run.driven_moment = np.asarray(out[f"{best[0]}/force"], dtype=float)[:, ring_moment_column]
    run.geometry["driven_ring"] = best[0]


def _planar_races(out):
    """Race radii from the model description ("races 18.2700 / 27.4700 mm")."""
    m = re.search(r"races ([0-9.eE+-]+) / ([0-9.eE+-]+) mm", out.attrs.get("model", ""))
    if not m:
        raise ReportInputError(f"{out.path}: the root attribute 'model' does not state the race radii "
                               "('races R_i / R_o mm'), needed for the kinematic cage speed")
    return 1e-3 * float(m.group(1)), 1e-3 * float(m.group(2))


def read_planar(out):
    t = _need(out, "time")
    cage_w = _need(out, "cage/angular_velocity")
    r_in, r_out = _planar_races(out)
    w_in, w_out = _need(out, "inner_ring/angular_velocity"), _need(out, "outer_ring/angular_velocity")
    # Line contact at 0 deg: the cage turns with the rollers' centres, rolling without slip on both
    # races: omega_c = (omega_i r_i + omega_o r_o) / (r_i + r_o).
    epi = (w_in * r_in + w_out * r_out) / (r_in + r_out)
    pos = _need(out, "rollers/position")
    load = _need(out, "segments/roller_inner_race/normal_force")
    run = BearingRun(out.path, "planar", "roller", _scene_name(out), t, cage_w, epi, epi,
                     _need(out, "cage/position")[:, :2], _need(out, "cage/velocity")[:, :2],
                     _need(out, "cage/angle"), pos, load)
    run.geometry.update({"inner_race_radius": r_in, "outer_race_radius": r_out, "pitch_radius": 0.5 * (r_in + r_out)})
    m = re.search(r"pocket clearance ([0-9.eE+-]+) mm", out.attrs.get("model", ""))
    run.geometry["pocket_clearance"] = 1e-3 * float(m.group(1)) if m else math.nan
    m = re.search(r"land \(radius [0-9.eE+-]+ mm, clearance ([0-9.eE+-]+) mm\)", out.attrs.get("model", ""))
    run.geometry["land_clearance"] = 1e-3 * float(m.group(1)) if m else 0.0
    if "segments/cage_bar_front" in out:
        front, rear = _need(out, "segments/cage_bar_front/normal_force"), _need(out, "segments/cage_bar_rear/normal_force")
        # The file's front is ahead in +z; the report's front is ahead in the cage's sense of rotation.
        run.bar_front, run.bar_rear = (front, rear) if run.direction > 0 else (rear, front)
    if "segments/cage_land/normal_force" in out:
        run.land_force = np.sum(_need(out, "segments/cage_land/normal_force"), axis=1)
    run.bridge_force, run.bridges_flexible = bridge_forces(out)
    _pocket_steps(out, run)
    _driven(out, run, 2)
    _sum_power(out, run)
    return run


def read_spatial(out):
    t = _need(out, "time")
    n = int(out.attrs.get("ball_count", 0))
    pos = _need(out, "balls/position")
    if n == 0:
        n = pos.shape[1]
    run = BearingRun(out.path, "spatial", "ball", _scene_name(out), t, _need(out, "cage/angular_velocity")[:, 2],
                     _need(out, "cage/epicyclic_speed"),
                     _need(out, "cage/rolling_speed") if "cage/rolling_speed" in out else None,
                     _need(out, "cage/position")[:, :2], _need(out, "cage/velocity")[:, :2],
                     _need(out, "cage/angles")[:, 2] if "cage/angles" in out else np.zeros_like(t), pos[:, :, :2], None)
    if run.rolling_speed is None:
        run.notes.append("no /cage/rolling_speed (a file written before it existed): slip against the nominal "
                         "contact angle only")
    for key in ("pitch_radius", "pocket_clearance", "land_clearance"):
        run.geometry[key] = float(out.attrs.get(key, math.nan))
    for kind in out.segment_kinds():
        seg = {"names": out[f"segments/{kind}/names"]}
        for name in out.file[f"segments/{kind}"].keys():
            if name != "names":
                seg[name] = _need(out, f"segments/{kind}/{name}")
        seg["element"] = seg.pop("ball", np.full(len(seg["names"]), -1.0)).astype(int)
        run.contact[kind] = seg
    if "ball_inner_groove" not in run.contact:
        raise ReportInputError(f"{out.path}: dataset '/segments/ball_inner_groove/normal_force' is missing")
    groove = run.contact["ball_inner_groove"]
    if (groove["element"] < 0).any() or (groove["element"] >= n).any():
        raise ReportInputError(f"{out.path}: '/segments/ball_inner_groove/ball' holds an index outside 0 .. {n - 1}")
    run.element_load = element_loads(groove["normal_force"], groove["element"], n)
    if "ball_pocket" in run.contact:
        pocket = run.contact["ball_pocket"]
        for key in ("normal_force", "circumferential_force"):
            if key not in pocket:
                raise ReportInputError(f"{out.path}: dataset '/segments/ball_pocket/{key}' is missing")
        run.bar_front, run.bar_rear = split_bar_forces(pocket["normal_force"], pocket["circumferential_force"],
                                                       pocket["element"], n, run.direction)
        run.pocket_circumferential = element_loads(pocket["circumferential_force"], pocket["element"], n)
    if "cage_land" in run.contact:
        run.land_force = np.sum(run.contact["cage_land"]["normal_force"], axis=1)
    _pocket_steps(out, run)
    _driven(out, run, 5)
    _sum_power(out, run)
    return run


def read_run(path):
    """The run in `path` (an output file or an interrupted run's .partial)."""
    try:
        out = RacewayOutput(path)
    except FileNotFoundError:
        raise ReportInputError(f"{path}: no such file") from None
    except OSError as err:
        raise ReportInputError(f"{path}: not an HDF5 file ({err})") from None
    with out:
        kind = out.attrs.get("model_kind", "planar")
        run = read_spatial(out) if kind == "spatial" else read_planar(out)
        if out.rows < out.file["time"].shape[0]:
            run.notes.append(f"series cut to their shortest length, {out.rows} samples (an interrupted run)")
        run.build = out.build
        run.scene_text = out.scene_text
    return run
