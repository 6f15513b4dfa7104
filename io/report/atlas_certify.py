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
    parts = ["settled" if cert["settled"]["ok"] else "NOT settled"]
    c = cert.get("converged", {})
    if c.get("checked"):
        parts.append(f"rtol {c['rtol']:g} {'agrees' if c['ok'] else 'DISAGREES'}")
    r = cert.get("realisations", {})
    if r.get("checked"):
        parts.append(f"{len(r['values'])} realisations, CI +-{r['half_width_95']:.3g} "
                     f"{'<=' if r['ok'] else '>'} {r['target']:g}")
    return "; ".join(parts)


def certified(cert):
    """A point is certified when every check it had passed."""
    return bool(cert["settled"]["ok"] and cert.get("converged", {}).get("ok", True)
                and cert.get("realisations", {}).get("ok", True))
