"""How an atlas point is certified (docs/atlas.md, "Certification").

- settled: the window (settling_time .. end_time) is cut into `blocks` equal blocks; the metric of
  each block and of its successor differ by at most block_tolerance, and the cage centre's orbit
  does not grow from block to block by more than the factor 1 + growth_tolerance in all (a slowly
  growing whirl keeps a small metric and small steps while its radius doubles; an unstable point
  may grow: that is its instability, cage_motion's growing-whirl class). Each block's own class is
  recorded as evidence, not required to be the window's: a block shorter than a whirl turn cannot
  show a whirl. A point that is not settled is recorded as such (its class stands, flagged): the
  run was too short for it.
- converged: a sample of the points (every k-th point in the order they were run, k = round(1 /
  convergence_sample)) is rerun with [solver] rtol = convergence_rtol; it agrees when its class is
  the same and its metric within convergence_tolerance.
- realisations: where the motion is irregular (unstable), the point is rerun at each value of the
  realisation key (a cage start offset, an unbalance phase); the metric's mean over the base run and
  the realisations and the half-width of its 95 % confidence interval (Student's t) are recorded, and
  the point is certified when the half-width is at most ci_target.
"""
import math

import numpy as np

# Student's t, two-sided 95 %, by degrees of freedom (1..30); beyond, the normal's 1.96 (error < 2 %).
T95 = (12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160, 2.145, 2.131,
       2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042)


def t95(dof):
    return T95[dof - 1] if 1 <= dof <= len(T95) else 1.96


def block_slices(n, blocks):
    """`blocks` consecutive slices of n samples (the last ones take the remainder)."""
    edges = np.linspace(0, n, blocks + 1).astype(int)
    return [slice(int(a), int(b)) for a, b in zip(edges[:-1], edges[1:])]


def orbit_growth(block_radii):
    """Last block's orbit radius over the first's when the radius grows from every block to the next
    (a whirl still growing), else 1."""
    r = [float(v) for v in block_radii]
    if len(r) < 2 or not all(math.isfinite(v) and v > 0 for v in r):
        return 1.0
    return r[-1] / r[0] if all(b > a for a, b in zip(r[:-1], r[1:])) else 1.0


def settled(block_metrics, block_classes, window_class, tolerance, block_radii=(), growth_tolerance=math.inf):
    """The settledness evidence of a window from its blocks' metrics, classes and orbit radii."""
    values = [float(v) for v in block_metrics]
    steps = [abs(b - a) for a, b in zip(values[:-1], values[1:])]
    worst = max(steps) if steps else 0.0
    growth = orbit_growth(block_radii)
    # A growing orbit unsettles a stable or circling class (a longer run could change it), not an
    # unstable one: growth is what an instability does.
    grows_ok = growth <= 1 + growth_tolerance or window_class == "unstable"
    ok = bool(all(math.isfinite(s) for s in steps) and worst <= tolerance and grows_ok)
    return {"ok": ok, "block_metric": values, "block_class": list(block_classes), "largest_step": worst,
            "tolerance": tolerance, "orbit_growth": growth, "growth_tolerance": growth_tolerance,
            "classes_agree": all(c == window_class for c in block_classes)}


def in_convergence_sample(index, share):
    """Whether the index-th point run (0-based) is rerun at the tighter rtol."""
    if share <= 0:
        return False
    k = max(1, int(round(1.0 / share)))
    return index % k == 0


def converged(base_class, base_metric, tight_class, tight_metric, rtol, tolerance):
    diff = abs(float(tight_metric) - float(base_metric))
    return {"checked": True, "ok": bool(tight_class == base_class and diff <= tolerance), "rtol": rtol,
            "class": tight_class, "metric": float(tight_metric), "difference": diff, "tolerance": tolerance}


def confidence(values, target):
    """Mean and 95 % half-width of the metric over the realisations; ok when the half-width <= target."""
    v = np.asarray([float(x) for x in values], dtype=float)
    n = len(v)
    half = t95(n - 1) * float(np.std(v, ddof=1)) / math.sqrt(n) if n > 1 else math.inf
    return {"checked": True, "ok": bool(half <= target), "values": v.tolist(), "mean": float(np.mean(v)),
            "half_width_95": half, "target": target}


