"""The bearing's bodies as drawable shapes over time, for the ParaView exports (report_xdmf.py,
report_vtk.py).

From a run's .h5 (planar or spatial) at every stride-th sample:
- the rolling elements: one point per element at its centre, with its radius (`element_radius_m`,
  to draw it as a sphere or disc: ParaView's Glyph filter scaled by that array) and the normal force
  of its inner-race contacts (`inner_race_normal_force_N`, the columns of the element summed);
- the inner and outer ring: the race circle (spatial: the groove bottom at the nominal pitch radius
  -/+ D/2, the clearance not drawn; planar: the race radii of the model) in the ring's plane, centred
  on the ring's centre and tilted with it, and a radial mark that turns with the ring (its speed
  integrated over the samples: a ring's angle about its axis is no state of the models);
- the cage: the pitch circle in the cage's plane (its centre, tilt and angle) and one radial bar
  between each pair of pockets (pocket k at the cage angle + 2 pi k / Z, as in the models).
Every point carries `body` (0..Z-1 the rolling elements, Z the cage, Z+1 the inner ring, Z+2 the
outer ring). Planar runs lie in z = 0. Positions in m, time in s.
"""
import math
import re
from dataclasses import dataclass, field

import h5py
import numpy as np

CIRCLE_SEGMENTS = 64


class ExportInputError(Exception):
    """A file the exports cannot draw: names the file and what is missing."""


@dataclass
class Body:
    """One body over the samples: points [S x m x 3], polyline cells (lists of point indices, a
    one-point cell is a vertex), point data name -> [S x m]."""
    name: str
    points: np.ndarray
    cells: list
    point_data: dict = field(default_factory=dict)


@dataclass
class Bodies:
    h5_path: str
    kind: str                 # "planar" or "spatial"
    samples: np.ndarray       # row indices into the .h5's series
    times: np.ndarray         # [S] s
    bodies: list              # [elements, cage, inner_ring, outer_ring]


def _float(pattern, text, what, path):
    m = re.search(pattern, text)
    if not m:
        raise ExportInputError(f"{path}: the root attribute 'model' does not state {what}")
    return float(m.group(1))


def _text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def cardan_rotation(angles):
    """[S x 3] Cardan x-y-z angles -> [S x 3 x 3] rotations Rx(a) Ry(b) Rz(c), body to bearing frame
    (solver/bearing/model.cpp, cardan_rotation)."""
    a, b, c = (angles[:, k] for k in range(3))
    one, zero = np.ones_like(a), np.zeros_like(a)

    def stack(rows):
        return np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)
    rx = stack([[one, zero, zero], [zero, np.cos(a), -np.sin(a)], [zero, np.sin(a), np.cos(a)]])
    ry = stack([[np.cos(b), zero, np.sin(b)], [zero, one, zero], [-np.sin(b), zero, np.cos(b)]])
    rz = stack([[np.cos(c), -np.sin(c), zero], [np.sin(c), np.cos(c), zero], [zero, zero, one]])
    return rx @ ry @ rz


def _xyz(rows):
    """[S x k] positions (k = 2 planar, 3 spatial) as [S x 3]."""
    out = np.zeros((rows.shape[0], 3))
    out[:, :min(3, rows.shape[1])] = rows[:, :3]
    return out


def _turned(f, name, rows):
    """The angle about z a ring has turned through at the sample rows: its speed integrated over every
    sample from the first (trapezoid rule; a ring's angle about its axis is no state of the models)."""
    if f"{name}/angular_velocity" not in f:
        return np.zeros(len(rows))
    w = np.asarray(f[f"{name}/angular_velocity"][:rows[-1] + 1], dtype=float)
    w = w[:, 2] if w.ndim == 2 else w
    t = np.asarray(f["time"][:rows[-1] + 1], dtype=float)
    angle = np.concatenate([[0.0], np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(t))])
    return angle[rows]


