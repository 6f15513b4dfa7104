"""Cage and rolling-element metrics of `raceway report`: pure functions on numpy arrays (no files).

All quantities are SI (s, m, m/s, rad, rad/s, N, N s) unless a name says otherwise (`_rpm`, `_deg`).

Time integrals over a window use the trapezoid rule. Its weights w_i (half the sum of the two
intervals next to sample i, half an interval at the window's ends, summing to the window length)
are used for every time-based quantity, so they are mutually consistent:
    impulse = sum_i w_i |F_i|,  contact time = sum_{i in contact} w_i,
    RMS = sqrt(sum_i w_i F_i^2 / window length),  duty cycle = contact time / window length.
For a sampled square pulse of height F lasting k samples (zeros on both sides) this gives an
impulse F k dt and a duration k dt exactly: each sample stands for one interval dt.

Plain means (cage speed, centroid statistics, loads) are sample means, like the run summary's
`cage_speed_rpm`, because output times are equally spaced.

Functions return NaN for what is undefined on the data (a zero mean speed, an empty bin, no
contact); they raise ValueError for inconsistent inputs (an empty window, a bad bin width).
"""
import math
from dataclasses import dataclass

import numpy as np

TWO_PI = 2 * math.pi
RPM = 60.0 / TWO_PI  # rad/s -> rpm


@dataclass
class Window:
    """Samples [begin, end) of the time series that form the analysis window."""
    begin: int
    end: int
    t_begin: float
    t_end: float
    default_second_half: bool

    @property
    def samples(self):
        return self.end - self.begin

    @property
    def length(self):
        return self.t_end - self.t_begin

    @property
    def slice(self):
        return slice(self.begin, self.end)


def select_window(time, start=None):
    """The samples with time >= start or, by default, the second half of the run (time >= t0 + (t1 -
    t0) / 2, the run summary's "second half"); 1e-9 of the run length keeps a sample on the edge."""
    t = np.asarray(time, dtype=float)
    if t.size < 2:
        raise ValueError("fewer than 2 output times")
    if not np.all(np.diff(t) > 0):
        raise ValueError("output times are not increasing")
    t0, t1 = t[0], t[-1]
    start_time = t0 + 0.5 * (t1 - t0) if start is None else start
    begin = int(np.searchsorted(t, start_time - 1e-9 * (t1 - t0), side="left"))
    if t.size - begin < 2:
        raise ValueError(f"fewer than 2 output times at or after the window start {start_time:g} s "
                         f"(run ends at {t1:g} s)")
    return Window(begin, t.size, float(t[begin]), float(t1), start is None)


def trapezoid_weights(time, window):
    t = np.asarray(time, dtype=float)[window.slice]
    h = 0.5 * np.diff(t)
    w = np.zeros(t.size)
    w[:-1] += h
    w[1:] += h
    return w


def ratio_or_nan(num, den):
    return num / den if den != 0 and math.isfinite(den) else math.nan


# ---- cage speed ----------------------------------------------------------------------------------

def speed_stats(cage_speed, kinematic_speed, window):
    """Sample means over the window of the cage speed and a kinematic reference speed, the slip
    1 - cage / kinematic, and the cage speed's extremes."""
    c = np.asarray(cage_speed, dtype=float)[window.slice]
    k = np.asarray(kinematic_speed, dtype=float)[window.slice]
    mean_c, mean_k = float(np.mean(c)), float(np.mean(k))
    return {"mean_rad_s": mean_c, "mean_rpm": mean_c * RPM, "min_rad_s": float(c.min()), "max_rad_s": float(c.max()),
            "kinematic_rad_s": mean_k, "kinematic_rpm": mean_k * RPM,
            "slip": 1.0 - mean_c / mean_k if mean_k != 0 else math.nan}


def cage_direction(mean_speed):
    """+1 for a cage turning in +z (also for 0 or NaN), -1 in -z."""
    return -1 if mean_speed < 0 else 1


# ---- cage centroid (seed 001 section 4) ---------------------------------------------------------

