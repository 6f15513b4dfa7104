"""The cage's motion over a window, classified: stable, circling or unstable (docs/atlas.md).

Inputs are plain arrays in SI (the cage centre's path in the bearing's radial plane, the cage's
speed about the axis, the guiding clearance, the pocket impacts), so the classification runs on a
run's output (classify_output) and on synthetic orbits alike (tests/io/report/atlas_test.py).

The metrics:

- orbit ratio rho = rms distance of the centre from its mean position / guiding clearance (the
  cage's radial play: the land clearance of a land-guided cage, else the pocket clearance);
- whirl: the angle the centre sweeps about its mean position (unwrapped), whole turns of it, its
  mean rate and that rate over the cage's mean speed (whirl-frequency / cage-frequency ratio,
  signed: +1 a whirl turning with the cage at its speed, whichever way the cage turns);
- seed 001's irregularity metrics (section 4, eq. 9): the vortex radius ratio (max - min) / mean of
  the centre's distance from its mean position, and the velocity deviation sigma_v = std / mean of
  the centre's speed, both over the window's last whole whirl turns (report_metrics.whole_turn_window,
  as the report; the whole window when it holds less than one turn);
- the pocket impacts (window_impacts): new bar engagements per pocket and per cage revolution (the
  impact rate) and the mean impact energy, the kinetic energy an impact's impulse J gives the free
  cage, J^2 / (2 m), also as a ratio to the kinetic energy of the cage's centre orbiting at the
  guiding clearance at the cage's speed, m (Omega c)^2 / 2 (the impact energy ratio);
- the cage dynamics indicator (CDI), ours, in the spirit of Schwarz et al. (Tribology Transactions,
  2022; docs/references.md), not their definition: min(1, rho) x (1 - p), where p is the share of
  the centre's displacement power (its discrete spectrum, the mean removed) in the strongest whirl
  line and its two neighbours. A settled centre has a small rho, a regular whirl puts nearly all
  its power in one line (p near 1): both give a CDI near 0; an irregular orbit over the clearance
  spreads its power (p small) and gives a CDI towards 1.

The classes (THRESHOLDS, each overridable):

- stable: rho < stable_orbit_ratio and no hard impacting: not (more than impact_rate_max impacts per
  pocket and cage revolution with an impact energy ratio above impact_energy_ratio_min; the rate
  alone where the energy is unknown);
- circling: a regular whirl: at least circling_min_turns whole turns, vortex radius ratio at most
  circling_vortex_ratio, sigma_v at most circling_sigma_v, no hard impacting;
- unstable: everything else (an irregular orbit or frequent pocket impacts); `reasons` says which
  criteria decided;
- unknown: no guiding clearance to scale the orbit by.

`raceway report` puts motion_summary's object into summary.json (`cage_motion`) and the campaign
table its class and indicator; the atlas (docs/atlas.md) classifies its points with it.
"""
import math

import numpy as np

import report_metrics as rm

TWO_PI = 2.0 * math.pi

THRESHOLDS = {
    "stable_orbit_ratio": 0.2,     # rms orbit radius / clearance below it: a settled centre
    "circling_min_turns": 1,       # whole whirl turns a circling cage makes in the window
    "circling_vortex_ratio": 0.5,  # seed 001's vortex radius ratio at most this for a regular whirl
    "circling_sigma_v": 0.5,       # seed 001's velocity deviation at most this for a regular whirl
    "impact_rate_max": 1.0,        # pocket impacts per pocket and cage revolution at most (stable, circling) ...
    "impact_energy_ratio_min": 0.1,  # ... unless their energy is below this share of the whirl energy
    "whirl_growth_rate": 0.005,    # a sub-synchronous whirl growing faster (per cage revolution) ...
    "whirl_growth_min_amplitude": 0.01,  # ... at an amplitude of at least this share of the clearance: unstable
    "whirl_sustained_amplitude": 0.05,  # a sub-synchronous whirl this large (share of the clearance), not decaying: unstable
}

# The sub-synchronous band (whirl frequency / cage frequency, either direction) where an oil whirl
# lies, the window's segments for its growth and the cage revolutions a segment needs at least
# (its spectrum resolves 1 / revolutions of the cage's frequency: 4 separate half speed from 0 and 1).
SUBSYNC_BAND = (0.2, 0.8)
SUBSYNC_SEGMENTS = 4
SUBSYNC_MIN_REVOLUTIONS = 4.0

