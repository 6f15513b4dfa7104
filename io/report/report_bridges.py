"""Cage bridge forces of a planar roller bearing run (seed 003): their metrics.

A bridge is the bar between two pockets: bridge k lies between pocket k (whose front bar it is) and
pocket k + 1 (whose rear bar it is), at the cage-frame angle 2 pi (k + 1/2) / Z. Its force is
signed, positive in the +z sense of rotation:
  - flexible bridges ([cage] bridges = "flexible"): the bridge spring's force, the dataset
    /segments/cage_bridge/normal_force (k u, with u the bridge's tangential deflection);
  - rigid bridges: the pocket forces on the bar, front[k] - rear[k + 1] (the file's front and rear,
    ahead and behind in +z).
The summary gives the peak |force| (time, bridge, azimuth), the median over the window of the
largest |force| of each 1 ms, and per-azimuth bins of |force|; the figures (report_plots.py) show the
forces against time and against the bridge's azimuth in the bearing frame.
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

