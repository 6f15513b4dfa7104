#!/usr/bin/env python3
"""Seed 003's bearing with a rigid and a flexible outer ring: the three quantities of seed 003 3.2.

    seed003_flexible_ring_compare.py RIGID.h5 FLEXIBLE.h5 [--window-start S] [--figure OUT.png] [--label TEXT]

Prints one markdown table row per file (docs/planetary.md, "Flexible outer ring"):
  - loaded zone: the azimuth range (5 deg bins, bearing frame) where the window's time mean of the
    inner-race roller load exceeds 1 % (and 10 %) of the largest bin mean: where the rollers are
    pinched between the rings (the report's definition, io/report/report_metrics.py load_zone);
  - peak roller load: the mean over the gear revolutions in the window of each revolution's largest
    inner-race (and outer-race) roller load;
  - impacts: a rise of a roller's force on one bar of its pocket above 500 N (re-armed when it falls
    below 250 N): the sustained pocket forces under the carrier's field are 150-300 N, seed 003's
    impacts some kN. Counted per roller and cage revolution (relative to the bearing frame, in the
    window), front and rear bars apart, and by the roller's azimuth at the peak.
  - the rim's radial deflection at the rollers (flexible ring): the rigid ring's approach from the
    positions less the stored approach.
"""
import argparse
import math
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "io", "report"))
import report_metrics as rm  # noqa: E402

DEG = 180.0 / math.pi
IMPACT_N = 500.0  # N; re-armed below half of it


def impacts(force, azimuth, window, level=IMPACT_N):
    """[(index, roller, peak N, azimuth rad)] of the rises above `level` (re-armed below half of it)
    inside the window."""
    out = []
    for k in range(force.shape[1]):
        armed, start = True, None
        for i in range(window.begin, window.begin + window.samples):
            v = force[i, k]
            if armed and v > level:
                armed, start = False, i
            elif not armed and v < 0.5 * level:
                j = start + int(np.argmax(force[start:i, k]))
                out.append((j, k, float(force[j, k]), float(azimuth[j, k])))
                armed = True
    return out


def per_revolution_peak(time, load, window, period):
    t = time[window.slice]
    q = np.max(load[window.slice], axis=1)
    peaks = [q[(t >= a) & (t < a + period)].max() for a in np.arange(t[0], t[-1] - period + 1e-12, period)]
    return float(np.mean(peaks)), len(peaks)


def analyse(path, window_start):
    f = h5py.File(path, "r")
    time = f["time"][:]
    w = rm.select_window(time, window_start)
    xy = f["rollers/position"][:] - f["outer_ring/position"][:][:, None, :]
    az = rm.azimuth(xy[..., 0], xy[..., 1])
    if int(f["segments"].attrs.get("sample_stride", 1)) != 1:
        raise SystemExit(f"{path}: the segment diagnostics are stored once every few samples ([output] "
                         "segment_every); this comparison needs them at every sample")
    inner = f["segments/roller_inner_race/normal_force"][:]
    outer = f["segments/roller_outer_race/normal_force"][:]
    bins = rm.bin_by_azimuth(az[w.slice], inner[w.slice], 5.0 / DEG)
    peak_bin = float(np.nanmax(bins["mean"]))
    zone = {p: rm.load_zone(bins, p * peak_bin) for p in (0.01, 0.10)}
    gear = abs(float(np.mean(f["outer_ring/angular_velocity"][w.slice])))
    period = 2 * math.pi / gear
    cage = f["cage/angles" if "cage/angles" in f else "cage/angle"][:]  # layout 3 / layout 2
    cage_revs = abs(cage[w.begin + w.samples - 1] - cage[w.begin]) / (2 * math.pi)
    z = inner.shape[1]
    r = {"file": os.path.basename(path), "window": (time[w.begin], time[w.begin + w.samples - 1]),
         "zone_1": zone[0.01]["width"] * DEG, "zone_10": zone[0.10]["width"] * DEG,
         "zone_centre": zone[0.01]["centre"] * DEG,
         "peak_inner": per_revolution_peak(time, inner, w, period), "peak_outer": per_revolution_peak(time, outer, w, period),
         "cage_revs": cage_revs, "bins": bins, "outer_bins": rm.bin_by_azimuth(az[w.slice], outer[w.slice], 5.0 / DEG)}
    for bar in ("front", "rear"):
        ev = impacts(f[f"segments/cage_bar_{bar}/normal_force"][:], az, w)
        r[bar] = ev
        r[bar + "_rate"] = len(ev) / (z * cage_revs)
        r[bar + "_strong_rate"] = len(impacts(f[f"segments/cage_bar_{bar}/normal_force"][:], az, w, 2 * IMPACT_N)) / (
            z * cage_revs)
    # The rim's radial deflection at each roller: rigid-ring approach less the stored one.
    if "segments/outer_ring_mode/approach" in f:
        race = rigid_race_radius(f)
        d = np.hypot(xy[..., 0], xy[..., 1])
        rigid = d + roller_radius(f) - race
        r["rim"] = rm.bin_by_azimuth(az[w.slice], (rigid - f["segments/roller_outer_race/approach"][:])[w.slice], 5.0 / DEG)
    return r


def scene_text(f):
    for key in ("scene_text",):
        if key in f.attrs:
            v = f.attrs[key]
            return v.decode() if isinstance(v, bytes) else str(v)
    raise KeyError("no scene text in the file")