CLASSES = ("stable", "circling", "unstable")


def thresholds(overrides=None):
    """THRESHOLDS with `overrides` (a dict of some of its keys) applied; an unknown key is a ValueError."""
    t = dict(THRESHOLDS)
    for key, value in (overrides or {}).items():
        if key not in t:
            raise ValueError(f"unknown threshold '{key}' (known: {', '.join(THRESHOLDS)})")
        t[key] = float(value)
    return t


def _ratio(num, den):
    return num / den if den > 0 and math.isfinite(den) else math.nan


def whirl_metrics(time, x, y, cage_speed_mean):
    """Turns, rate and rate / cage speed of the centre's angle about its mean position."""
    cx, cy = float(np.mean(x)), float(np.mean(y))
    phi = np.arctan2(y - cy, x - cx)
    swept = float(np.sum(np.remainder(np.diff(phi) + math.pi, TWO_PI) - math.pi))
    duration = float(time[-1] - time[0])
    rate = swept / duration if duration > 0 else math.nan
    # Signed: +1 for a whirl turning with the cage at its speed, whichever way the cage turns.
    ratio = rate / cage_speed_mean if cage_speed_mean and math.isfinite(cage_speed_mean) else math.nan
    return {"whirl_turns": int(math.floor(abs(swept) / TWO_PI)), "whirl_frequency_hz": rate / TWO_PI,
            "whirl_to_cage_frequency": ratio}


def spectral_peak_share(x, y):
    """Share of the centre displacement's power (mean removed) in the strongest spectral line and
    its two neighbours; 1 for a pure circular whirl swept over whole turns, small for broadband motion."""
    z = (x - np.mean(x)) + 1j * (y - np.mean(y))
    power = np.abs(np.fft.fft(z)) ** 2
    power[0] = 0.0
    total = float(np.sum(power))
    if not total > 0:
        return 1.0
    k = int(np.argmax(power))
    n = len(power)
    return float(sum(power[(k + d) % n] for d in (-1, 0, 1)) / total)


def without_synchronous(time, z, cage_speed_mean):
    """z less its least-squares fit by a constant and circles at the cage's speed either way: the
    unbalance's synchronous circle would otherwise leak into the sub-synchronous band of a segment
    of a few revolutions (its spectral lines are a quarter of the cage's frequency apart)."""
    t = time - time[0]
    basis = np.column_stack([np.ones_like(t), np.exp(1j * cage_speed_mean * t), np.exp(-1j * cage_speed_mean * t)])
    coefficients, *_ = np.linalg.lstsq(basis, z, rcond=None)
    return z - basis @ coefficients


def subsync_line(time, x, y, cage_speed_mean):
    """Amplitude [m] and frequency / cage frequency (signed: + with the cage) of the strongest line of
    the centre's displacement (its own mean and synchronous circle removed, Hann window: a whirl
    a e^(i w t) on a spectral bin gives a) with |frequency / cage frequency| in SUBSYNC_BAND; NaN
    where the band holds no bin."""
    z = without_synchronous(time, x + 1j * y, cage_speed_mean)
    w = np.hanning(len(z))
    spectrum = np.abs(np.fft.fft(z * w)) / np.sum(w)
    ratio = np.fft.fftfreq(len(z), (time[-1] - time[0]) / (len(z) - 1)) * TWO_PI / cage_speed_mean
    band = (np.abs(ratio) >= SUBSYNC_BAND[0]) & (np.abs(ratio) <= SUBSYNC_BAND[1])
    if not band.any():
        return math.nan, math.nan
    k = int(np.argmax(np.where(band, spectrum, -1.0)))
    return float(spectrum[k]), float(ratio[k])


