"""The figures of `raceway report` (raceway_report.py), for planar and spatial runs.

Every figure is 1600 px wide, titled with the scene's name, with plain tick labels (no axis offset
such as "+1.19e3") and units in its axis labels; time series show every sample (no thinning, so
every impact is drawn), the analysis window shaded and the vertical axis scaled to the values inside
it (scale_to_window: a start-up transient is clipped, not allowed to flatten the window). draw_all(run, summary, folder) writes them and
returns (names written, failures); each helper is importable on its own (figure(), save()).
"""
import math
import os
import textwrap
import traceback

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import report_metrics as rm  # noqa: E402

WIDTH_IN, HEIGHT_IN, DPI = 16.0, 6.5, 100  # 1600 x 650 px
FRONT, REAR = "tab:blue", "tab:red"
plt.rcParams.update({"axes.formatter.useoffset": False, "axes.grid": True, "grid.alpha": 0.3, "font.size": 12,
                     "axes.titlesize": 14, "legend.fontsize": 11})


def figure(run, what, height=HEIGHT_IN, ncols=1):
    """A figure titled "<scene>: <what>"."""
    fig, axes = plt.subplots(1, ncols, figsize=(WIDTH_IN, height), squeeze=False)
    fig.suptitle(f"{run.scene_name}: {what}", fontsize=15)
    return fig, axes[0] if ncols > 1 else axes[0][0]


def save(fig, folder, name):
    for ax in fig.axes:
        if not ax.name == "polar":
            ax.ticklabel_format(useOffset=False, style="plain", axis="both") if _linear(ax) else None
    fig.tight_layout()
    fig.savefig(os.path.join(folder, name), dpi=DPI)
    plt.close(fig)
    return name


def _linear(ax):
    return ax.get_xscale() == "linear" and ax.get_yscale() == "linear"


def shade_window(ax, summary):
    w = summary["window"]
    ax.axvspan(w["start_s"], w["end_s"], color="0.93", zorder=0, label=f"window {w['start_s']:.4g}-{w['end_s']:.4g} s")


def scale_to_window(ax, run, summary, *series):
    """The vertical axis of a time plot scaled to the values inside the analysis window (the whole
    run stays on the time axis), so a start-up transient (a spin-up) does not flatten the window;
    earlier samples beyond the scale are clipped, and the plot says so."""
    w = summary["window"]
    inside = (run.time >= w["start_s"] - 1e-12) & (run.time <= w["end_s"] + 1e-12)
    values = [np.asarray(y, dtype=float) for y in series if y is not None]
    within = np.concatenate([y[inside].ravel() for y in values]) if values else np.zeros(0)
    within = within[np.isfinite(within)]
    if within.size == 0:
        return
    lo, hi = float(within.min()), float(within.max())
    span = hi - lo if hi > lo else max(abs(hi), 1e-12)
    lo, hi = lo - 0.08 * span, hi + 0.08 * span
    ax.set_ylim(lo, hi)
    outside = np.concatenate([y[~inside].ravel() for y in values])
    outside = outside[np.isfinite(outside)]
    if outside.size and (outside.min() < lo or outside.max() > hi):
        ax.text(0.01, 0.98, "scaled to the window: earlier samples (start-up) off scale", transform=ax.transAxes,
                va="top", ha="left", fontsize=10, color="0.3")


def cage_speed(run, s, folder):
    fig, ax = figure(run, "cage speed against the kinematic speed")
    shade_window(ax, s)
    cs = s["cage_speed"]
    ax.plot(run.time, run.cage_speed * rm.RPM, lw=0.8, label=f"cage (window mean {cs['mean_rpm']:.2f} rpm)")
    if run.kind == "spatial":
        ax.plot(run.time, run.epicyclic_speed * rm.RPM, lw=1.2, ls=":", color="0.3",
                label=f"kinematic at the nominal contact angle ({cs['epicyclic_rpm']:.2f} rpm)")
    if "rolling_rpm" in cs:
        label = "kinematic at the loaded contact angle" if run.kind == "spatial" else "kinematic (epicyclic, line contact)"
        ax.plot(run.time, run.rolling_speed * rm.RPM, lw=1.4, ls="--", color="k",
                label=f"{label} ({cs['rolling_rpm']:.2f} rpm, slip {100 * cs['slip']:.3f} %)")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("speed about the bearing axis [rpm]")
    w = s["window"]
    inside = run.cage_speed[w["samples"] * -1:] * rm.RPM
    span = max(float(np.ptp(inside)), 1e-3 * abs(cs["mean_rpm"]) + 1e-9)
    ax.set_ylim(min(inside.min(), cs.get("rolling_rpm", cs["epicyclic_rpm"])) - 0.6 * span,
                max(inside.max(), cs.get("rolling_rpm", cs["epicyclic_rpm"])) + 0.6 * span)
    ax.legend(loc="lower right")
    return save(fig, folder, "cage_speed.png")


