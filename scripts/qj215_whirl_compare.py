#!/usr/bin/python3
"""Seed 001's cage-stability metrics (vortex radius ratio, sigma_v of eq. 9) of the QJ215 sweep
campaigns with realisations (docs/campaigns/qj215_whirl.md): one swept axis (speed, axial or radial
load) and a `realisation` axis (the cage's start). Per point: the mean, standard deviation and range
over the realisations of the campaign table's columns (io/report/report_metrics.py centroid_metrics:
over the last whole whirl turns of the window, about their mean centre), the trend directions over
seed 001's ranges, and optionally the metrics over successive blocks of revolutions (settling).

Usage: qj215_whirl_compare.py OUT_PREFIX CAMPAIGN_DIR [--rtol RTOL_CAMPAIGN_DIR] [--blocks REVS]
writes OUT_PREFIX.csv (per point), OUT_PREFIX.png (the figure) and prints the trend and rtol tables
(--blocks: the metrics over blocks of REVS revolutions of every run's whole length, OUT_PREFIX_blocks.csv,
needs the runs' .h5 files);
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

METRICS = ("vortex_radius_ratio", "sigma_v")
# The swept quantity of each campaign table column, in the unit seed 001 plots it in.
AXES = {"speed": ("inner ring speed, r/min", rm.RPM), "axial_load": ("axial load Fa, N", 1.0),
        "radial_load": ("radial load Fr, N", -1.0)}

# Seed 001's figures as its text describes them (sections 4.1-4.3; the figures' values are not in
# the text): the direction of both ratios over each stretch of the sweep, and what the text says.
SEED_TRENDS = {
    "speed": ("seed 001 Fig. 10: falls to 3000 r/min, rises after it and levels off; range 0.15",
              [((1000, 3000), "falls"), ((3000, 8000), "rises")]),
    "axial_load": ("seed 001 Fig. 12: falls to 3000 N, rises after it; range 0.45",
                   [((1000, 3000), "falls"), ((3000, 5000), "rises")]),
    "radial_load": ("seed 001 Fig. 14: rises; the ratio above 1.0 at 600 N",
                    [((100, 600), "rises")]),
}


# The size of seed 001's ratios its text gives: drawn as a line over the stated stretch of the sweep.
SEED_SIZES = {"speed": (0.15, [1000, 8000]), "axial_load": (0.45, [1000, 5000]), "radial_load": (1.0, [550, 650])}
SEED_SIZES_TEXT = {"speed": "the ratio's range over the sweep, 0.15", "axial_load": "the ratio's range, 0.45",
                   "radial_load": "the ratio above 1.0 at 600 N"}


def read_table(campaign_dir):
    """The done rows of a campaign table, each with its swept `value` in seed 001's unit."""
    rows = list(csv.DictReader((pathlib.Path(campaign_dir) / "campaign_table.csv").open()))
    axis = next(k for k in rows[0] if k in AXES)
    out = []
    for r in rows:
        if r["status"] != "done":
            continue
        r = dict(r, axis=axis, value=round(float(r[f"{axis}_si"]) * AXES[axis][1], 6))
        for k in METRICS + ("cage_whirl_radius_m", "vortex_turns", "whirl_frequency_hz", "cage_speed_rpm",
                            "window_revolutions"):
            r[k] = float(r[k]) if r.get(k) else math.nan
        out.append(r)
    return axis, out


def point_stats(rows):
    """Per swept value: n, mean, standard deviation (n - 1), min, max of each metric over the
    realisations, and the mean distance of the cage centre from the axis."""
    out = []
    for value in sorted({r["value"] for r in rows}):
        rs = [r for r in rows if r["value"] == value]
        p = {"value": value, "realisations": len(rs)}
        for k in METRICS + ("vortex_turns",):
            v = np.array([r[k] for r in rs])
            p.update({f"{k}_mean": float(np.mean(v)), f"{k}_std": float(np.std(v, ddof=1)) if len(v) > 1 else math.nan,
                      f"{k}_min": float(np.min(v)), f"{k}_max": float(np.max(v))})
        p["axis_radius_um_mean"] = 1e6 * float(np.mean([r["cage_whirl_radius_m"] for r in rs]))
        p["whirl_to_cage_speed_mean"] = float(np.mean([60 * r["whirl_frequency_hz"] / r["cage_speed_rpm"] for r in rs]))
        out.append(p)
    return out


