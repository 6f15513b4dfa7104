#!/usr/bin/python3
"""Seed 001's cage-stability metrics (vortex radius ratio, sigma_v of eq. 9) of QJ215 sweep campaigns
(one swept axis: speed, axial or radial load), three ways, into a CSV and a figure
(docs/campaigns/qj215_whirl.md):

  - `mean_centre`: about the centre of the window's samples, as `raceway report` and the campaign
    table (io/report/report_metrics.py centroid_metrics over the last half of the run);
  - `whole_turns`: the same over the longest end of that window holding a whole number of whirl
    turns (the mean centre of a circle swept 4.5 times sits r / (4.5 pi) off its centre, which alone
    gives a ratio of 0.14);
  - `axis`: about the bearing axis (the orbit's centre under a pure axial load).

Seed 001's figures 10, 12 and 14 are drawn as what its text says of them (trend and range): their
values are not in the text.

Usage: qj215_whirl_compare.py OUT_PREFIX LABEL=CAMPAIGN_DIR [LABEL=CAMPAIGN_DIR ...]
writes OUT_PREFIX.csv and OUT_PREFIX.png;
       qj215_whirl_compare.py --orbits OUT.png LABEL=RUN.h5 [LABEL=RUN.h5 ...]
draws the cage centre's orbit of each run (first half grey, second half in colour) in the land
clearance. Needs h5py, numpy, matplotlib.
"""
import csv
import math
import pathlib
import sys

import h5py
import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "io" / "report"))
import report_metrics as rm  # noqa: E402  (the report's own metric functions)


def whole_turn_window(time, x, y, window):
    """The latest start inside `window` after which the centre sweeps a whole number (>= 1) of turns
    about its mean centre; `window` itself when it holds less than one turn."""
    s = window.slice
    phi = np.unwrap(np.arctan2(y[s] - np.mean(y[s]), x[s] - np.mean(x[s])))
    swept_from = phi[-1] - phi  # angle swept from each sample to the end
    turns = math.floor(abs(swept_from[0]) / rm.TWO_PI)
    if turns < 1:
        return window
    begin = int(np.nonzero(np.abs(swept_from) >= turns * rm.TWO_PI)[0][-1])
    return rm.select_window(time, start=float(time[window.begin + begin]))


def metrics_of(h5_path):
    with h5py.File(h5_path, "r") as f:
        t = f["time"][:]
        p, v = f["cage/position"][:], f["cage/velocity"][:]
        spin = f["cage/angular_velocity"][:, 2]  # about the cage axis, rad/s
    x, y, vx, vy = p[:, 0], p[:, 1], v[:, 0], v[:, 1]
    window = rm.select_window(t)
    cage = float(np.mean(spin[window.slice]))
    out = {}
    for name, w in (("mean_centre", window), ("whole_turns", whole_turn_window(t, x, y, window))):
        m = rm.centroid_metrics(t, x, y, vx, vy, w, cage)
        out[f"{name}_vortex_radius_ratio"] = m["vortex_radius_ratio"]
        out[f"{name}_sigma_v"] = m["sigma_v"]
        if name == "mean_centre":
            out["axis_vortex_radius_ratio"] = m["axis_radius_ratio"]
            out["axis_radius_mean_um"] = 1e6 * m["axis_radius_mean_m"]
            out["whirl_to_cage_speed"] = m["whirl_to_cage_speed_ratio"]
            out["whirl_turns"] = m["whirl_revolutions"]
    return out


# The swept quantity of each campaign table column, in the unit seed 001 plots it in.
AXES = {"speed": ("inner ring speed, r/min", rm.RPM), "axial_load": ("axial load Fa, N", 1.0),
        "radial_load": ("radial load Fr, N", -1.0)}

# Seed 001's figures as its text describes them (sections 4.1-4.3; the figures' values are not in
# the text): the shape of the vortex radius ratio over the sweep, 0 at its minimum, and what the
# text says. Anchored at our value at the seed's minimum: a statement of trend and range, not data.
SEED_SHAPES = {
    "speed": ("seed 001 Fig. 10 (text: min at 3000 r/min, range 0.15)",
              [1000, 2000, 3000, 4000, 5000, 6000, 7000, 8000], [0.15, 0.075, 0, 0.05, 0.1, 0.135, 0.145, 0.15], 3000),
    "axial_load": ("seed 001 Fig. 12 (text: min at 3000 N, range 0.45)",
                   [1000, 2000, 3000, 4000, 5000], [0.3, 0.15, 0, 0.2, 0.45], 3000),
    "radial_load": ("seed 001 Fig. 14 (text: rising, above 1.0 at 600 N)",
                    [100, 200, 300, 400, 500, 600], None, None),
}


