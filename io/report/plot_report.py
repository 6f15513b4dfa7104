#!/usr/bin/env python3
"""Plots of `raceway report` for a spatial (ball-bearing) run.

    plot_report.py OUT.h5 SUMMARY_JSON OUTDIR

Reads the run's HDF5 file (layout: docs/output_layout.md, "Spatial (ball-bearing) runs") through
raceway_output.py (numpy arrays with their units, beside this script) and the
summary.json that `raceway report` wrote (time window, cage direction, contact threshold, azimuth
bins) and writes small PNGs into OUTDIR:

    cage_speed.png            cage and epicyclic speed against time
    cage_centroid.png         cage centre trajectory (equal axes), land-clearance circle if land-guided
    pocket_force_time.png     front / rear bar force of pocket 0 and of all pockets against time
    pocket_force_azimuth.png  front / rear bar force against the pocket's azimuth
    ball_load_azimuth.png     inner-groove ball load against azimuth, binned mean and the max
    power_loss.png            power loss per segment kind against time (if the file has it)

Exit codes: 0 all plots written; 3 matplotlib, h5py or numpy missing; 1 a plot failed (the
others are still written); 2 bad arguments.
Needs /usr/bin/python3 with python3-matplotlib, python3-h5py, python3-numpy (scripts/bootstrap.sh).
"""
import json
import math
import os
import sys
import traceback

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from raceway_output import RacewayOutput
except ImportError as err:  # the report reads exit code 3 as "modules missing"
    print(f"plot_report.py: {err}; install python3-matplotlib python3-h5py python3-numpy", file=sys.stderr)
    sys.exit(3)

DPI = 90
SIZE = (6.4, 3.6)
FRONT, REAR = "tab:blue", "tab:red"
MAX_POINTS = 4000  # per line/scatter, to keep the PNGs a few tens of kB


def thin(n, limit=MAX_POINTS):
    """Index step that leaves at most about `limit` points."""
    return max(1, int(math.ceil(n / limit)))


def series(f, path):
    return np.asarray(f[path], dtype=float) if path in f else None


def window_mask(t, summary):
    w = summary["window"]
    return (t >= w["start_s"] - 1e-12 * max(1.0, abs(w["start_s"]))) & (t <= w["end_s"])


def shade_window(ax, summary):
    w = summary["window"]
    ax.axvspan(w["start_s"], w["end_s"], color="0.92", zorder=0, label="window")


def save(fig, outdir, name):
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, name), dpi=DPI)
    plt.close(fig)


def cage_speed(f, summary, outdir):
    t = series(f, "time")
    n = len(t)
    cage = series(f, "cage/angular_velocity")[:n, 2]
    epi = series(f, "cage/epicyclic_speed")[:n]
    rpm = 60.0 / (2 * math.pi)
    s = thin(n)
    fig, ax = plt.subplots(figsize=SIZE)
    shade_window(ax, summary)
    ax.plot(t[::s], cage[::s] * rpm, lw=0.8, label="cage")
    ax.plot(t[::s], epi[::s] * rpm, lw=1.2, ls="--", color="k", label="epicyclic")
    cs = summary["cage_speed"]
    slip = cs.get("slip")
    slip_text = f", slip {100 * slip:.2f} %" if slip is not None else ""
    ax.set_title(f"cage {cs['mean_rpm']:.1f} rpm, epicyclic {cs['epicyclic_rpm']:.1f} rpm{slip_text}", fontsize=9)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("speed (rpm)")
    ax.legend(fontsize=8, loc="best")
    save(fig, outdir, "cage_speed.png")


def guidance(f):
    """'inner_land', 'outer_land', 'rolling_element' or None, from the scene text."""
    text = f.scene_text
    if not text:
        return None
    try:
        import tomllib

        return tomllib.loads(str(text)).get("cage", {}).get("guidance")
    except Exception:  # an unreadable scene only loses the clearance circle
        return None