def cage_centroid(run, s, folder):
    fig, (ax, ax2) = figure(run, "cage centre orbit", height=7.5, ncols=2)
    w = s["window"]
    first = len(run.time) - w["samples"]
    x, y = 1e6 * run.cage_xy[:, 0], 1e6 * run.cage_xy[:, 1]
    ax.plot(x[:first + 1], y[:first + 1], lw=0.5, color="0.7", label="before the window")
    pts = ax.scatter(x[first:], y[first:], c=run.time[first:], s=3, cmap="viridis", label="window")
    fig.colorbar(pts, ax=ax, label="time [s]")
    c = s["cage_centroid"]
    land = c.get("land_clearance_m") or 0.0
    if land and math.isfinite(land) and land > 0:
        th = np.linspace(0, 2 * math.pi, 361)
        ax.plot(1e6 * land * np.cos(th), 1e6 * land * np.sin(th), "k--", lw=1, label="land clearance")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [um]")
    ax.set_ylabel("y [um]")
    ax.set_title(f"vortex radius {1e6 * c['vortex_radius_mean_m']:.3g} um (mean), whirl "
                 f"{c['whirl_to_cage_speed_ratio']:.3g} x cage speed" if c.get("whirl") == "whirling"
                 else textwrap.fill(c.get("whirl_note", "centre"), 70), fontsize=10 if c.get("whirl") != "whirling" else None)
    ax.legend(loc="upper right", fontsize=9)
    r = np.hypot(x - 1e6 * c["centre_x_m"], y - 1e6 * c["centre_y_m"])
    ax2.plot(run.time, r, lw=0.7)
    shade_window(ax2, s)
    scale_to_window(ax2, run, s, r)
    ax2.set_xlabel("time [s]")
    ax2.set_ylabel("distance from the vortex centre [um]")
    ax2.axvline(c["vortex_window_start_s"], color="k", lw=0.8, ls=":")  # the vortex metrics' whole turns
    return save(fig, folder, "cage_centroid.png")


def element_load(run, s, folder):
    e = run.element
    fig, ax = figure(run, f"inner-race {e} load against azimuth (window)")
    az = s["azimuth"]
    centre = np.asarray(az["bin_centre_deg"], dtype=float)
    get = lambda k: np.asarray([math.nan if v is None else v for v in az[f"{e}_load_{k}_n"]], dtype=float)
    ax.fill_between(centre, get("min"), get("max"), color="tab:orange", alpha=0.25, step="mid", label="range (min-max)")
    ax.plot(centre, get("mean"), "o-", color="tab:orange", ms=3, label="time mean per bin")
    ld = s[f"{e}_load"]
    if ld["loaded_all_round"]:
        ax.set_title("loaded all round")
    elif ld["load_zone_width_deg"] is not None and math.isfinite(ld["load_zone_width_deg"]):
        ax.set_title(f"load zone {ld['load_zone_width_deg']:.0f} deg wide, centred at {ld['load_zone_centre_deg']:.0f} deg")
    ax.axhline(ld["largest_mean_n"], color="k", ls="--", lw=1,
               label=f"largest {e} load, window mean {ld['largest_mean_n']:.4g} N (peak {ld['max_n']:.4g} N)")
    ax.set_xlim(0, 360)
    ax.set_xticks(range(0, 361, 30))
    ax.set_xlabel("azimuth of the element centre [deg] (0 = +x, counter-clockwise)")
    ax.set_ylabel("normal force on the inner race [N]")
    ax.legend(loc="upper left")
    return save(fig, folder, f"{e}_load_azimuth.png")