def whole_turn_window(time, x, y, window):
    """The longest end of `window` in which the centre sweeps a whole number (>= 1) of turns about
    the window's mean centre, and that number; (`window`, 0) when it holds less than one turn.

    Over whole turns the mean of the samples is the orbit's centre (for a circle or an ellipse swept
    at a steady rate); over a part-swept one it is not: the mean of a circle swept 4.5 times lies
    1 / (4.5 pi) = 0.071 of its radius off the centre, which alone gives a vortex radius ratio of 0.14."""
    s = window.slice
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    phi = np.unwrap(np.arctan2(y[s] - np.mean(y[s]), x[s] - np.mean(x[s])))
    swept_from = np.abs(phi[-1] - phi)  # angle swept from each sample to the window's end
    # Each sample stands for one output interval, so n samples stand for the angle of n - 1 steps
    # plus one: N samples a period apart of N hold one turn exactly, and their mean is its centre.
    step = swept_from[0] / (len(swept_from) - 1)
    turns = math.floor((swept_from[0] + step) / TWO_PI * (1 + 1e-9))
    if turns < 1:
        return window, 0
    begin = window.begin + int(np.argmin(np.abs(swept_from + step - turns * TWO_PI)))
    return Window(begin, window.end, float(np.asarray(time, dtype=float)[begin]), window.t_end, False), turns


def centroid_metrics(time, x, y, vx, vy, window, cage_speed_mean):
    """Vortex metrics of the cage centre (seed 001 section 4, eq. 9), over the whole whirl turns at
    the end of the window (whole_turn_window; the whole window when it holds less than one turn):
    the vortex radius is the distance from the mean centre of those turns (a radial load shifts
    the orbit), its ratio (max - min) / mean; sigma_v = std / mean of the centre speed |v| over the
    same samples. The axis_ radius is about the bearing axis over the whole window. Whirl: mean rate
    of the unwrapped angle about the vortex centre over the whole window, + counter-clockwise."""
    x, y, vx, vy = (np.asarray(a, dtype=float) for a in (x, y, vx, vy))
    s = window.slice
    vortex, turns = whole_turn_window(time, x, y, window)
    v = vortex.slice
    cx, cy = float(np.mean(x[v])), float(np.mean(y[v]))
    m = {"centre_x_m": cx, "centre_y_m": cy, "vortex_turns": turns, "vortex_window_start_s": vortex.t_begin,
         "vortex_window_s": vortex.length}
    for prefix, (ox, oy), w in (("vortex_radius", (cx, cy), v), ("axis_radius", (0.0, 0.0), s)):
        r = np.hypot(x[w] - ox, y[w] - oy)
        mean = float(np.mean(r))
        m.update({f"{prefix}_mean_m": mean, f"{prefix}_min_m": float(r.min()), f"{prefix}_max_m": float(r.max()),
                  f"{prefix}_ratio": ratio_or_nan(float(r.max() - r.min()), mean)})
    speed = np.hypot(vx[v], vy[v])
    m["speed_mean_m_s"] = float(np.mean(speed))
    m["speed_std_m_s"] = float(np.std(speed, ddof=1))
    m["sigma_v"] = ratio_or_nan(m["speed_std_m_s"], m["speed_mean_m_s"])
    phi = np.arctan2(y[s] - cy, x[s] - cx)
    swept = float(np.sum(np.remainder(np.diff(phi) + math.pi, TWO_PI) - math.pi))
    # A centre that does not move (radii at the rounding level of its coordinates) has no whirl.
    if not m["vortex_radius_max_m"] > 64 * np.finfo(float).eps * (abs(cx) + abs(cy)):
        m["vortex_radius_ratio"] = math.nan
        swept = math.nan
    whirl = swept / window.length
    m.update({"whirl_frequency_rad_s": whirl, "whirl_frequency_hz": whirl / TWO_PI,
              "whirl_to_cage_speed_ratio": ratio_or_nan(whirl, cage_speed_mean), "whirl_revolutions": swept / TWO_PI})
    return m


WHIRL_KEYS = ("vortex_radius_mean_m", "vortex_radius_min_m", "vortex_radius_max_m", "vortex_radius_ratio",
              "speed_mean_m_s", "speed_std_m_s", "sigma_v", "whirl_frequency_rad_s", "whirl_frequency_hz",
              "whirl_to_cage_speed_ratio", "whirl_revolutions")