def cage_centroid(f, summary, outdir):
    t = series(f, "time")
    n = len(t)
    pos = series(f, "cage/position")[:n]
    m = window_mask(t, summary)
    um = 1e6
    fig, ax = plt.subplots(figsize=(4.6, 4.6))
    s = thin(n)
    ax.plot(pos[::s, 0] * um, pos[::s, 1] * um, lw=0.4, color="0.75", label="whole run")
    pw = pos[m]
    sw = thin(len(pw))
    ax.plot(pw[::sw, 0] * um, pw[::sw, 1] * um, lw=0.7, color="tab:blue", label="window")
    c = summary["cage_centroid"]
    ax.plot([c["centre_x_m"] * um], [c["centre_y_m"] * um], "k+", ms=8, label="mean centre")
    clearance = c.get("land_clearance_m") or 0.0
    kind = guidance(f)
    if clearance > 0 and kind in ("inner_land", "outer_land"):
        ring = "inner_ring" if kind == "inner_land" else "outer_ring"
        rp = series(f, f"{ring}/position")
        centre = rp[:n][m, :2].mean(axis=0) if rp is not None else np.zeros(2)
        th = np.linspace(0, 2 * math.pi, 361)
        ax.plot((centre[0] + clearance * np.cos(th)) * um, (centre[1] + clearance * np.sin(th)) * um, "k--",
                lw=0.8, label=f"land clearance ({kind.replace('_', ' ')})")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (µm)")
    ax.set_ylabel("y (µm)")
    ratio, sigma = c.get("vortex_radius_ratio"), c.get("sigma_v")
    fmt = lambda v: "n/a" if v is None else f"{v:.3f}"  # noqa: E731
    ax.set_title(f"radius ratio {fmt(ratio)}, sigma_v {fmt(sigma)}", fontsize=9)
    ax.legend(fontsize=7, loc="upper right")
    save(fig, outdir, "cage_centroid.png")


def bar_forces(f, summary, n):
    """front, rear: [T x pockets] normal force on each bar (docs/output_layout.md sign convention)."""
    g = f.segments("ball_pocket")
    fn = np.asarray(g["normal_force"], dtype=float)[:n]
    fc = np.asarray(g["circumferential_force"], dtype=float)[:n]
    ball = np.asarray(g["ball"]).astype(int)
    pockets = int(summary["ball_count"])
    direction = summary["pocket_forces"]["direction"]
    front = np.zeros((fn.shape[0], pockets))
    rear = np.zeros_like(front)
    on = fn > 0
    is_front = fc * direction < 0
    for c, k in enumerate(ball):
        front[:, k] += np.where(on[:, c] & is_front[:, c], fn[:, c], 0.0)
        rear[:, k] += np.where(on[:, c] & ~is_front[:, c], fn[:, c], 0.0)
    return front, rear


def pocket_force_time(f, summary, outdir):
    t = series(f, "time")
    n = len(t)
    front, rear = bar_forces(f, summary, n)
    m = window_mask(t, summary)
    tw = t[m]
    s = thin(len(tw))
    fig, axes = plt.subplots(2, 1, figsize=(6.4, 4.8), sharex=True)
    ax = axes[0]
    ax.plot(tw[::s], front[m, 0][::s], color=FRONT, lw=0.8, label="front bar")
    ax.plot(tw[::s], -rear[m, 0][::s], color=REAR, lw=0.8, label="rear bar (drawn negative)")
    ax.set_ylabel("pocket 0 (N)")
    ax.legend(fontsize=7, loc="upper right")
    ax = axes[1]
    pockets = front.shape[1]
    for k in range(pockets):
        ax.plot(tw[::s], front[m, k][::s], color=FRONT, lw=0.4, alpha=0.6)
        ax.plot(tw[::s], -rear[m, k][::s], color=REAR, lw=0.4, alpha=0.6)
    ax.set_ylabel(f"all {pockets} pockets (N)")
    ax.set_xlabel("time (s)")
    pf = summary["pocket_forces"]
    frac = pf.get("rear_impulse_fraction")
    frac_text = "n/a" if frac is None else f"{100 * frac:.0f} %"
    axes[0].set_title(f"cage bar forces: front {pf['front']['events']} contacts, rear {pf['rear']['events']} "
                      f"contacts, rear impulse {frac_text}", fontsize=9)
    save(fig, outdir, "pocket_force_time.png")


def ball_azimuth_deg(f, n):
    p = series(f, "balls/position")[:n]
    return np.degrees(np.mod(np.arctan2(p[:, :, 1], p[:, :, 0]), 2 * math.pi))


def binned_line(ax, summary, key, color, label, sign=1.0):
    az = summary.get("azimuth", {})
    if "bin_centre_deg" not in az or key not in az:
        return
    y = np.array([np.nan if v is None else v for v in az[key]], dtype=float)
    ax.plot(az["bin_centre_deg"], sign * y, color=color, lw=1.5, label=label)


def finish_azimuth_plot(fig, ax, outdir, what, ylabel, name):
    """The common end of the plots against azimuth: a 0-360 deg axis, labels, legend, saved as name."""
    ax.set_xlim(0, 360)
    ax.set_xticks(range(0, 361, 45))
    ax.set_xlabel(f"{what} azimuth (deg, atan2(y, x))")
    ax.set_ylabel(ylabel)
    ax.legend(fontsize=7, loc="best")
    save(fig, outdir, name)