def pocket_force_time(run, s, folder):
    p = s["pocket_forces"]
    imp = p["impacts"]
    fig, ax = figure(run, f"pocket forces against time: all {len(run.time)} samples, {imp['count']} impacts marked")
    shade_window(ax, s)
    ax.plot(run.time, run.bar_front.max(axis=1), lw=0.6, color=FRONT, label="front bar (largest over pockets)")
    ax.plot(run.time, -run.bar_rear.max(axis=1), lw=0.6, color=REAR, label="rear bar (largest over pockets), drawn negative")
    drawn = [run.bar_front.max(axis=1), -run.bar_rear.max(axis=1)]
    if run.pocket_steps is not None:
        # The peak over every step of each output interval (drawn over the interval it closes):
        # the contacts the samples fall between still show at their height.
        for bar, sign, color in (("front", 1.0, FRONT), ("rear", -1.0, REAR)):
            peak = run.pocket_steps[bar]["peak_force"].max(axis=1)
            ax.plot(run.time, sign * peak, lw=0.5, alpha=0.45, color=color, drawstyle="steps-pre",
                    label=f"{bar} bar, peak between samples (every step)")
            drawn.append(sign * peak)
    t = np.asarray(imp["time_s"], dtype=float)
    f = np.asarray(imp["peak_n"], dtype=float)
    front = np.asarray([b == "front" for b in imp["bar"]], dtype=bool)
    ax.plot(t[front], f[front], "v", color=FRONT, ms=5, label=f"front impact peaks ({int(front.sum())})")
    ax.plot(t[~front], -f[~front], "^", color=REAR, ms=5, label=f"rear impact peaks ({int((~front).sum())})")
    ax.axhline(0, color="k", lw=0.5)
    scale_to_window(ax, run, s, *drawn)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("bar normal force [N] (rear < 0)")
    ax.set_title(f"contact threshold {p['threshold_n']:.3g} N; front = the bar ahead in the cage's sense of rotation")
    ax.legend(loc="upper right", fontsize=9)
    return save(fig, folder, "pocket_force_time.png")


def pocket_force_azimuth(run, s, folder):
    az = s["azimuth"]
    fig, ax = figure(run, "pocket forces against the pocket's azimuth (window)")
    centre = np.asarray(az["bin_centre_deg"], dtype=float)
    arr = lambda k: np.asarray([math.nan if v is None else v for v in az[k]], dtype=float)
    for bar, colour in (("front", FRONT), ("rear", REAR)):
        ax.plot(centre, arr(f"{bar}_force_mean_n"), "o-", ms=3, color=colour, label=f"{bar} bar, time mean per bin")
        ax.plot(centre, arr(f"{bar}_force_max_n"), "--", lw=1, color=colour, label=f"{bar} bar, peak per bin")
    ax.set_xlim(0, 360)
    ax.set_xticks(range(0, 361, 30))
    ax.set_xlabel("azimuth of the pocket [deg]")
    ax.set_ylabel("bar normal force [N]")
    ax.legend(loc="upper right")
    return save(fig, folder, "pocket_force_azimuth.png")


def _per_kind(run, s, folder, name, what, ylabel, value, scale):
    fig, ax = figure(run, what)
    shade_window(ax, s)
    drawn = []
    for kind, seg in run.contact.items():
        y = value(seg)
        if y is None or not np.any(np.isfinite(y)) or not np.any(y != 0):
            continue
        ax.plot(run.time, scale * y, lw=0.8, label=kind)
        drawn.append(scale * y)
    if not drawn:
        plt.close(fig)
        return None
    scale_to_window(ax, run, s, *drawn)
    ax.set_xlabel("time [s]")
    ax.set_ylabel(ylabel)
    ax.legend(loc="upper right")
    return save(fig, folder, name)


def _loaded(seg, key, reduce):
    if key not in seg:
        return None
    q = seg["normal_force"]
    return reduce(np.where(q > 0, seg[key], np.nan), axis=1)


def contact_pressure(run, s, folder):
    return _per_kind(run, s, folder, "contact_pressure.png", "largest Hertz contact pressure per contact kind",
                     "max pressure [GPa]", lambda seg: _loaded(seg, "max_pressure", np.nanmax), 1e-9)


def film_thickness(run, s, folder):
    return _per_kind(run, s, folder, "film_thickness.png", "thinnest central film of the loaded contacts",
                     "film thickness [um]", lambda seg: _loaded(seg, "film_thickness", np.nanmin), 1e6)


def contact_angle(run, s, folder):
    """Omitted where every angle is below the model's resolution (rm.contact_angle_resolution); the
    angles below it are drawn as 0."""
    resolution = rm.contact_angle_resolution(run.geometry)
    floor = resolution if math.isfinite(resolution) else 0.0

    def weighted(seg):
        if "contact_angle" not in seg or not np.any(seg["contact_angle"]):
            return None
        q = seg["normal_force"]
        total = q.sum(axis=1)
        a = np.where(total > 0, (q * np.abs(seg["contact_angle"])).sum(axis=1) / np.where(total > 0, total, 1), np.nan)
        return np.where(a > floor, a, np.where(np.isfinite(a), 0.0, np.nan))
    what = "load-weighted mean contact angle of the groove contacts"
    if math.isfinite(resolution):
        what += f" (below the model's resolution, {resolution * 180 / math.pi:.2g} deg: 0)"
    return _per_kind(run, s, folder, "contact_angle.png", what, "contact angle [deg]", weighted, 180 / math.pi)