def _pose(f, name, rows):
    """Centre [S x 3] and rotation [S x 3 x 3] of a ring or the cage at the sample rows: its tilt
    (spatial runs) and its angle about z (the cage's state; a ring's integrated speed)."""
    centre = _xyz(np.asarray(f[f"{name}/position"][rows], dtype=float))
    angles = np.zeros((len(rows), 3))
    # Layout 3 writes /X/angles in both kinds: [S x 3] (tilts, about z) spatial, [S] (about z)
    # planar; layout 2 wrote the planar cage's /cage/angle.
    tilts = np.asarray(f[f"{name}/angles"][rows], dtype=float) if f"{name}/angles" in f else None
    if tilts is not None and tilts.ndim == 2:
        angles[:, :2] = tilts[:, :2]
    if name == "cage":
        for path in ("cage/angles", "cage/angle"):
            if path in f:
                a = np.asarray(f[path][rows], dtype=float)
                angles[:, 2] = a[:, 2] if a.ndim == 2 else a
                break
    else:
        angles[:, 2] = _turned(f, name, rows)
    return centre, cardan_rotation(angles)


def _shape(centre, rotation, local, cells, name, body_id):
    """A shape given in the body's frame (local [m x 3]) placed at every sample."""
    points = centre[:, None, :] + np.einsum("sij,mj->smi", rotation, local)
    shape = (points.shape[0], points.shape[1])
    return Body(name, points, cells, {"body": np.full(shape, float(body_id)), "element_radius_m": np.zeros(shape),
                                      "inner_race_normal_force_N": np.zeros(shape)})


def _circle_with_marks(radius, marks):
    """The circle (CIRCLE_SEGMENTS points, one closed polyline) and radial marks [(angle, r0, r1)]
    (two points each, one segment)."""
    a = 2 * math.pi * np.arange(CIRCLE_SEGMENTS) / CIRCLE_SEGMENTS
    local = [np.column_stack([radius * np.cos(a), radius * np.sin(a), np.zeros_like(a)])]
    cells = [list(range(CIRCLE_SEGMENTS)) + [0]]
    for angle, r0, r1 in marks:
        base = CIRCLE_SEGMENTS + 2 * len(cells[1:])
        local.append(np.array([[r0 * math.cos(angle), r0 * math.sin(angle), 0.0],
                               [r1 * math.cos(angle), r1 * math.sin(angle), 0.0]]))
        cells.append([base, base + 1])
    return np.vstack(local), cells


def _element_loads(f, elements, count, rows):
    """[S x count] inner-race normal force per element (its columns summed), or zeros."""
    kind = "ball_inner_groove" if elements == "balls" else "roller_inner_race"
    load = np.zeros((len(rows), count))
    group = f.get(f"segments/{kind}")
    if group is None or "normal_force" not in group:
        return load
    if "element" in group or "ball" in group:  # layout 3 / 2
        owner = np.asarray(group["element" if "element" in group else "ball"][()], dtype=int)
    else:
        names = [_text(n) for n in group["names"][()]]
        owner = np.array([int(m.group(1)) if (m := re.match(r"roller\[(\d+)\]", n)) else -1 for n in names])
    force = np.asarray(group["normal_force"][rows], dtype=float)
    for column, k in enumerate(owner):
        if 0 <= k < count:
            load[:, k] += force[:, column]
    return load


