"""Spatial cylindrical roller bearings in `raceway report`: the slice loads along each roller (a heat
map against the roller's azimuth), the rib (flange) contacts, and the rollers' tilt and skew.

Read from the spatial layout (docs/output_layout.md, "Spatial roller-bearing runs"):
- /segments/roller_inner_slice, roller_outer_slice: one column per slice and roller (names
  `roller[k]/inner_race/slice[j]`, j from the roller's -z end), `element` the roller;
- /segments/roller_flange: one column per rib and roller (names `roller[k]/outer_rib_plus_z`);
- /rollers/angles [T x n x 2]: the Cardan angles (alpha about x, beta about y) of each roller's
  axis, axis = Rx(alpha) Ry(beta) e_z.

Tilt and skew (tilt_skew): the same Cardan decomposition in the roller's own frame (e_r, e_t, e_z)
at its azimuth psi (e_r = (cos psi, sin psi, 0), e_t = e_z x e_r): axis = R_er(skew) R_et(tilt) e_z,
so tilt = asin(axis . e_r) turns the axis in the radial plane (about e_t), skew = atan2(-axis . e_t,
axis . e_z) turns it about the radial direction. At psi = 0 they are beta and alpha.

Every mean is a trapezoid time mean over the report's window, except the azimuth bins (the mean of
the samples whose roller lies in the bin, as the report's other azimuth bins).
"""
import math
import re

import numpy as np

import report_metrics as rm

RACES = (("inner", "roller_inner_slice"), ("outer", "roller_outer_slice"))
MRAD = 1e3
DEG = 180.0 / math.pi


def applies(run):
    """Only spatial roller runs have a roller section."""
    return run.kind == "spatial" and run.element == "roller" and "roller_inner_slice" in run.contact


def _text(name):
    return name.decode() if isinstance(name, bytes) else str(name)


def _slice_of(kind, names):
    """The slice index of each column (from its name `.../slice[j]`)."""
    out = []
    for name in names:
        m = re.search(r"/slice\[(\d+)\]$", _text(name))
        if not m:
            raise ValueError(f"/segments/{kind}/names: '{_text(name)}' does not end in /slice[j]")
        out.append(int(m.group(1)))
    return np.asarray(out, dtype=int)


def slice_table(seg, kind, n, key="normal_force"):
    """The segment kind's `key` as [T x n x S]: roller, slice from the -z end."""
    j = _slice_of(kind, seg["names"])
    k = np.asarray(seg["element"], dtype=int)
    if (k < 0).any() or (k >= n).any():
        raise ValueError(f"/segments/{kind}/element holds an index outside 0 .. {n - 1}")
    values = np.asarray(seg[key], dtype=float)
    table = np.zeros((values.shape[0], n, int(j.max()) + 1))
    table[:, k, j] = values
    return table


def rib_series(seg, n):
    """Per rib of the design ({name: {"force", "power", "per_roller"}}): the force and power summed
    over the rollers [T], and each roller's force [T x n]."""
    names = [_text(x).split("/", 1)[-1] for x in seg["names"]]
    k = np.asarray(seg["element"], dtype=int)
    out = {}
    for rib in dict.fromkeys(names):
        cols = [c for c, name in enumerate(names) if name == rib]
        per_roller = np.zeros((seg["normal_force"].shape[0], n))
        per_roller[:, k[cols]] = seg["normal_force"][:, cols]
        power = np.sum(seg["power_loss"][:, cols], axis=1) if "power_loss" in seg else None
        out[rib] = {"force": np.sum(per_roller, axis=1), "power": power, "per_roller": per_roller}
    return out


def tilt_skew(angles, xy):
    """Tilt (about e_t, in the radial plane) and skew (about e_r) [rad] of each roller's axis from
    its Cardan angles about x, y [.. x 2] and its centre's x, y [.. x 2] (the azimuth)."""
    a, b = angles[..., 0], angles[..., 1]
    axis = np.stack([np.sin(b), -np.sin(a) * np.cos(b), np.cos(a) * np.cos(b)], axis=-1)
    psi = np.arctan2(xy[..., 1], xy[..., 0])
    radial = axis[..., 0] * np.cos(psi) + axis[..., 1] * np.sin(psi)
    tangential = -axis[..., 0] * np.sin(psi) + axis[..., 1] * np.cos(psi)
    return np.arcsin(np.clip(radial, -1.0, 1.0)), np.arctan2(-tangential, axis[..., 2])


def _parameter(p, key):
    v = p.get(key, {}).get("value")
    return v if isinstance(v, (int, float, str)) and not isinstance(v, bool) else None