def trend(rows, lo, hi, metric):
    """Least-squares slope of metric against the swept value over [lo, hi], every realisation a point,
    its standard error and the direction it resolves: 'rises' / 'falls' when |slope| > 2 standard
    errors, else 'no trend resolved'. Also the change of the point means from lo to hi."""
    rs = [r for r in rows if lo - 1e-9 <= r["value"] <= hi + 1e-9 and math.isfinite(r[metric])]
    x, y = np.array([r["value"] for r in rs]), np.array([r[metric] for r in rs])
    a = np.vstack([x - x.mean(), np.ones_like(x)]).T
    coef, res, *_ = np.linalg.lstsq(a, y, rcond=None)
    dof = len(x) - 2
    sigma2 = float(res[0]) / dof if dof > 0 and res.size else math.nan
    se = math.sqrt(sigma2 / float(np.sum((x - x.mean()) ** 2)))
    slope = float(coef[0])
    direction = ("rises" if slope > 0 else "falls") if abs(slope) > 2 * se else "no trend resolved"
    mean_at = lambda v: float(np.mean(y[np.abs(x - v) < 1e-9]))
    return {"slope": slope, "se": se, "direction": direction, "change": mean_at(hi) - mean_at(lo)}


def block_metrics(h5_path, revs, samples_per_rev=600):
    """The vortex metrics over successive blocks of `revs` driven-ring revolutions of the whole run."""
    with h5py.File(h5_path, "r") as f:
        t = f["time"][:]
        p, v = f["cage/position"][:], f["cage/velocity"][:]
    step = revs * samples_per_rev
    out = []
    for b in range(0, len(t) - step, step):
        w = rm.select_window(t[:b + step + 1], start=float(t[b]))
        m = rm.centroid_metrics(t, p[:, 0], p[:, 1], v[:, 0], v[:, 1], w, 1.0)
        out.append((b // samples_per_rev, (b + step) // samples_per_rev, m["vortex_radius_ratio"], m["sigma_v"],
                    m["vortex_turns"]))
    return out


def blocks(campaign_dir, rows, revs):
    """Every run's block metrics and, per block, their mean over the realisations of each point."""
    per_run = []
    for r in rows:
        for first, last, ratio, sigma, turns in block_metrics(pathlib.Path(campaign_dir) / f"{r['scene']}.h5", revs):
            per_run.append({"value": r["value"], "realisation": r["realisation"], "from_rev": first, "to_rev": last,
                            "vortex_radius_ratio": ratio, "sigma_v": sigma, "vortex_turns": turns})
    return per_run


def print_blocks(per_run):
    """Per point, the realisations' mean ratio in each block, and the mean over all points."""
    spans = sorted({(b["from_rev"], b["to_rev"]) for b in per_run})
    print("block metrics (mean over realisations): value | " + " | ".join(f"rev {a}-{b}" for a, b in spans))
    for value in sorted({b["value"] for b in per_run}):
        cells = []
        for span in spans:
            bs = [b for b in per_run if b["value"] == value and (b["from_rev"], b["to_rev"]) == span]
            cells.append(f"{np.mean([b['vortex_radius_ratio'] for b in bs]):.3f} / {np.mean([b['sigma_v'] for b in bs]):.3f}")
        print(f"| {value:g} | " + " | ".join(cells) + " |")