def cage_land(run, s, folder):
    fig, ax = figure(run, "cage-land force (guiding ring)")
    shade_window(ax, s)
    cl = s["cage_land"]
    ax.plot(run.time, run.land_force, lw=0.7, color="tab:purple",
            label=f"land normal force (window mean {cl['force_mean_n']:.4g} N, peak {cl['force_peak_n']:.4g} N)")
    scale_to_window(ax, run, s, run.land_force)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("normal force [N]")
    ax.legend(loc="upper right")
    return save(fig, folder, "cage_land_force.png")


def friction(run, s, folder):
    fr = s["friction"]
    fig, (ax, ax2) = figure(run, "friction torque and power loss", ncols=2)
    if run.driven_moment is not None:
        sign = 1.0 if np.mean(run.driven_speed) >= 0 else -1.0
        ax.plot(run.time, -sign * run.driven_moment * 1e3, lw=0.6,
                label=f"contacts' moment against the {fr['driven_ring']}'s rotation "
                      f"(window mean {1e3 * fr['friction_torque_mean_n_m']:.4g} mN m)")
        shade_window(ax, s)
        scale_to_window(ax, run, s, -sign * run.driven_moment * 1e3)
        ax.set_ylabel("friction torque [mN m]")
        ax.set_xlabel("time [s]")
        ax.legend(loc="upper right", fontsize=9)
    for kind, p in run.power_loss.items():
        ax2.plot(run.time, p, lw=0.7, label=f"{kind} ({fr.get(kind + '_power_loss_mean_w', math.nan):.4g} W mean)")
    shade_window(ax2, s)
    scale_to_window(ax2, run, s, *run.power_loss.values())
    ax2.set_xlabel("time [s]")
    ax2.set_ylabel("power loss [W]")
    ax2.legend(loc="upper right", fontsize=9)
    return save(fig, folder, "friction.png")


def bridge_force_time(run, s, folder):
    b = s["cage_bridges"]
    f = run.bridge_force
    fig, ax = figure(run, f"cage bridge forces against time ({b['model']} bridges)")
    shade_window(ax, s)
    ax.plot(run.time, np.max(np.abs(f), axis=1), lw=0.6, color="0.4", label="largest |force| over the bridges")
    ax.plot(run.time, f[:, 0], lw=0.8, color="tab:green", label="bridge 0 (+: pushed in +z)")
    scale_to_window(ax, run, s, np.max(np.abs(f), axis=1), f[:, 0])
    ax.axhline(b["median_1ms_max_n"], color="k", ls="--", lw=1,
               label=f"median of the 1 ms maxima in the window, {b['median_1ms_max_n']:.4g} N (peak {b['peak_n']:.4g} N)")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("bridge force [N]")
    ax.legend(loc="upper right", fontsize=9)
    return save(fig, folder, "bridge_force_time.png")


def bridge_force_azimuth(run, s, folder):
    b = s["cage_bridges"]
    fig, ax = figure(run, f"cage bridge |force| against the bridge's azimuth, window ({b['model']} bridges)")
    centre = np.asarray(b["bin_centre_deg"], dtype=float)
    arr = lambda key: np.asarray([math.nan if v is None else v for v in b[key]], dtype=float)
    ax.plot(centre, arr("abs_force_mean_n"), "o-", ms=3, color="tab:green", label="time mean per bin")
    ax.plot(centre, arr("abs_force_max_n"), "--", lw=1, color="tab:green", label="peak per bin")
    ax.set_xlim(0, 360)
    ax.set_xticks(range(0, 361, 30))
    ax.set_xlabel("azimuth of the bridge [deg] (bearing frame, 0 = +x, counter-clockwise)")
    ax.set_ylabel("|bridge force| [N]")
    ax.legend(loc="upper right")
    return save(fig, folder, "bridge_force_azimuth.png")


def draw_all(run, summary, folder):
    """Every figure the run has data for; returns (names written, failure texts)."""
    plots = [cage_speed, cage_centroid, element_load]
    if "pocket_forces" in summary:
        plots += [pocket_force_time, pocket_force_azimuth]
    if run.contact:
        plots += [contact_angle, contact_pressure, film_thickness]
    if "cage_bridges" in summary:
        plots += [bridge_force_time, bridge_force_azimuth]
    if "cage_land" in summary:
        plots.append(cage_land)
    if "friction" in summary:
        plots.append(friction)
    import report_rollers_plots  # imports this module's helpers
    plots += report_rollers_plots.plots(summary)
    written, failures = [], []
    for plot in plots:
        try:
            name = plot(run, summary, folder)
            if name:
                written.append(name)
        except Exception:  # one failed figure must not stop the others; the report says which
            failures.append(f"{plot.__name__}: {traceback.format_exc(limit=3)}")
            plt.close("all")
    return written, failures