def summary(cert):
    """One line of how a point was certified (the table's `certified_by`)."""
    p, t = cert.get("probe", {}), cert.get("threshold", {})
    parts = ["settled" if cert["settled"]["ok"] else "NOT settled"]
    if p.get("checked"):
        parts[0] = "settled" if cert["settled"]["ok"] else "window NOT settled (its orbit grows)"
        word = f"{p['class']}" if p["ok"] else "NOT decided"
        longer = [f"{v} +{n} windows" for v, n in zip(p["values"], p.get("probe_later_windows", [])) if n]
        later = f" (longer: {', '.join(longer)})" if longer else ""
        parts.append(f"stability probe ({', '.join(p['values'])} off-centre{later}: "
                     f"{', '.join(p['probe_class'])}) {word}")
    c = cert.get("converged", {})
    if c.get("checked"):
        parts.append(f"rtol {c['rtol']:g} {'agrees' if c['ok'] else 'DISAGREES'}")
    if t.get("checked"):
        side = [('>' if x["mean"] > x["threshold"] else '<=') if x["clear"] else "spans" for x in t["thresholds"]]
        each = ", ".join(f"{x['metric']} {x['mean']:.3g} +-{x['half_width_95']:.2g} {w} {x['threshold']:g}"
                         for x, w in zip(t["thresholds"], side))
        parts.append(f"threshold over {t['runs']} runs: {each}" + (f" -> {t['class']}" if t["ok"] else " NOT decided"))
    r = cert.get("realisations", {})
    if r.get("checked"):
        parts.append(f"{len(r['values'])} realisations, CI +-{r['half_width_95']:.3g} "
                     f"{'<=' if r['ok'] else '>'} {r['target']:g}")
    return "; ".join(parts)


def certified(cert):
    """A point is certified when every check it had passed; a probed point (its window cannot say where
    its motion ends) by its stability probe alone, an rtol rerun of another class by the threshold's
    runs."""
    probe = cert.get("probe", {})
    settled_ok = probe["ok"] if probe.get("checked") else cert["settled"]["ok"]
    converged_ok = cert.get("converged", {}).get("ok", True) or cert.get("threshold", {}).get("ok", False)
    return bool(settled_ok and converged_ok and cert.get("realisations", {}).get("ok", True))


# --- A point that has not settled, or sits on a class threshold (docs/atlas.md, "Certification of a
# point": the stability probe and the threshold's runs). RULE stamps a certification made with them:
# an atlas resumed re-certifies its uncertified points made before (their files read again, the
# missing runs made).
RULE = 8


def needs_probe(settled_record, base, thresholds):
    """Whether a stable or circling point's window cannot say where its motion ends: its orbit grows
    from block to block (settled_record), or its sub-synchronous whirl (one line through the window)
    grows faster than whirl_growth_rate while still below the unstable class's floor (the orbit may
    not grow with it: the unbalance's synchronous circle is larger). Either grows from round-off or a
    small seed: the centred cage is linearly unstable, the window too short to see the end."""
    if base.get("motion_class") not in ("stable", "circling") or \
            settled_record["largest_step"] > settled_record["tolerance"]:
        return False
    grows = not settled_record["ok"] and settled_record["orbit_growth"] > 1 + settled_record["growth_tolerance"]
    whirl = (bool(base.get("subsync_coherent")) or adjacent_bins(base)) and \
        base.get("subsync_growth_per_rev", math.nan) > thresholds["whirl_growth_rate"]
    return grows or whirl


def adjacent_bins(metrics):
    """Whether the segments' sub-synchronous lines are one whirl between two spectral bins: the same
    direction in every segment, within one bin and a half of each other (a whirl between two bins
    shows in either from segment to segment, which the class's coherence, half a bin, does not
    take for one whirl; a wandering centre's line also turns round)."""
    f, width = metrics.get("subsync_frequencies") or [], metrics.get("subsync_bin", math.nan)
    if len(f) < 3 or not math.isfinite(width):
        return False
    return (all(v > 0 for v in f) or all(v < 0 for v in f)) and max(f) - min(f) <= 1.5 * width


def probe_verdict(probe, probe_settled, thresholds):
    """One probe's word (the point rerun with the cage started off-centre, above the growth floor):
    'unstable' when the window of the probe is unstable (the whirl persists or grows from there),
    'stable' when it is stable or circling, settled, and its sub-synchronous whirl ends below the
    sustained-whirl amplitude, not growing (it decays towards the centred cage or a small limit
    cycle: the attractor lies below where it ended), else 'undecided'."""
    cls = probe["motion_class"]
    if cls == "unstable":
        return "unstable"
    amplitude = probe.get("subsync_amplitude_ratio", math.nan)
    below = not (amplitude >= thresholds["whirl_sustained_amplitude"])  # NaN: no whirl line measured
    # A probe whose own whirl still grows (below the floor) bounds nothing: it needs a probe itself.
    growing = (bool(probe.get("subsync_coherent")) or adjacent_bins(probe)) and \
        probe.get("subsync_growth_per_rev", math.nan) > thresholds["whirl_growth_rate"]
    if cls in ("stable", "circling") and probe_settled["ok"] and below and not growing:
        return "stable"
    return "undecided"


def probe_words(runs, settled_records, thresholds):
    """Each probe's word (probe_verdict) and the bracket of the whirl's attractor: probes that start
    either side of a limit cycle approach it from below (growing) and from above (decaying), so the
    cycle lies between the largest amplitude a growing probe reached and the smallest a decaying one
    came down to. A decaying probe still above the sustained amplitude is undecided on its own; when a
    growing probe has already reached that amplitude, the cycle is above it: unstable."""
    words = [probe_verdict(m, s, thresholds) for (_, m), s in zip(runs, settled_records)]
    rate, sustained = thresholds["whirl_growth_rate"], thresholds["whirl_sustained_amplitude"]

    def amplitudes(sign):
        return [m["subsync_amplitude_ratio"] for _, m in runs if m.get("subsync_coherent")
                and sign * m.get("subsync_growth_per_rev", math.nan) > rate]
    low, high = max(amplitudes(+1), default=math.nan), min(amplitudes(-1), default=math.nan)
    if low >= sustained:
        words = ["unstable" if w == "undecided" else w for w in words]
    return words, [low, high]