def _check(f, h5_path):
    """The element series' name and the radii (element, pitch, inner and outer race) of the file,
    or ExportInputError naming what is missing."""
    elements = "balls" if "balls/position" in f else "rollers"
    for path in (f"{elements}/position", "cage/position", "inner_ring/position", "outer_ring/position", "time"):
        if path not in f:
            raise ExportInputError(f"{h5_path}: dataset '/{path}' is missing")
    spatial = _text(f.attrs.get("model_kind", "planar")) == "spatial"
    if "element_radius" in f.attrs and "pitch_radius" in f.attrs:  # layout 3: the bearing attributes
        element, pitch = float(f.attrs["element_radius"]), float(f.attrs["pitch_radius"])
        if spatial:
            return elements, (element, pitch, pitch - element, pitch + element)
        return elements, (element, pitch, float(f.attrs["inner_race_radius"]), float(f.attrs["outer_race_radius"]))
    # Earlier layouts: from the model's description.
    model = _text(f.attrs.get("model", ""))
    if spatial:
        element = 0.5e-3 * _float(r"D = ([0-9.eE+-]+) mm", model, "the ball diameter ('D = ... mm')", h5_path)
        pitch = float(f.attrs["pitch_radius"]) if "pitch_radius" in f.attrs else 0.5e-3 * _float(
            r"pitch diameter ([0-9.eE+-]+) mm", model, "the pitch diameter", h5_path)
        return elements, (element, pitch, pitch - element, pitch + element)
    race_in = 1e-3 * _float(r"races ([0-9.eE+-]+) /", model, "the race radii ('races R_i / R_o mm')", h5_path)
    race_out = 1e-3 * _float(r"races [0-9.eE+-]+ / ([0-9.eE+-]+) mm", model, "the race radii", h5_path)
    element = 1e-3 * _float(r"roller radius ([0-9.eE+-]+) mm", model, "the roller radius ('roller radius ... mm')",
                            h5_path)
    return elements, (element, 0.5 * (race_in + race_out), race_in, race_out)


def check_exportable(h5_path):
    """Raises ExportInputError (naming the file and what is missing) if the exports cannot draw the file."""
    with h5py.File(h5_path, "r") as f:
        _check(f, h5_path)


def read_bodies(h5_path, max_steps):
    """The bodies at every stride-th sample, the smallest stride giving at most max_steps samples."""
    with h5py.File(h5_path, "r") as f:
        elements, (element_radius, pitch, race_in, race_out) = _check(f, h5_path)
        # An interrupted run's series may stop at different samples: cut them to the shortest.
        inner_kind = "ball_inner_groove" if elements == "balls" else "roller_inner_race"
        series = [f"{elements}/position", "time", f"segments/{inner_kind}/normal_force"]
        series += [f"{body}/{name}" for body in ("cage", "inner_ring", "outer_ring")
                   for name in ("position", "angles", "angle", "angular_velocity")]
        # The segment diagnostics may be stored once every `every` samples ([output] segment_every):
        # the frames are at those samples.
        every = int(f["segments"].attrs.get("sample_stride", 1)) if "segments" in f else 1
        total = min(f[p].shape[0] * (every if p.startswith("segments/") else 1) for p in series if p in f)
        if total < 1:
            raise ExportInputError(f"{h5_path}: no samples")
        stride = every * max(1, -(-(-(-total // every)) // max_steps))
        rows = np.arange(0, total, stride)
        spatial = _text(f.attrs.get("model_kind", "planar")) == "spatial"
        centres = np.asarray(f[f"{elements}/position"][rows], dtype=float)
        count = centres.shape[1]
        points = np.zeros((len(rows), count, 3))
        points[:, :, :min(3, centres.shape[2])] = centres[:, :, :3]
        shape = (len(rows), count)
        element_body = Body(elements, points, [[k] for k in range(count)],
                            {"body": np.broadcast_to(np.arange(count, dtype=float), shape).copy(),
                             "element_radius_m": np.full(shape, element_radius),
                             "inner_race_normal_force_N": _element_loads(f, elements, count, rows // every)})
        bar = 0.8 * element_radius
        bars = [(2 * math.pi * (k + 0.5) / count, pitch - bar, pitch + bar) for k in range(count)]
        cage = _shape(*_pose(f, "cage", rows), *_circle_with_marks(pitch, bars), "cage", count)
        inner = _shape(*_pose(f, "inner_ring", rows), *_circle_with_marks(race_in, [(0.0, race_in - bar, race_in)]),
                       "inner_ring", count + 1)
        outer = _shape(*_pose(f, "outer_ring", rows), *_circle_with_marks(race_out, [(0.0, race_out, race_out + bar)]),
                       "outer_ring", count + 2)
        times = np.asarray(f["time"][rows], dtype=float)
    return Bodies(h5_path, "spatial" if spatial else "planar", rows, times, [element_body, cage, inner, outer])