#: Land contact in at least this share of the window's samples, with no whole whirl turn: pinned.
PINNED_LAND_CONTACT = 0.9


def whirl_state(m, land_contact_fraction=None):
    """Whether the vortex metrics (centroid_metrics `m`) mean anything for the cage's motion: they
    describe a centre orbiting its vortex centre, so they need at least one whole whirl turn in the
    window (vortex_turns, and net about the vortex centre, whirl_revolutions). Returns {"whirl":
    state, "whirl_note": why} and, unless the cage whirls, NaN for every vortex and whirl metric
    (WHIRL_KEYS): "still" (the centre does not move), "pinned_on_land" (the cage touches its
    guiding land in >= 90 % of the window's samples and turns less than once about its centre),
    "no_whirl" (less than one whole turn), "whirling"."""
    swept = m.get("whirl_revolutions", math.nan)
    # Whole turns both ways: about the mean centre of the window's end (vortex_turns) and, net, about
    # the vortex centre over the whole window (whirl_revolutions).
    turns = min(m.get("vortex_turns", 0), math.floor(abs(swept)) if math.isfinite(swept) else 0)
    if not math.isfinite(m.get("vortex_radius_ratio", math.nan)) and not math.isfinite(swept):
        state, note = "still", "the cage centre does not move: no whirl, vortex metrics undefined"
    elif turns < 1 and land_contact_fraction is not None and land_contact_fraction >= PINNED_LAND_CONTACT:
        state = "pinned_on_land"
        note = (f"the cage is pinned on its land (land contact in {100 * land_contact_fraction:.0f} % of the window, "
                f"{abs(swept):.2g} turns about its centre): no whirl, vortex metrics undefined")
    elif turns < 1:
        state = "no_whirl"
        land = "" if land_contact_fraction is None else \
            f" (on its land in {100 * land_contact_fraction:.0f} % of the window)"
        note = (f"the cage centre turns {abs(swept):.2g} times about its vortex centre in the window{land}, less than "
                "once: no whirl, vortex metrics undefined")
    else:
        return {"whirl": "whirling", "whirl_note": f"{turns} whole whirl turns in the window"}
    out = {"whirl": state, "whirl_note": note}
    out.update({k: math.nan for k in WHIRL_KEYS})
    return out


# ---- contact angle --------------------------------------------------------------------------------

def contact_angle_resolution(geometry):
    """The smallest contact angle [rad] the model resolves: the integrator's absolute tolerance on the
    rolling elements' positions over the distance from the ball centre to a groove's curvature
    centre, (f - 1/2) D = groove radius - ball radius (the contact angle is the direction of that
    line; an error of the tolerance across it turns it by tolerance / distance). The nearer groove
    sets it. NaN when the geometry is not known (no ball grooves)."""
    tol = geometry.get("element_position_tolerance", math.nan)
    r = geometry.get("element_radius", math.nan)
    arms = [geometry.get(k, math.nan) - r for k in ("inner_groove_radius", "outer_groove_radius")]
    arms = [a for a in arms if math.isfinite(a) and a > 0]
    return tol / min(arms) if arms and math.isfinite(tol) and tol > 0 else math.nan


def above_resolution(angle, resolution):
    """`angle` where it exceeds `resolution` (in magnitude), else 0 (NaN stays NaN; NaN resolution: angle)."""
    if not math.isfinite(angle) or not math.isfinite(resolution):
        return angle
    return angle if abs(angle) > resolution else 0.0


# ---- pocket (bar) forces --------------------------------------------------------------------------

def split_bar_forces(normal_force, circumferential_force, ball, pockets, direction):
    """Spatial pockets onto bars: column c's normal force goes to the front bar (ahead in the sense of
    rotation) when circumferential_force * direction < 0, else to the rear bar (docs/output_layout.md);
    columns of one pocket add up. Returns front, rear [T x pockets]."""
    fn = np.asarray(normal_force, dtype=float)
    fc = np.asarray(circumferential_force, dtype=float)
    front = np.zeros((fn.shape[0], pockets))
    rear = np.zeros((fn.shape[0], pockets))
    touching = fn > 0
    for c, k in enumerate(np.asarray(ball, dtype=int)):
        on_front = touching[:, c] & (fc[:, c] * direction < 0)
        front[:, k] += np.where(on_front, fn[:, c], 0.0)
        rear[:, k] += np.where(touching[:, c] & ~on_front, fn[:, c], 0.0)
    return front, rear