def subsync_growth(time, x, y, clearance, cage_speed_mean):
    """The sub-synchronous whirl's growth over the window: its amplitude (subsync_line) in each of up
    to SUBSYNC_SEGMENTS equal segments of at least SUBSYNC_MIN_REVOLUTIONS cage revolutions, the
    least-squares slope of its logarithm against cage revolutions (growth rate per cage revolution:
    0.01 grows e-fold in 100 revolutions), the last segment's amplitude / clearance and frequency /
    cage frequency. NaN (no measure) with fewer than three such segments."""
    revolutions = abs(cage_speed_mean) * float(time[-1] - time[0]) / TWO_PI if math.isfinite(cage_speed_mean) else 0.0
    segments = min(SUBSYNC_SEGMENTS, int(revolutions // SUBSYNC_MIN_REVOLUTIONS))
    out = {"subsync_amplitudes_m": [], "subsync_growth_per_rev": math.nan, "subsync_amplitude_ratio": math.nan,
           "subsync_frequency_ratio": math.nan, "subsync_coherent": False}
    if segments < 3:
        return out
    edges = np.linspace(0, len(time), segments + 1).astype(int)
    lines = [subsync_line(time[a:b], x[a:b], y[a:b], cage_speed_mean) for a, b in zip(edges[:-1], edges[1:])]
    amplitudes = np.array([a for a, _ in lines])
    mids = np.array([abs(cage_speed_mean) * (0.5 * (time[a] + time[b - 1]) - time[0]) / TWO_PI
                     for a, b in zip(edges[:-1], edges[1:])])
    out["subsync_amplitudes_m"] = amplitudes.tolist()
    out["subsync_frequency_ratio"] = lines[-1][1]
    out["subsync_frequencies"] = [float(f) for _, f in lines]  # each segment's line (evidence)
    out["subsync_bin"] = segments / revolutions  # a segment's spectral bin / the cage's frequency
    # One whirl through the window: its line at the same frequency in every segment, within half a
    # spectral bin (1 / a segment's cage revolutions). A wandering centre's strongest line jumps
    # from bin to bin and direction to direction between segments; a film whirl's stays put.
    half_bin = 0.5 * segments / revolutions
    out["subsync_coherent"] = bool(all(abs(f - lines[-1][1]) <= half_bin for _, f in lines))
    out["subsync_amplitude_ratio"] = _ratio(float(amplitudes[-1]), clearance)
    if np.all(amplitudes > 0) and np.all(np.isfinite(amplitudes)):
        out["subsync_growth_per_rev"] = float(np.polyfit(mids, np.log(amplitudes), 1)[0])
    return out


def oil_whirl(m, t):
    """The reason a window's sub-synchronous whirl makes it unstable, or None: a coherent one (the
    same line in every segment, subsync_growth) that grows faster than
    whirl_growth_rate per cage revolution at an amplitude of at least whirl_growth_min_amplitude of
    the clearance (an oil whirl setting in), or it is at least whirl_sustained_amplitude of the
    clearance and decays no faster than whirl_growth_rate (an oil whirl that has grown)."""
    rate, amplitude = m.get("subsync_growth_per_rev", math.nan), m.get("subsync_amplitude_ratio", math.nan)
    if not m.get("subsync_coherent", False):
        return None  # no one whirl: a wandering centre's strongest line changes between segments
    where = f"sub-synchronous whirl at {m.get('subsync_frequency_ratio', math.nan):.3g} of the cage speed"
    if rate > t["whirl_growth_rate"] and amplitude >= t["whirl_growth_min_amplitude"]:
        return (f"{where} grows {rate:.3g} > {t['whirl_growth_rate']:.3g} per cage revolution at amplitude "
                f"{amplitude:.3g} >= {t['whirl_growth_min_amplitude']:.3g} of the clearance")
    if amplitude >= t["whirl_sustained_amplitude"] and rate >= -t["whirl_growth_rate"]:
        return (f"{where} of {amplitude:.3g} >= {t['whirl_sustained_amplitude']:.3g} of the clearance, "
                f"not decaying (growth {rate:.3g} >= -{t['whirl_growth_rate']:.3g} per cage revolution)")
    return None


def orbit_metrics(time, x, y, clearance, cage_speed_mean, vx=None, vy=None):
    """The orbit's metrics (module docstring) of the centre path x(t), y(t) [m] over the window."""
    time, x, y = (np.asarray(a, dtype=float) for a in (time, x, y))
    if vx is None or vy is None:
        vx, vy = np.gradient(x, time), np.gradient(y, time)
    r = np.hypot(x - np.mean(x), y - np.mean(y))
    # seed 001's metrics over the window's last whole whirl turns (the report's choice: the mean of a
    # part-swept circle is off its centre), the whole window when it holds less than one turn.
    whole, _ = rm.whole_turn_window(time, x, y, rm.select_window(time, start=float(time[0])))
    w = whole.slice
    rv = np.hypot(x[w] - np.mean(x[w]), y[w] - np.mean(y[w]))
    speed = np.hypot(np.asarray(vx, dtype=float)[w], np.asarray(vy, dtype=float)[w])
    m = {"orbit_ratio": _ratio(float(np.sqrt(np.mean(r ** 2))), clearance),
         "orbit_radius_m": float(np.mean(r)),
         "vortex_radius_ratio": _ratio(float(rv.max() - rv.min()), float(np.mean(rv))),
         "sigma_v": _ratio(float(np.std(speed, ddof=1)), float(np.mean(speed))),
         "spectral_peak_share": spectral_peak_share(x, y)}
    m.update(whirl_metrics(time, x, y, cage_speed_mean))
    m.update(subsync_growth(time, x, y, clearance, cage_speed_mean))
    rho = m["orbit_ratio"] if math.isfinite(m["orbit_ratio"]) else 0.0
    m["cage_dynamics_indicator"] = min(1.0, rho) * (1.0 - m["spectral_peak_share"])
    return m


def impact_metrics(impact_count, impact_energies, pockets, cage_revolutions, whirl_energy=math.nan):
    """Impact rate (per pocket and cage revolution), mean impact energy [J] and its ratio to
    `whirl_energy` [J] (NaN where either is unknown)."""
    per = pockets * abs(cage_revolutions)
    energies = np.asarray(impact_energies, dtype=float)
    energy = float(np.mean(energies)) if energies.size else (0.0 if impact_count == 0 else math.nan)
    return {"impact_rate": impact_count / per if per > 0 else 0.0, "impact_energy_j": energy,
            "impact_energy_ratio": _ratio(energy, whirl_energy), "impacts": int(impact_count)}


def classify_metrics(m, overrides=None):
    """The class of metrics `m` (orbit_metrics plus impact_metrics) and the reasons for it."""
    t = thresholds(overrides)
    if not math.isfinite(m["orbit_ratio"]):
        return "unknown", ["no guiding clearance (land or pocket) to scale the orbit by"]
    energy = m.get("impact_energy_ratio", math.nan)
    impacts_ok = not (m.get("impact_rate", 0.0) > t["impact_rate_max"]
                      and not energy <= t["impact_energy_ratio_min"])  # NaN energy: the rate decides
    impact_note = (f"impact rate {m.get('impact_rate', 0.0):.3g} > {t['impact_rate_max']:.3g} per pocket and "
                   f"revolution at energy ratio {energy:.3g} > {t['impact_energy_ratio_min']:.3g}")
    growing = oil_whirl(m, t)
    if m["orbit_ratio"] < t["stable_orbit_ratio"]:
        if impacts_ok and not growing:
            return "stable", [f"orbit ratio {m['orbit_ratio']:.3g} < {t['stable_orbit_ratio']:.3g}"]
        return "unstable", [r for r in (None if impacts_ok else impact_note, growing) if r]
    reasons = [growing] if growing else []
    if m["whirl_turns"] < t["circling_min_turns"]:
        reasons.append(f"{m['whirl_turns']} whole whirl turns < {t['circling_min_turns']:.3g}")
    if not m["vortex_radius_ratio"] <= t["circling_vortex_ratio"]:
        reasons.append(f"vortex radius ratio {m['vortex_radius_ratio']:.3g} > {t['circling_vortex_ratio']:.3g}")
    if not m["sigma_v"] <= t["circling_sigma_v"]:
        reasons.append(f"sigma_v {m['sigma_v']:.3g} > {t['circling_sigma_v']:.3g}")
    if not impacts_ok:
        reasons.append(impact_note)
    if reasons:
        return "unstable", reasons
    return "circling", [f"regular whirl: {m['whirl_turns']} turns at orbit ratio {m['orbit_ratio']:.3g}, "
                        f"whirl / cage frequency {m['whirl_to_cage_frequency']:.3g}"]


def classify(time, x, y, clearance, cage_speed, pockets=1, impact_count=0, impact_energies=(),
             overrides=None, vx=None, vy=None, cage_mass=None):
    """Metrics, class and reasons of a window: the centre path, the cage's speed about the axis
    [rad/s, array or mean], the guiding clearance [m], the pocket count, the window's impacts and
    the cage's mass [kg] (for the impact energy ratio; None: unknown)."""
    time = np.asarray(time, dtype=float)
    speed = float(np.mean(cage_speed))
    m = orbit_metrics(time, x, y, clearance, speed, vx, vy)
    revolutions = speed * float(time[-1] - time[0]) / TWO_PI
    whirl_energy = 0.5 * cage_mass * (speed * clearance) ** 2 if cage_mass else math.nan
    m.update(impact_metrics(impact_count, impact_energies, pockets, revolutions, whirl_energy))
    m["motion_class"], m["reasons"] = classify_metrics(m, overrides)
    return m


def window_impacts(pocket_steps, window, cage_mass, share=0.01):
    """Impact count and energies J^2 / (2 m) in the samples `window` (a slice) from the step-resolved
    pocket statistics (report_data.BearingRun.pocket_steps): an impact is an output interval in which
    a bar's largest step force exceeds `share` of the window's largest (at least 1e-3 N, the report's
    contact threshold) after an interval in which it did not (a new engagement, not a ball pushing
    the cage through the load zone); J is the bar's impulse over that interval."""
    bars = list((pocket_steps or {}).values())
    if not bars:
        return 0, []
    peaks = [np.asarray(bar["peak_force"], dtype=float)[window] for bar in bars]
    threshold = max(share * max(float(np.max(p, initial=0.0)) for p in peaks), 1e-3)
    count, energies = 0, []
    for bar, peak in zip(bars, peaks):
        impulse = np.asarray(bar["impulse"], dtype=float)[window]
        on = peak > threshold
        start = on[1:] & ~on[:-1]
        count += int(np.sum(start))
        if cage_mass and cage_mass > 0:
            energies.extend((impulse[1:][start] ** 2 / (2.0 * cage_mass)).tolist())
    return count, energies


def guiding_clearance(geometry):
    """The cage's radial play [m]: the land clearance of a land-guided cage, else the pocket clearance."""
    land = geometry.get("land_clearance") or 0.0
    return land if land > 0 else (geometry.get("pocket_clearance") or math.nan)


def classify_run(run, start, end=None, cage_mass=None, overrides=None):
    """Classification of a BearingRun (report_data.read_run) over the samples with start <= t (<= end)."""
    t = run.time
    s = (t >= start) & (t <= (t[-1] if end is None else end))
    window = np.nonzero(s)[0]
    sl = slice(int(window[0]), int(window[-1]) + 1)
    count, energies = window_impacts(run.pocket_steps, sl, cage_mass)
    return classify(t[sl], run.cage_xy[sl, 0], run.cage_xy[sl, 1], guiding_clearance(run.geometry),
                    run.cage_speed[sl], pockets=run.elements, impact_count=count, impact_energies=energies,
                    overrides=overrides, vx=run.cage_vxy[sl, 0], vy=run.cage_vxy[sl, 1], cage_mass=cage_mass)


def output_cage_mass(path):
    """The cage's mass [kg] from its net force and acceleration in the output (F = m a, least squares
    over the radial components of every sample); None where the file has neither or the cage never
    accelerates."""
    from raceway import RacewayOutput

    with RacewayOutput(path) as out:
        if "cage/force" not in out or "cage/acceleration" not in out:
            return None
        f = np.asarray(out["cage/force"], dtype=float)[:, :2]
        a = np.asarray(out["cage/acceleration"], dtype=float)[:, :2]
    den = float(np.sum(a * a))
    return float(np.sum(f * a)) / den if den > 0 else None


SUMMARY_KEYS = ("motion_class", "reasons", "cage_dynamics_indicator", "orbit_ratio", "whirl_turns",
                "whirl_to_cage_frequency", "vortex_radius_ratio", "sigma_v", "spectral_peak_share", "impact_rate",
                "impact_energy_j", "impact_energy_ratio")


def motion_summary(run, window):
    """The report's `cage_motion` object: classify_run over the report's window (report_metrics.Window)
    with the thresholds' defaults, and the cage mass it used."""
    mass = output_cage_mass(run.path)
    m = classify_run(run, window.t_begin, window.t_end, cage_mass=mass)
    out = {k: m[k] for k in SUMMARY_KEYS}
    out["cage_mass_kg"] = mass if mass is not None else math.nan
    return out