def plot_blocks(axis, per_run, path):
    """Each metric's mean over the realisations in each block against the block's end, one line per point."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    for value in sorted({b["value"] for b in per_run}):
        bs = [b for b in per_run if b["value"] == value]
        ends = sorted({b["to_rev"] for b in bs})
        for ax, k in zip(axes, METRICS):
            ax.semilogy(ends, [np.mean([b[k] for b in bs if b["to_rev"] == e]) for e in ends], "o-", label=f"{value:g}")
    for ax, k in zip(axes, METRICS):
        ax.set_xlabel("end of the block of revolutions")
        ax.set_ylabel(f"{k}, mean over the realisations")
        ax.grid(alpha=0.3)
    axes[0].legend(title=AXES[axis][0], fontsize=7)
    fig.suptitle("settling: the vortex metrics over successive blocks of revolutions", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def rtol_check(rows, rtol_dir):
    """Each run of the rtol campaign against the run of the same point and realisation, and the
    realisations' spread at that point."""
    _, tight = read_table(rtol_dir)
    stats = {p["value"]: p for p in point_stats(rows)}
    out = []
    for t in tight:
        base = next(r for r in rows if r["value"] == t["value"] and r["realisation"] == t["realisation"])
        row = {"value": t["value"], "realisation": t["realisation"]}
        for k in METRICS:
            row.update({f"{k}_base": base[k], f"{k}_tight": t[k], f"{k}_realisation_std": stats[t["value"]][f"{k}_std"]})
        out.append(row)
    return out