def contact_runs(force, threshold):
    """(first, last) sample of each run of consecutive samples with |force| > threshold."""
    on = np.abs(np.asarray(force, dtype=float)) > threshold
    edges = np.diff(np.concatenate([[0], on.astype(np.int8), [0]]))
    return list(zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1) - 1))


def contact_stats(time, force, window, threshold):
    """RMS, peak, impulse, events (runs above the threshold; one going on at the window's start
    counts), contact time, mean duration and duty cycle of one bar's force over the window."""
    f = np.abs(np.asarray(force, dtype=float)[window.slice])
    w = trapezoid_weights(time, window)
    on = f > threshold
    events = len(contact_runs(f, threshold))
    contact_time = float(np.sum(w[on]))
    return {"rms_n": math.sqrt(float(np.sum(w * f * f)) / window.length), "peak_n": float(f.max(initial=0.0)),
            "impulse_n_s": float(np.sum(w * f)), "events": events, "contact_time_s": contact_time,
            "mean_duration_s": contact_time / events if events else math.nan,
            "duty_cycle": contact_time / window.length}


def step_contact_stats(steps, k, window):
    """Peak, impulse, events (contact onsets), contact time, mean duration and duty cycle of one bar of
    pocket k over the window from the step-resolved statistics (/cage/pocket_step_*: each row the
    steps of the output interval ending at its sample), so from every integrator step rather than
    from the samples: the rows of the intervals inside the window, (t_begin, t_end]. An onset is the
    force going from 0 to > 0 between two steps (no threshold); a contact going on at the window's
    start is not one. `steps`: {"onsets", "peak_force", "impulse", "contact_time": [T x pockets]}."""
    rows = slice(window.begin + 1, window.end)
    events = int(round(float(np.sum(steps["onsets"][rows, k]))))
    contact_time = float(np.sum(steps["contact_time"][rows, k]))
    return {"peak_n": float(np.max(steps["peak_force"][rows, k], initial=0.0)),
            "impulse_n_s": float(np.sum(steps["impulse"][rows, k])), "events": events, "contact_time_s": contact_time,
            "mean_duration_s": contact_time / events if events else math.nan,
            "duty_cycle": contact_time / window.length}


def total_stats(per_pocket, window):
    """Totals over pockets: events, impulse, contact time summed; peak the max; RMS the root of the
    mean of the mean squares; duty cycle the mean; mean duration contact time / events."""
    n = len(per_pocket)
    t = {"rms_n": math.sqrt(sum(p["rms_n"] ** 2 for p in per_pocket) / n) if n else math.nan,
         "peak_n": max((p["peak_n"] for p in per_pocket), default=0.0),
         "impulse_n_s": sum(p["impulse_n_s"] for p in per_pocket),
         "events": sum(p["events"] for p in per_pocket),
         "contact_time_s": sum(p["contact_time_s"] for p in per_pocket)}
    t["mean_duration_s"] = t["contact_time_s"] / t["events"] if t["events"] else math.nan
    t["duty_cycle"] = t["contact_time_s"] / (n * window.length) if n else math.nan
    return t


def default_contact_threshold(front, rear, window):
    """1 % of the peak bar force over the window, at least 1e-3 N."""
    peak = max(float(np.max(np.abs(front[window.slice]), initial=0.0)),
               float(np.max(np.abs(rear[window.slice]), initial=0.0)))
    return max(0.01 * peak, 1e-3)


def impacts(time, front, rear, threshold):
    """Every impact of the whole run, one per run of samples above the threshold on one bar of one
    pocket: its time and force at the peak sample, pocket, bar ("front"/"rear"), duration (s)."""
    t = np.asarray(time, dtype=float)
    out = []
    for bar, forces in (("front", front), ("rear", rear)):
        for k in range(forces.shape[1]):
            for a, b in contact_runs(forces[:, k], threshold):
                i = a + int(np.argmax(forces[a:b + 1, k]))
                out.append((float(t[i]), float(forces[i, k]), k, bar, float(t[b] - t[a])))
    out.sort()
    return {"count": len(out), "time_s": [o[0] for o in out], "peak_n": [o[1] for o in out],
            "pocket": [o[2] for o in out], "bar": [o[3] for o in out], "duration_s": [o[4] for o in out]}