def pocket_force_azimuth(f, summary, outdir):
    t = series(f, "time")
    n = len(t)
    front, rear = bar_forces(f, summary, n)
    m = window_mask(t, summary)
    az = ball_azimuth_deg(f, n)[m]
    thr = summary["pocket_forces"]["threshold_n"]
    fig, ax = plt.subplots(figsize=SIZE)
    for data, color, sign, name in ((front[m], FRONT, 1.0, "front"), (rear[m], REAR, -1.0, "rear")):
        sel = data > thr
        x, y = az[sel], data[sel]
        s = thin(len(x))
        ax.scatter(x[::s], sign * y[::s], s=6, color=color, alpha=0.4, lw=0, label=f"{name} bar contacts")
        binned_line(ax, summary, f"{name}_force_max_n", color, f"{name} max per bin", sign)
    ax.axhline(0, color="k", lw=0.5)
    finish_azimuth_plot(fig, ax, outdir, "pocket", "bar force (N; rear drawn negative)", "pocket_force_azimuth.png")


def ball_load_azimuth(f, summary, outdir):
    t = series(f, "time")
    n = len(t)
    fn = series(f, "segments/ball_inner_groove/normal_force")[:n]
    ball = np.asarray(f["segments/ball_inner_groove/ball"]).astype(int)
    balls = int(summary["ball_count"])
    q = np.zeros((fn.shape[0], balls))
    for c, k in enumerate(ball):
        q[:, k] += fn[:, c]  # four-point bearings: both arcs of a ball
    m = window_mask(t, summary)
    az = ball_azimuth_deg(f, n)[m].reshape(-1)
    qw = q[m].reshape(-1)
    s = thin(len(qw))
    fig, ax = plt.subplots(figsize=SIZE)
    ax.scatter(az[::s], qw[::s], s=3, color="0.6", alpha=0.5, lw=0, label="samples")
    binned_line(ax, summary, "ball_load_mean_n", "tab:green", "mean per bin")
    bl = summary["ball_load"]
    if bl.get("max_n") is not None:
        ax.axhline(bl["max_n"], color="k", ls="--", lw=0.8, label=f"max {bl['max_n']:.0f} N")
    start, end = bl.get("load_zone_start_deg"), bl.get("load_zone_end_deg")
    if start is not None and end is not None and (bl.get("load_zone_width_deg") or 0) < 359.9:
        spans = [(start, end)] if end > start else [(start, 360), (0, end)]
        for i, (a, b) in enumerate(spans):
            ax.axvspan(a, b, color="tab:green", alpha=0.08, label="load zone" if i == 0 else None)
    finish_azimuth_plot(fig, ax, outdir, "ball", "inner-groove ball load (N)", "ball_load_azimuth.png")


def power_loss(f, summary, outdir):
    t = series(f, "time")
    n = len(t)
    s = thin(n)
    fig, ax = plt.subplots(figsize=SIZE)
    total = np.zeros(n)
    for kind in f.segment_kinds():
        if f"segments/{kind}/power_loss" not in f:
            continue
        p = series(f, f"segments/{kind}/power_loss")[:n].sum(axis=1)
        total += p
        ax.plot(t[::s], p[::s], lw=0.7, label=kind)
    ax.plot(t[::s], total[::s], lw=1.0, color="k", label="total")
    shade_window(ax, summary)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("power loss (W)")
    ax.legend(fontsize=7, loc="best")
    save(fig, outdir, "power_loss.png")


def has_power_loss(f):
    return any(f"segments/{k}/power_loss" in f for k in f.segment_kinds())


def main(argv):
    if len(argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    h5_path, summary_path, outdir = argv[1:]
    with open(summary_path, encoding="utf-8") as fh:
        summary = json.load(fh)
    os.makedirs(outdir, exist_ok=True)
    failures = 0
    with RacewayOutput(h5_path) as f:
        plots = [cage_speed, cage_centroid]
        if "pocket_forces" in summary and "segments/ball_pocket" in f:
            plots += [pocket_force_time, pocket_force_azimuth]
        if "ball_load" in summary and "segments/ball_inner_groove" in f:
            plots.append(ball_load_azimuth)
        if has_power_loss(f):
            plots.append(power_loss)
        for plot in plots:
            try:
                plot(f, summary, outdir)
            except Exception:  # one broken plot must not cost the others
                failures += 1
                print(f"plot_report.py: {plot.__name__} failed:\n{traceback.format_exc()}", file=sys.stderr)
                plt.close("all")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