def plot(axis, stats, rows, path, rtol_rows=()):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.4))
    x = [p["value"] for p in stats]
    for ax, k in zip(axes, METRICS):
        ax.plot([r["value"] for r in rows], [r[k] for r in rows], ".", color="0.6", ms=5, label="each realisation")
        mean = np.array([p[f"{k}_mean"] for p in stats])
        spread = [mean - [p[f"{k}_min"] for p in stats], [p[f"{k}_max"] for p in stats] - mean]
        ax.errorbar(x, mean, yerr=spread, fmt="o-", capsize=3, label="mean, bars: range over the realisations")
        ax.set_yscale("log")
        if rtol_rows:
            ax.plot([r["value"] for r in rtol_rows], [r[f"{k}_tight"] for r in rtol_rows], "rx", ms=6,
                    label="rtol 1e-8")
    axes[2].plot(x, [p["axis_radius_um_mean"] for p in stats], "o-")
    axes[2].axhline(100, color="0.5", ls="--", lw=0.8)
    axes[2].text(x[0], 101, "land clearance", fontsize=8, color="0.4")
    axes[2].set_ylim(0, 110)
    seed_range, seed_x = SEED_SIZES[axis]
    axes[0].plot(seed_x, [seed_range] * len(seed_x), "k:", label=f"seed 001: {SEED_SIZES_TEXT[axis]}")
    axes[0].set_ylabel("vortex radius ratio (max - min) / mean")
    axes[1].set_ylabel("sigma_v (seed 001 eq. 9)")
    axes[2].set_ylabel("mean cage-centre distance from the axis, um")
    for ax in axes:
        ax.set_xlabel(AXES[axis][0])
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7)
    n, window = stats[0]["realisations"], float(np.mean([r["window_revolutions"] for r in rows]))
    fig.suptitle(f"QJ215, cage unbalance 50 um: {n} realisations per point, the whole whirl turns of the last "
                 f"{window:.0f} revolutions. {SEED_TRENDS[axis][0]}", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def plot_orbits(path, specs, clearance_um=100.0, window_from=(1, 2)):
    """The cage centre's orbit of each LABEL=RUN.h5 in `specs`: the run up to window_from (a fraction,
    numerator and denominator) of its samples grey, the rest (the metrics' window) in colour. With
    clearance_um, the guiding gap drawn and every run at its scale; with None, each run at its own
    scale and the title saying how far its window reaches."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(specs), figsize=(3.2 * len(specs), 3.6), squeeze=False)
    circle = np.linspace(0, rm.TWO_PI, 361)
    for ax, spec in zip(axes[0], specs):
        label, _, h5_path = spec.partition("=")
        with h5py.File(h5_path, "r") as f:
            p = 1e6 * f["cage/position"][:, :2]
        start = window_from[0] * len(p) // window_from[1]
        if clearance_um is not None:
            ax.plot(clearance_um * np.cos(circle), clearance_um * np.sin(circle), "k--", lw=0.6)
        ax.plot(p[:start + 1, 0], p[:start + 1, 1], color="0.75", lw=0.4)
        ax.plot(p[start:, 0], p[start:, 1], lw=0.6)
        reach = 1.15 * clearance_um if clearance_um is not None else 1.1 * float(np.max(np.abs(p)))
        ax.set_aspect("equal")
        ax.set_xlim(-reach, reach)
        ax.set_ylim(-reach, reach)
        title = label if clearance_um is not None else \
            f"{label}\nlast third within {float(np.max(np.hypot(*p[start:].T))):.2g} um"
        ax.set_title(title, fontsize=8)
        ax.set_xlabel("x, um")
    axes[0][0].set_ylabel("y, um")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def write_csv(path, rows):
    keys = list(dict.fromkeys(k for r in rows for k in r))
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})


def report(axis, stats, rows, rtol_rows):
    print("| value | n | ratio mean +- std | ratio range | sigma_v mean +- std | sigma_v range | whole turns | "
          "whirl / cage speed | from the axis, um |")
    for p in stats:
        print(f"| {p['value']:g} | {p['realisations']} | {p['vortex_radius_ratio_mean']:.3f} +- "
              f"{p['vortex_radius_ratio_std']:.3f} | {p['vortex_radius_ratio_min']:.3f}-{p['vortex_radius_ratio_max']:.3f} "
              f"| {p['sigma_v_mean']:.3f} +- {p['sigma_v_std']:.3f} | {p['sigma_v_min']:.3f}-{p['sigma_v_max']:.3f} | "
              f"{p['vortex_turns_min']:.0f}-{p['vortex_turns_max']:.0f} | {p['whirl_to_cage_speed_mean']:.3f} | "
              f"{p['axis_radius_um_mean']:.1f} |")
    print(SEED_TRENDS[axis][0])
    for (lo, hi), seed in SEED_TRENDS[axis][1]:
        for k in METRICS:
            t = trend(rows, lo, hi, k)
            print(f"  {k} {lo:g}-{hi:g}: seed {seed}; raceway {t['direction']} (slope {t['slope']:.3g} +- {t['se']:.2g} "
                  f"per unit, change of the means {t['change']:+.3f})")
    for r in rtol_rows:
        print(f"  rtol 1e-6 -> 1e-8 at {r['value']:g}, realisation {r['realisation']}: ratio "
              f"{r['vortex_radius_ratio_base']:.4f} -> {r['vortex_radius_ratio_tight']:.4f}, sigma_v "
              f"{r['sigma_v_base']:.4f} -> {r['sigma_v_tight']:.4f} (realisations' std {r['vortex_radius_ratio_realisation_std']:.3f}, "
              f"{r['sigma_v_realisation_std']:.3f})")


def main(argv):
    if len(argv) >= 4 and argv[1] == "--orbits":
        plot_orbits(argv[2], argv[3:])
        return 0
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    prefix, campaign_dir, options = argv[1], argv[2], dict(zip(argv[3::2], argv[4::2]))
    axis, rows = read_table(campaign_dir)
    stats = point_stats(rows)
    rtol_rows = rtol_check(rows, options["--rtol"]) if "--rtol" in options else []
    write_csv(f"{prefix}.csv", stats)
    if rtol_rows:
        write_csv(f"{prefix}_rtol.csv", rtol_rows)
    plot(axis, stats, rows, f"{prefix}.png", rtol_rows)
    report(axis, stats, rows, rtol_rows)
    if "--blocks" in options:
        per_run = blocks(campaign_dir, rows, int(options["--blocks"]))
        write_csv(f"{prefix}_blocks.csv", per_run)
        print_blocks(per_run)
        plot_blocks(axis, per_run, f"{prefix}_settling.png")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