# ---- azimuth --------------------------------------------------------------------------------------

def azimuth(x, y):
    """atan2(y, x) in [0, 2 pi)."""
    a = np.mod(np.arctan2(y, x), TWO_PI)
    return np.where(a >= TWO_PI, 0.0, a)


def bin_count(width):
    if not (width > 0 and width <= TWO_PI * (1 + 1e-12)):
        raise ValueError("the azimuth bin width must be in (0, 360] deg")
    q = TWO_PI / width
    return int(round(q)) if abs(q - round(q)) < 1e-9 * q else int(math.ceil(q))


def bin_by_azimuth(az, value, width):
    """Mean, min, max and count of value per azimuth bin [k w, (k + 1) w) (the last ends at 2 pi);
    non-finite values are skipped; empty bins hold NaN."""
    n = bin_count(width)
    az = np.ravel(az)
    v = np.ravel(value)
    ok = np.isfinite(az) & np.isfinite(v)
    k = np.minimum((np.mod(az[ok], TWO_PI) / width).astype(int), n - 1)
    v = v[ok]
    count = np.bincount(k, minlength=n)
    total = np.bincount(k, weights=v, minlength=n)
    lo = np.full(n, np.inf)
    hi = np.full(n, -np.inf)
    np.minimum.at(lo, k, v)
    np.maximum.at(hi, k, v)
    empty = count == 0
    lower = np.arange(n) * width
    upper = np.append(lower[1:], TWO_PI)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = np.where(empty, np.nan, total / np.maximum(count, 1))
    return {"lower": lower, "upper": upper, "centre": 0.5 * (lower + upper), "count": count, "mean": mean,
            "min": np.where(empty, np.nan, lo), "max": np.where(empty, np.nan, hi)}


def load_zone(bins, threshold):
    """The widest circular run of bins whose mean exceeds the threshold; empty bins inside a run do
    not break it. Returns start, end (outer edges, rad; end < start when it wraps through 0),
    width, centre and all_round (no unloaded bin). No loaded bin: NaNs."""
    mean, count = bins["mean"], bins["count"]
    n = mean.size
    empty = (count == 0) | np.isnan(mean)
    loaded = ~empty & (mean > threshold)
    unloaded = ~empty & ~loaded
    nan = {"start": math.nan, "end": math.nan, "width": math.nan, "centre": math.nan, "all_round": False}
    if not loaded.any():
        return nan
    if not unloaded.any():
        return {"start": 0.0, "end": TWO_PI, "width": TWO_PI, "centre": math.pi, "all_round": True}
    best = None
    for k in range(n):
        if unloaded[k] or not unloaded[(k - 1) % n]:
            continue
        length = 0
        while length < n and not unloaded[(k + length) % n]:
            length += 1
        first, last = k, k + length - 1
        while first <= last and not loaded[first % n]:
            first += 1
        while last > first and not loaded[last % n]:
            last -= 1
        if first > last or not loaded[first % n]:
            continue
        width = sum(bins["upper"][j % n] - bins["lower"][j % n] for j in range(first, last + 1))
        if best is None or width > best[0]:
            best = (width, first % n, last % n)
    width, first, last = best
    start, end = bins["lower"][first], bins["upper"][last]
    return {"start": float(start), "end": float(end - TWO_PI if end >= TWO_PI else end), "width": float(width),
            "centre": float(math.fmod(start + 0.5 * width, TWO_PI)), "all_round": False}


def element_loads(normal_force, element, elements):
    """Per-element load [T x elements]: the columns of each element added (four-point: both arcs)."""
    fn = np.asarray(normal_force, dtype=float)
    out = np.zeros((fn.shape[0], elements))
    for c, k in enumerate(np.asarray(element, dtype=int)):
        out[:, k] += fn[:, c]
    return out


def time_mean(time, values, window):
    """Trapezoid time mean over the window along the first axis."""
    w = trapezoid_weights(time, window)
    v = np.asarray(values, dtype=float)[window.slice]
    return np.tensordot(w, v, axes=(0, 0)) / window.length