def rows_of(label, campaign_dir):
    table = pathlib.Path(campaign_dir) / "campaign_table.csv"
    for r in csv.DictReader(table.open()):
        axis = next(k for k in r if k in AXES)
        row = {"case": label, "axis": axis, "value": float(r[f"{axis}_si"]) * AXES[axis][1], "status": r["status"]}
        h5 = pathlib.Path(campaign_dir) / f"{r['scene']}.h5"
        if h5.exists():
            row.update(metrics_of(h5))
        else:  # a table without its runs: only the campaign's own columns
            row.update({"mean_centre_vortex_radius_ratio": float(r["vortex_radius_ratio"]),
                        "mean_centre_sigma_v": float(r["sigma_v"]),
                        "axis_radius_mean_um": 1e6 * float(r["cage_whirl_radius_m"])})
        yield row


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.4))
    cases = list(dict.fromkeys(r["case"] for r in rows))
    axis = rows[0]["axis"]
    for case in cases:
        rs = [r for r in rows if r["case"] == case]
        n = [r["value"] for r in rs]
        for ax, key in zip(axes, ("whole_turns_vortex_radius_ratio", "whole_turns_sigma_v", "axis_radius_mean_um")):
            fallback = key.replace("whole_turns", "mean_centre")
            ax.plot(n, [r.get(key, r.get(fallback, math.nan)) for r in rs], "o-", label=case)
    label, shape_x, shape, minimum_at = SEED_SHAPES[axis]
    anchor = next((r for r in rows if r["case"] == cases[0] and minimum_at is not None
                   and abs(r["value"] - minimum_at) < 1e-6 * minimum_at), None)
    if anchor is not None:
        base = anchor.get("whole_turns_vortex_radius_ratio", math.nan)
        axes[0].plot(shape_x, [base + v for v in shape], "k:", lw=1.5, label=label)
    else:
        axes[0].plot([shape_x[-1]], [1.0], "kv", label=label)
    axes[0].set_ylabel("vortex radius ratio (max - min) / mean")
    axes[1].set_ylabel("sigma_v (seed 001 eq. 9)")
    axes[2].set_ylabel("mean cage-centre distance from the axis, um")
    axes[2].axhline(100, color="0.5", ls="--", lw=0.8)
    axes[2].text(shape_x[0], 101, "land clearance", fontsize=8, color="0.4")
    for ax in axes:
        ax.set_xlabel(AXES[axis][0])
        ax.grid(alpha=0.3)
        ax.set_yscale("log")
    axes[1].set_ylim(bottom=1e-4)  # a motionless centre's sigma_v (1e-16, rounding) lies below
    axes[0].legend(fontsize=7)
    fig.suptitle("QJ215: cage whirl (last 10 of 20 revolutions; ratios over whole whirl turns)", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def plot_orbits(path, specs, clearance_um=100.0):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(specs), figsize=(3.2 * len(specs), 3.6), squeeze=False)
    circle = np.linspace(0, rm.TWO_PI, 361)
    for ax, spec in zip(axes[0], specs):
        label, _, h5_path = spec.partition("=")
        with h5py.File(h5_path, "r") as f:
            p = 1e6 * f["cage/position"][:, :2]
        half = len(p) // 2
        ax.plot(clearance_um * np.cos(circle), clearance_um * np.sin(circle), "k--", lw=0.6)
        ax.plot(p[:half + 1, 0], p[:half + 1, 1], color="0.75", lw=0.4)
        ax.plot(p[half:, 0], p[half:, 1], lw=0.6)
        ax.set_aspect("equal")
        ax.set_xlim(-1.15 * clearance_um, 1.15 * clearance_um)
        ax.set_ylim(-1.15 * clearance_um, 1.15 * clearance_um)
        ax.set_title(label, fontsize=8)
        ax.set_xlabel("x, um")
    axes[0][0].set_ylabel("y, um")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main(argv):
    if len(argv) >= 4 and argv[1] == "--orbits":
        plot_orbits(argv[2], argv[3:])
        return 0
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    rows = []
    for spec in argv[2:]:
        label, _, directory = spec.partition("=")
        rows.extend(rows_of(label, directory))
    keys = list(dict.fromkeys(k for r in rows for k in r))
    with open(f"{argv[1]}.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})
    plot(rows, f"{argv[1]}.png")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