def _length(text, key):
    import re
    m = re.search(rf'^{key}\s*=\s*"([0-9.eE+-]+)\s*(mm|um)"', text, re.M)
    return float(m.group(1)) * (1e-3 if m.group(2) == "mm" else 1e-6)


def roller_radius(f):
    return 0.5 * _length(scene_text(f), "roller_diameter")


def rigid_race_radius(f):
    t = scene_text(f)
    return 0.5 * (_length(t, "pitch_diameter") + _length(t, "roller_diameter") + 0.5 * _length(t, "radial_clearance"))


def sectors(events, zone_start, zone_end):
    """Counts of events inside the loaded zone and outside it."""
    inside = 0
    for _, _, _, a in events:
        if (zone_start <= zone_end and zone_start <= a <= zone_end) or (zone_start > zone_end and (a >= zone_start or a <= zone_end)):
            inside += 1
    return inside, len(events) - inside


def row(r, label):
    fi, fo = r["peak_inner"], r["peak_outer"]
    fp = max([e[2] for e in r["front"]], default=0.0)
    rp = max([e[2] for e in r["rear"]], default=0.0)
    fm = np.median([e[2] for e in r["front"]]) if r["front"] else 0.0
    rmed = np.median([e[2] for e in r["rear"]]) if r["rear"] else 0.0
    return (f"| {label} | {r['zone_1']:.0f} ({r['zone_10']:.0f}) | {r['zone_centre']:.0f} | {fi[0]:.0f} ({fo[0]:.0f}) | "
            f"{r['front_rate']:.2f} / {r['rear_rate']:.2f} | {fm:.0f} / {rmed:.0f} | {fp:.0f} / {rp:.0f} | "
            f"{fi[1]} revs, {r['cage_revs']:.2f} cage revs |")


def figure(results, labels, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(3, 1, figsize=(11, 11), sharex=True)
    for r, label, colour in zip(results, labels, ("tab:blue", "tab:orange")):
        c = r["bins"]["centre"] * DEG
        axes[0].plot(c, r["bins"]["mean"], "o-", ms=2, color=colour, label=f"{label}: inner race")
        axes[0].plot(c, r["outer_bins"]["mean"], "--", color=colour, label=f"{label}: outer race")
        for bar, marker in (("front", "^"), ("rear", "v")):
            ev = r[bar]
            axes[1].plot([e[3] * DEG for e in ev], [e[2] for e in ev], marker, ls="none", color=colour, ms=5,
                         label=f"{label}: {bar} bar ({r[bar + '_rate']:.2f} per roller and revolution)")
        if "rim" in r:
            axes[2].plot(c, 1e6 * r["rim"]["mean"], "o-", ms=2, color=colour, label=f"{label}: time mean")
            axes[2].fill_between(c, 1e6 * r["rim"]["min"], 1e6 * r["rim"]["max"], color=colour, alpha=0.2)
    axes[0].set_ylabel("roller load [N] (time mean per 5 deg bin)")
    axes[1].set_ylabel(f"pocket impact peak [N] (> {IMPACT_N:.0f} N)")
    axes[1].set_yscale("log")
    axes[2].set_ylabel("rim's radial deflection at the roller [um] (+: outward)")
    axes[2].set_xlabel("azimuth of the roller about the outer ring's centre [deg] (bearing frame, 0 = +x = away from the sun)")
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    axes[2].set_xlim(0, 360)
    axes[2].set_xticks(range(0, 361, 30))
    fig.suptitle("seed 003 planet bearing: rigid and flexible outer ring (window of the runs)")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("rigid")
    p.add_argument("flexible")
    p.add_argument("--window-start", type=float, default=None)
    p.add_argument("--figure", default=None)
    p.add_argument("--label", default="")
    a = p.parse_args()
    res = [analyse(a.rigid, a.window_start), analyse(a.flexible, a.window_start)]
    labels = [f"rigid {a.label}".strip(), f"flexible {a.label}".strip()]
    print("| outer ring | loaded zone [deg] at 1 % (10 %) | centre [deg] | peak roller load inner (outer) [N] | "
          "impacts per roller and revolution, front / rear | median impact peak front / rear [N] | "
          "largest front / rear [N] | window |")
    print("|---|---|---|---|---|---|---|---|")
    for r, label in zip(res, labels):
        print(row(r, label))
    for r, label in zip(res, labels):
        z = rm.load_zone(r["bins"], 0.01 * float(np.nanmax(r["bins"]["mean"])))
        for bar in ("front", "rear"):
            inside, outside = sectors(r[bar], z["start"] % (2 * math.pi), z["end"] % (2 * math.pi))
            print(f"{label}: {bar} impacts inside the loaded zone {inside}, outside {outside}")
            sector = np.bincount([int(e[3] * DEG // 30) for e in r[bar]], minlength=12)
            print(f"{label}: {bar} impacts per 30 deg sector from 0 deg: {list(sector)}; above {2 * IMPACT_N:.0f} N: "
                  f"{r[bar + '_strong_rate']:.2f} per roller and revolution")
        if "rim" in r:
            m = r["rim"]["mean"]
            print(f"{label}: rim deflection at the rollers, time mean per bin: {1e6 * np.nanmin(m):.1f} to "
                  f"{1e6 * np.nanmax(m):.1f} um")
    if a.figure:
        figure(res, labels, a.figure)


if __name__ == "__main__":
    main()