def hertz_inputs(run, slices):
    """(slice width [m], E* [Pa]) for the slice pressures, from the run summary's resolved scene
    parameters (None where they are missing: no pressures)."""
    p = (run.life_input or {}).get("parameters", {})
    length, corner = run.geometry.get("roller_length"), _parameter(p, "bearing.corner_radius") or 0.0
    moduli = []
    for key in ("bearing.roller_material", "bearing.ring_material"):
        name = _parameter(p, key)
        e, nu = _parameter(p, f"materials.{name}.youngs_modulus"), _parameter(p, f"materials.{name}.poisson_ratio")
        if not isinstance(e, (int, float)) or not isinstance(nu, (int, float)):
            return None
        moduli.append((1.0 - nu * nu) / e)
    if not isinstance(length, (int, float)) or not math.isfinite(length):
        return None
    return (length + 2.0 * corner) / slices, 1.0 / sum(moduli)


def slice_pressure(run, race, load):
    """Hertz line-contact pressure of each slice [T x n x S], p0 = sqrt(q' E* / (pi R)) with q' the
    slice's load over its width (the roller's length with its corners, cut into equal slices) and R
    the reduced radius of roller and race: the slice's mean line load, so a pressure peak at a
    profile's edge narrower than a slice is smoothed over the slice. None without the inputs."""
    inputs = hertz_inputs(run, load.shape[2])
    r, race_radius = run.geometry.get("element_radius"), run.geometry.get(f"{race}_race_radius")
    if inputs is None or not r or not race_radius:
        return None
    width, e_star = inputs
    curvature = 1.0 / r + (1.0 / race_radius if race == "inner" else -1.0 / race_radius)
    return np.sqrt(np.maximum(load, 0.0) / width * e_star * curvature / math.pi)


def series(run):
    """The per-sample arrays of the roller section (the plots use them too)."""
    n = run.elements
    out = {"slices": {}, "ribs": {}, "azimuth": rm.azimuth(run.element_xy[..., 0], run.element_xy[..., 1])}
    for race, kind in RACES:
        seg = run.contact.get(kind)
        if seg is None:
            continue
        load = slice_table(seg, kind, n)
        out["slices"][race] = {"load": load, "pressure": slice_pressure(run, race, load)}
    if "roller_flange" in run.contact:
        out["ribs"] = rib_series(run.contact["roller_flange"], n)
    if run.roller_angles is not None:
        out["tilt"], out["skew"] = tilt_skew(run.roller_angles, run.element_xy)
    return out


def _race(run, w, bins, q, pressure, azimuth):
    """One race: the heat map's numbers."""
    slices = q.shape[2]
    mean = rm.time_mean(run.time, q, w)                       # [n x S]
    by_slice = np.sum(mean, axis=0)                           # [S]
    heat = [rm.bin_by_azimuth(azimuth[w.slice], q[w.slice, :, j], bins)["mean"] for j in range(slices)]
    qw = q[w.slice]
    i, k, j = np.unravel_index(int(np.argmax(qw)), qw.shape)
    total = float(np.sum(by_slice))
    centre = (np.arange(slices) + 0.5) / slices * 2.0 - 1.0   # slice centres, -1 .. 1 over the sliced length
    half = slices // 2  # the middle slice of an odd count counts half to each side
    minus = float(np.sum(by_slice[:half])) + (0.5 * float(by_slice[half]) if slices % 2 else 0.0)
    out = {"slices": slices,
           "load_mean_per_roller_slice_n": mean.tolist(),
           "load_by_slice_mean_n": by_slice.tolist(),
           "load_centre_offset": rm.ratio_or_nan(float(np.sum(by_slice * centre)), total),
           "minus_z_half_share": rm.ratio_or_nan(minus, total),
           "load_bin_mean_n": [list(h) for h in heat],
           "slice_load_peak_n": float(qw[i, k, j]), "slice_load_peak_roller": int(k), "slice_load_peak_slice": int(j),
           "slice_load_peak_azimuth_deg": float(azimuth[w.begin + i, k]) * DEG,
           "slice_load_peak_time_s": float(run.time[w.begin + i])}
    if pressure is not None:
        largest = np.max(np.where(q > 0, pressure, 0.0), axis=(1, 2))
        pw = pressure[w.slice]
        i, k, j = np.unravel_index(int(np.argmax(pw)), pw.shape)
        out.update({"max_pressure_largest_mean_pa": float(rm.time_mean(run.time, largest, w)),
                    "max_pressure_peak_pa": float(pw[i, k, j]), "max_pressure_peak_roller": int(k),
                    "max_pressure_peak_slice": int(j)})
    return out


