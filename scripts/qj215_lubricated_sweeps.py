#!/usr/bin/python3
"""Seed 001's three cage-stability sweeps, dry against lubricated (docs/campaigns/qj215_whirl.md,
"Lubricated cage contacts and drag"): the unbalance campaigns' tables (qj215_*_unbalance) against the
lubricated campaigns' (qj215_*_lubricated), at the lubricated runs' points and realisations only
(the same scene but for the oil, the films and the drag).

Usage: qj215_lubricated_sweeps.py OUT.png [CAMPAIGNS_DIR]
CAMPAIGNS_DIR: where the campaign_table.csv folders are (default docs/campaigns). Prints one table
per sweep (means over the realisations, their range in brackets) and draws the ratios against the
swept value. Needs numpy, matplotlib.
       qj215_lubricated_sweeps.py --orbits OUT.png LABEL=RUN.h5 [LABEL=RUN.h5 ...]
draws the cage centre's orbit of each run at its own scale: the first two thirds of the run grey,
the last third (the metrics' window of these campaigns) in colour. Needs h5py too.
"""
import csv
import pathlib
import sys

import numpy as np

SWEEPS = (("speed", "inner ring speed, r/min", 30 / np.pi), ("axial", "axial load Fa, N", 1.0),
          ("radial", "radial load Fr, N", -1.0))
AXIS_COLUMN = {"speed": "speed", "axial": "axial_load", "radial": "radial_load"}
COLUMNS = ("vortex_radius_ratio", "sigma_v", "cage_whirl_radius_m", "cage_speed_rpm", "pocket_force_rms_n",
           "power_loss_w")


def rows(folder, sweep, scale):
    """{(value, realisation): row} of the done runs of one campaign table."""
    out = {}
    for r in csv.DictReader((folder / "campaign_table.csv").open()):
        if r["status"] == "done":
            value = round(float(r[f"{AXIS_COLUMN[sweep]}_si"]) * scale, 3)
            out[(value, r["realisation"])] = {k: float(r[k]) if r.get(k) else np.nan for k in COLUMNS}
    return out


def paired(campaigns, sweep, scale):
    """Per swept value: the dry and lubricated rows of the realisations both campaigns ran."""
    dry = rows(campaigns / f"qj215_{sweep}_unbalance", sweep, scale)
    lub = rows(campaigns / f"qj215_{sweep}_lubricated", sweep, scale)
    out = {}
    for key in sorted(set(dry) & set(lub)):
        out.setdefault(key[0], []).append((dry[key], lub[key]))
    return out


def cell(values, fmt):
    v = np.array(values)
    return f"{np.mean(v):{fmt}} ({np.min(v):{fmt}}-{np.max(v):{fmt}})" if len(v) > 1 else f"{v[0]:{fmt}}"


def print_table(sweep, points):
    print(f"\n{sweep}: | value | n | ratio dry | ratio lubricated | sigma_v dry | sigma_v lubricated | "
          "centre from axis, um, dry / lubricated | cage rpm dry / lubricated | pocket RMS N dry / lubricated | "
          "loss W dry / lubricated |")
    for value, pairs in points.items():
        d = {k: [p[0][k] for p in pairs] for k in COLUMNS}
        w = {k: [p[1][k] for p in pairs] for k in COLUMNS}
        print(f"| {value:g} | {len(pairs)} | {cell(d['vortex_radius_ratio'], '.3g')} | "
              f"{cell(w['vortex_radius_ratio'], '.3g')} | {cell(d['sigma_v'], '.3g')} | {cell(w['sigma_v'], '.3g')} | "
              f"{1e6 * np.mean(d['cage_whirl_radius_m']):.1f} / {1e6 * np.mean(w['cage_whirl_radius_m']):.1f} | "
              f"{np.mean(d['cage_speed_rpm']):.2f} / {np.mean(w['cage_speed_rpm']):.2f} | "
              f"{np.mean(d['pocket_force_rms_n']):.3g} / {np.mean(w['pocket_force_rms_n']):.3g} | "
              f"{np.mean(d['power_loss_w']):.3g} / {np.mean(w['power_loss_w']):.3g} |")


def plot(all_points, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 3, figsize=(13, 6.5))
    for col, (sweep, label, _) in enumerate(SWEEPS):
        points = all_points[sweep]
        x = np.array(list(points))
        for row, metric in enumerate(("vortex_radius_ratio", "sigma_v")):
            ax = axes[row, col]
            for which, style, name in ((0, "ko-", "dry"), (1, "bs--", "lubricated")):
                runs = [[p[which][metric] for p in pairs] for pairs in points.values()]
                ax.semilogy(x, [np.mean(r) for r in runs], style, label=name, ms=4)
                for xi, r in zip(x, runs):
                    ax.semilogy([xi] * len(r), r, style[0] + ".", alpha=0.4)
            ax.set_xlabel(label)
            ax.set_ylabel(metric.replace("_", " "))
            ax.grid(alpha=0.3, which="both")
    axes[0, 0].legend(fontsize=8)
    fig.suptitle("QJ215, cage unbalance 50 um: dry against LGMT 3 base oil (films and drag); "
                 "mean of two realisations, each one a dot")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def plot_orbits(path, specs):
    """Each run's orbit at its own scale, the last third (these campaigns' window) in colour."""
    from qj215_whirl_compare import plot_orbits as draw  # the dry campaigns' drawing, at another scale
    draw(path, specs, clearance_um=None, window_from=(2, 3))


def main(argv):
    if len(argv) >= 4 and argv[1] == "--orbits":
        plot_orbits(argv[2], argv[3:])
        return 0
    if len(argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    campaigns = pathlib.Path(argv[2] if len(argv) > 2 else "docs/campaigns")
    all_points = {sweep: paired(campaigns, sweep, scale) for sweep, _, scale in SWEEPS}
    for sweep, points in all_points.items():
        print_table(sweep, points)
    plot(all_points, argv[1])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
