"""Cage bridge forces of a planar roller bearing run (seed 003): metrics and figures.

A bridge is the bar between two pockets: bridge k lies between pocket k (whose front bar it is) and
pocket k + 1 (whose rear bar it is), at the cage-frame angle 2 pi (k + 1/2) / Z. Its force is
signed, positive in the +z sense of rotation:
  - flexible bridges ([cage] bridges = "flexible"): the bridge spring's force, the dataset
    /segments/cage_bridge/normal_force (k u, with u the bridge's tangential deflection);
  - rigid bridges: the pocket forces on the bar, front[k] - rear[k + 1] (the file's front and rear,
    ahead and behind in +z).
The summary gives the peak |force| (time, bridge, azimuth), the median over the window of the
largest |force| of each 1 ms, and per-azimuth bins of |force|; the figures show the forces against
time and against the bridge's azimuth in the bearing frame.
"""
import math

import numpy as np

import report_metrics as rm

DEG = 180.0 / math.pi


def bridge_forces(out):
    """(forces [T x Z] N, flexible) from an open RacewayOutput, or (None, False) without pocket bars."""
    if "segments/cage_bridge/normal_force" in out:
        return np.asarray(out["segments/cage_bridge/normal_force"], dtype=float), True
    if "segments/cage_bar_front/normal_force" not in out:
        return None, False
    front = np.asarray(out["segments/cage_bar_front/normal_force"], dtype=float)
    rear = np.asarray(out["segments/cage_bar_rear/normal_force"], dtype=float)
    return front - np.roll(rear, -1, axis=1), False


def bridge_azimuth(cage_angle, bridges):
    """[T x Z] azimuth of each bridge in the bearing frame, in [0, 2 pi)."""
    k = np.arange(bridges)
    return np.mod(np.asarray(cage_angle)[:, None] + 2.0 * math.pi * (k[None, :] + 0.5) / bridges, 2.0 * math.pi)


def interval_maxima(time, values, window, interval=1e-3):
    """The largest of `values` (any shape per sample) in each whole `interval` of the window."""
    t = np.asarray(time)[window.slice]
    v = np.abs(np.asarray(values)[window.slice]).reshape(len(t), -1).max(axis=1)
    edges = np.arange(t[0], t[-1] + 1e-12, interval)
    out = [float(v[(t >= a) & (t < a + interval)].max()) for a in edges[:-1] if np.any((t >= a) & (t < a + interval))]
    return out


def summarize_bridges(run, window, bin_width):
    """The "cage_bridges" entry of summary.json, or None when the run has no pocket bars."""
    f = run.bridge_force
    if f is None:
        return None
    a = np.abs(f[window.slice])
    i, k = np.unravel_index(int(np.argmax(a)), a.shape)
    az = bridge_azimuth(run.cage_angle, f.shape[1])
    bins = rm.bin_by_azimuth(az[window.slice], a, bin_width)
    maxima = interval_maxima(run.time, f, window)
    return {"model": "flexible" if run.bridges_flexible else "rigid",
            "peak_n": float(a[i, k]), "peak_time_s": float(run.time[window.begin + i]), "peak_bridge": int(k),
            "peak_azimuth_deg": float(az[window.begin + i, k]) * DEG,
            "median_1ms_max_n": float(np.median(maxima)) if maxima else math.nan,
            "mean_abs_n": float(np.mean(a)),
            "bin_centre_deg": list(bins["centre"] * DEG), "abs_force_mean_n": list(bins["mean"]),
            "abs_force_max_n": list(bins["max"]),
            "note": "|force| of the bridge spring (flexible) or of the pocket forces on the bar (rigid)"}


def bridge_force_time(run, s, folder):
    import report_plots as rp
    b = s["cage_bridges"]
    f = run.bridge_force
    fig, ax = rp.figure(run, f"cage bridge forces against time ({b['model']} bridges)")
    rp.shade_window(ax, s)
    ax.plot(run.time, np.max(np.abs(f), axis=1), lw=0.6, color="0.4", label="largest |force| over the bridges")
    ax.plot(run.time, f[:, 0], lw=0.8, color="tab:green", label="bridge 0 (+: pushed in +z)")
    rp.scale_to_window(ax, run, s, np.max(np.abs(f), axis=1), f[:, 0])
    ax.axhline(b["median_1ms_max_n"], color="k", ls="--", lw=1,
               label=f"median of the 1 ms maxima in the window, {b['median_1ms_max_n']:.4g} N (peak {b['peak_n']:.4g} N)")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("bridge force [N]")
    ax.legend(loc="upper right", fontsize=9)
    return rp.save(fig, folder, "bridge_force_time.png")


def bridge_force_azimuth(run, s, folder):
    import report_plots as rp
    b = s["cage_bridges"]
    fig, ax = rp.figure(run, f"cage bridge |force| against the bridge's azimuth, window ({b['model']} bridges)")
    centre = np.asarray(b["bin_centre_deg"], dtype=float)
    arr = lambda key: np.asarray([math.nan if v is None else v for v in b[key]], dtype=float)
    ax.plot(centre, arr("abs_force_mean_n"), "o-", ms=3, color="tab:green", label="time mean per bin")
    ax.plot(centre, arr("abs_force_max_n"), "--", lw=1, color="tab:green", label="peak per bin")
    ax.set_xlim(0, 360)
    ax.set_xticks(range(0, 361, 30))
    ax.set_xlabel("azimuth of the bridge [deg] (bearing frame, 0 = +x, counter-clockwise)")
    ax.set_ylabel("|bridge force| [N]")
    ax.legend(loc="upper right")
    return rp.save(fig, folder, "bridge_force_azimuth.png")