def _ribs(run, w, ribs):
    out = {}
    for rib, r in ribs.items():
        pr = r["per_roller"][w.slice]
        entry = {"force_mean_n": float(rm.time_mean(run.time, r["force"], w)),
                 "force_peak_n": float(np.max(pr)) if pr.size else 0.0,
                 "contact_fraction": float(np.mean(pr > 0)) if pr.size else 0.0}
        if r["power"] is not None:
            entry["power_loss_mean_w"] = float(rm.time_mean(run.time, r["power"], w))
        out[rib] = entry
    return out


def _angle_stats(run, w, angle):
    a = angle[w.slice]
    per_roller = rm.time_mean(run.time, angle, w)
    return {"mean_mrad": float(np.mean(per_roller)) * MRAD,
            "rms_mrad": math.sqrt(float(np.mean(rm.time_mean(run.time, angle ** 2, w)))) * MRAD,
            "max_abs_mrad": float(np.max(np.abs(a))) * MRAD,
            "mean_per_roller_mrad": (per_roller * MRAD).tolist()}


def summarize_rollers(run, w, bins):
    """The summary's `rollers` section (None unless a spatial roller run)."""
    if not applies(run):
        return None
    s = series(run)
    centres = (np.arange(rm.bin_count(bins)) + 0.5) * bins
    out = {"window": {"start_s": w.t_begin, "end_s": w.t_end},
           "note": ("window means (trapezoid time means) unless a key says peak or max; slices numbered from the "
                    "roller's -z end; heat maps (load_bin_mean_n [slice][bin]) the mean of the samples whose roller "
                    "is in the azimuth bin (NaN: none); load_centre_offset: the load's centre along the roller, -1 at "
                    "the -z end, 0 the middle, +1 the +z end; minus_z_half_share: the -z half's share of the load "
                    "(0.5 when even); "
                    "max_pressure: Hertz line-contact pressure of the slice's mean line load (report_rollers.py)"),
           "bin_centre_deg": (centres * DEG).tolist(), "slices": {}}
    for race, t in s["slices"].items():
        out["slices"][race] = _race(run, w, bins, t["load"], t["pressure"], s["azimuth"])
    if s["ribs"]:
        out["ribs"] = _ribs(run, w, s["ribs"])
        out["ribs_note"] = "force and power summed over the rollers; force_peak_n one roller's largest"
    if "tilt" in s:
        out["tilt"] = _angle_stats(run, w, s["tilt"])
        out["skew"] = _angle_stats(run, w, s["skew"])
        out["tilt_skew_note"] = ("axis = R_er(skew) R_et(tilt) e_z at the roller's azimuth: tilt in the radial "
                                 "plane, skew about the radial direction; rms over rollers and the window")
    return out


def rows(summary):
    """The page's rows of the roller section."""
    r = summary.get("rollers")
    if not r:
        return []
    fmt = lambda v, scale=1.0, unit="": "-" if v is None or not math.isfinite(v) else f"{scale * v:.4g}{unit}"
    out = []
    for race, e in r["slices"].items():
        out.append((f"{race} race: largest slice load (peak; roller, slice from -z)",
                    f"{fmt(e['slice_load_peak_n'], unit=' N')} (roller {e['slice_load_peak_roller']}, slice "
                    f"{e['slice_load_peak_slice']} of {e['slices']})"))
        out.append((f"{race} race: load centre along the roller (-1 the -z end, +1 the +z end); -z half's share",
                    f"{fmt(e['load_centre_offset'])}; {fmt(e['minus_z_half_share'], 100.0, ' %')}"))
        if "max_pressure_largest_mean_pa" in e:
            out.append((f"{race} race: largest slice pressure (mean / peak)",
                        f"{fmt(e['max_pressure_largest_mean_pa'], 1e-9, ' GPa')} / "
                        f"{fmt(e['max_pressure_peak_pa'], 1e-9, ' GPa')}"))
    for rib, e in r.get("ribs", {}).items():
        out.append((f"rib {rib}: force (mean, all rollers / one roller's peak), power loss (mean)",
                    f"{fmt(e['force_mean_n'], unit=' N')} / {fmt(e['force_peak_n'], unit=' N')}, "
                    f"{fmt(e.get('power_loss_mean_w', math.nan), unit=' W')}"))
    for what in ("tilt", "skew"):
        if what in r:
            e = r[what]
            out.append((f"roller {what} (mean / rms / max |.|)", f"{fmt(e['mean_mrad'])} / {fmt(e['rms_mrad'])} / "
                                                                 f"{fmt(e['max_abs_mrad'])} mrad"))
    return out