def probes(base, runs, settled_records, thresholds):
    """The stability probe's evidence from its runs [(value, metrics)] and their settled records; 'ok'
    when every probe is settled and they agree, 'class' the class they give."""
    words, bracket = probe_words(runs, settled_records, thresholds)
    agree = len(set(words)) == 1 and words[0] != "undecided"
    cls = None
    if agree:
        cls = "unstable" if words[0] == "unstable" else base["motion_class"]
    return {"checked": True, "ok": bool(agree and all(s["ok"] for s in settled_records)), "class": cls,
            "verdicts": words, "values": [v for v, _ in runs], "probe_class": [m["motion_class"] for _, m in runs],
            "probe_growth_per_rev": [m.get("subsync_growth_per_rev", math.nan) for _, m in runs],
            "probe_amplitude_ratio": [m.get("subsync_amplitude_ratio", math.nan) for _, m in runs],
            "probe_settled": [bool(s["ok"]) for s in settled_records],
            "probe_later_windows": [m.get("later_windows", 0) for _, m in runs], "cycle_bracket": bracket,
            "probe_window_read": [m.get("window_read", "last window") for _, m in runs],
            "base_growth_per_rev": base.get("subsync_growth_per_rev", math.nan),
            "base_amplitude_ratio": base.get("subsync_amplitude_ratio", math.nan)}


def probe_reason(record, key, floor):
    """The point's reason from its probe: the centred cage's own growth and what the probes did."""
    starts = ", ".join(f"{key} = {v}" for v in record["values"])
    base = (f"the centred cage's sub-synchronous whirl grows {record['base_growth_per_rev']:.3g} per cage "
            f"revolution at {record['base_amplitude_ratio']:.3g} of the clearance (below the floor {floor:g}): the "
            "centred cage is linearly unstable")
    growth = ", ".join(f"{g:.3g}" for g in record["probe_growth_per_rev"])
    if record["class"] == "unstable":
        low = record.get("cycle_bracket", [math.nan])[0]
        cycle = f"; its limit cycle above {low:.3g} of the clearance" if low >= 0 else ""
        return (f"{base}; started at {starts} the whirl persists (probes unstable, growth per revolution "
                f"{growth}{cycle})")
    if record["class"]:
        ends = ", ".join(f"{a:.3g}" for a in record["probe_amplitude_ratio"])
        return (f"{base}, but started at {starts} the whirl decays (growth per revolution {growth}) to {ends} of the "
                "clearance, below the sustained-whirl amplitude: its attractor is bounded below it (stable)")
    return f"{base}; the probes at {starts} do not decide ({', '.join(record['verdicts'])})"


# The thresholds that separate the classes of a point's runs: (metric, threshold key, comparison of
# the class the metric passes: True when the metric must be at most the threshold).
CLASS_THRESHOLDS = (("orbit_ratio", "stable_orbit_ratio"), ("vortex_radius_ratio", "circling_vortex_ratio"),
                    ("sigma_v", "circling_sigma_v"))


def straddled(runs, thresholds):
    """The class thresholds that the runs' metrics lie on both sides of: [(metric, threshold key)]."""
    out = []
    for metric, key in CLASS_THRESHOLDS:
        sides = {float(m[metric]) <= thresholds[key] for m in runs if math.isfinite(float(m.get(metric, math.nan)))}
        if len(sides) > 1:
            out.append((metric, key))
    return out


def threshold_decision(runs, thresholds, classify):
    """A point whose runs (base, tighter rtol, start offsets) disagree in class: each threshold they
    straddle is decided by the 95 % confidence interval of its metric's mean over the runs (the
    interval clear of the threshold: that side); the class is then `classify` of the base's metrics
    with those means. 'ok' when every straddled threshold is decided."""
    decided, record = True, {"checked": True, "runs": len(runs), "classes": [m["motion_class"] for m in runs],
                             "thresholds": []}
    means = dict(runs[0])
    for metric, key in straddled(runs, thresholds):
        ci = confidence([m[metric] for m in runs], math.inf)
        lo, hi = ci["mean"] - ci["half_width_95"], ci["mean"] + ci["half_width_95"]
        clear = not lo <= thresholds[key] <= hi
        decided = decided and clear
        means[metric] = ci["mean"]
        record["thresholds"].append({"metric": metric, "threshold": thresholds[key], "mean": ci["mean"],
                                     "half_width_95": ci["half_width_95"], "values": ci["values"], "clear": clear})
    record["ok"] = bool(decided and record["thresholds"])
    record["class"] = classify(means)[0] if record["ok"] else None
    return record
