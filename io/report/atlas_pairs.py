"""The atlas's maps for every pair of parameters (docs/atlas.md, "Outputs"), drawn when an atlas has
more than two: DIR/atlas_<a>_<b>.png per pair (a, b) of parameter names. Each holds, per slice through
the other parameters (their range's low, middle and high, and the values where the classifier finds
the unstable class likeliest over the pair), the class the search's classifier predicts, its
boundary and uncertainty band, and the metric's Gaussian-process guide; every point projected onto
the pair with its class and certification (faint when it lies far from the slice); and the share
of the points that are unstable per cell of the pair, whatever the other parameters.

The arithmetic (slices, predictions on a slice, projections, shares) is apart from the drawing so
that the tests can check it against a stand-in with a known boundary."""
import itertools
import math
import os
import warnings

import numpy as np

import atlas_search as search
from atlas_file import parameter_value, parameter_values, style_axis

#: The slices through the other parameters: their range's low, middle and high (unit cube).
SLICE_LEVELS = ((0.0, "low"), (0.5, "middle"), (1.0, "high"))
#: A point lies near a slice when every other parameter is within this share of its range of it.
NEAR_SLICE = 0.25
#: The pair's cells for the share of unstable points (per axis).
SHARE_CELLS = 4
#: The likeliest slice is its own column unless it is this close (unit cube, every other parameter)
#: to one of SLICE_LEVELS's.
SAME_SLICE = 0.1


def file_name(atlas, i, j):
    ps = atlas["parameters"]
    return f"atlas_{ps[i]['name']}_{ps[j]['name']}.png"


def pairs(atlas):
    return list(itertools.combinations(range(len(atlas["parameters"])), 2))


def done_points(state):
    return [p for p in state["points"] if p["status"] == "done" and p.get("label")]


def unstable_class(atlas, labels):
    """The class whose region the likeliest slice looks for: "unstable" when seen, else the last of
    the atlas's classes seen that is not "stable" (None: every point stable, or none)."""
    seen = [c for c in atlas["classes"] if c in set(labels) and c != "stable"]
    return "unstable" if "unstable" in seen else (seen[-1] if seen else None)


def slice_cube(d, i, j, others, g):
    """The unit-cube points of the pair (i, j)'s grid g x g with the other parameters at `others` (in
    the order of the parameters other than i and j); the first parameter of the pair fastest."""
    a, b = np.meshgrid(g, g)
    cube = np.empty((a.size, d))
    rest = [k for k in range(d) if k not in (i, j)]
    for k, v in zip(rest, others):
        cube[:, k] = v
    cube[:, i], cube[:, j] = a.ravel(), b.ravel()
    return cube


def other_candidates(count):
    """Candidate settings of `count` other parameters for the likeliest slice: 21 levels of one, or
    the grid of 5 levels per parameter (up to 3 others) plus Halton points."""
    if count == 1:
        return np.linspace(0.0, 1.0, 21)[:, None]
    levels = np.linspace(0.0, 1.0, 5)
    grid = np.array(list(itertools.product(levels, repeat=count))) if count <= 3 else np.zeros((0, count))
    return np.vstack([grid, search.halton(64, count)])


def likeliest_others(model, cls, d, i, j):
    """The other parameters' values (unit cube) where the class `cls` covers the pair's plane most,
    by its mean probability over a 21 x 21 grid of the pair, and that mean."""
    col = list(model.classes_).index(cls)
    g = np.linspace(0.0, 1.0, 21)
    best, best_share = None, -1.0
    for others in other_candidates(d - 2):
        share = float(np.mean(model.predict_proba(slice_cube(d, i, j, others, g))[:, col]))
        if share > best_share + 1e-12:
            best, best_share = others, share
    return np.asarray(best, dtype=float), best_share


def slices(atlas, model, labels, i, j):
    """The slices of the pair (i, j): [{"others": unit values of the other parameters, "what": why}];
    the likeliest slice of the unstable class joins a level it is close to, else is added."""
    d = len(atlas["parameters"])
    out = [{"others": np.full(d - 2, level), "what": f"range's {name}"} for level, name in SLICE_LEVELS]
    cls = unstable_class(atlas, labels) if model is not None else None
    if cls is None or cls not in model.classes_:
        return out
    best, share = likeliest_others(model, cls, d, i, j)
    note = f"{cls} likeliest (mean probability {share:.2f} over the pair)"
    for s in out:
        if np.max(np.abs(s["others"] - best)) <= SAME_SLICE:
            s["what"] += f"; {note}"
            return out
    out.append({"others": best, "what": note})
    return out


def slice_values(atlas, i, j, others):
    """The other parameters' values in their units: {name: value}."""
    rest = [p for k, p in enumerate(atlas["parameters"]) if k not in (i, j)]
    return {p["name"]: parameter_value(p, v) for p, v in zip(rest, others)}


def slice_title(atlas, i, j, s):
    values = slice_values(atlas, i, j, s["others"])
    units = {p["name"]: p["unit"] for p in atlas["parameters"]}
    return ", ".join(f"{n} = {v:.4g} {units[n]}" for n, v in values.items()) + f"\n({s['what']})"


def predict_slice(model, d, i, j, others, n=81):
    """On the slice's n x n grid: the predicted class's index, the uncertainty u = 1 - max_k p_k and the
    line the boundary is drawn on (the second class's probability with two classes, at 1/2; else the
    class index, at its half-integers), each n x n (rows: the pair's second parameter)."""
    g = np.linspace(0.0, 1.0, n)
    cube = slice_cube(d, i, j, others, g)
    p = model.predict_proba(cube)
    z = np.argmax(p, axis=1).reshape(n, n).astype(float)
    line = p[:, 1].reshape(n, n) if len(model.classes_) == 2 else z
    return g, z, (1.0 - p.max(axis=1)).reshape(n, n), line


def projections(atlas, points, i, j, others=None):
    """The points projected onto the pair (i, j): x, y in the parameters' units, and, with a slice's
    `others`, whether each lies near it (every other parameter within NEAR_SLICE of its range)."""
    ps = atlas["parameters"]
    units = np.array([p["unit"] for p in points], dtype=float).reshape(len(points), len(ps))

    def value(k):
        return parameter_values(ps[k], units[:, k])

    rest = [k for k in range(len(ps)) if k not in (i, j)]
    near = np.ones(len(points), dtype=bool)
    if others is not None and rest:
        near = np.max(np.abs(units[:, rest] - np.asarray(others)[None, :]), axis=1) <= NEAR_SLICE + 1e-12
    return value(i), value(j), near


def unstable_shares(atlas, points, i, j, cls, cells=SHARE_CELLS):
    """Per cell of the pair (cells x cells, rows: the second parameter): the points in it (whatever the
    other parameters) and how many of them are of class `cls`."""
    total, hit = np.zeros((cells, cells), dtype=int), np.zeros((cells, cells), dtype=int)
    for p in points:
        a, b = (min(cells - 1, int(math.floor(p["unit"][k] * cells))) for k in (i, j))
        total[b, a] += 1
        hit[b, a] += p["label"] == cls
    return total, hit


def metric_model(units, values):
    """A Gaussian-process regression of the points' metric at their unit-cube places (constant x RBF plus
    white noise, normalised, fixed random state: a guide between the points, not a measurement), or
    None with fewer than 3 finite values."""
    from sklearn.exceptions import ConvergenceWarning
    from sklearn.gaussian_process import GaussianProcessRegressor
    from sklearn.gaussian_process.kernels import RBF, ConstantKernel, WhiteKernel

    values = np.asarray(values, dtype=float)
    keep = np.isfinite(values)
    if keep.sum() < 3:
        return None
    kernel = ConstantKernel(1.0, (1e-2, 1e2)) * RBF(0.3, (0.05, 3.0)) + WhiteKernel(1e-2, (1e-6, 1.0))
    model = GaussianProcessRegressor(kernel=kernel, normalize_y=True, random_state=0)
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", category=ConvergenceWarning)
        model.fit(np.asarray(units, dtype=float)[keep], values[keep])
    return model



CLASS_COLOURS = {"stable": "tab:green", "circling": "tab:blue", "unstable": "tab:red"}


def _scatter(ax, atlas, points, i, j, others):
    """The points projected onto the pair: colour by class, filled when certified, open when not;
    faint and small when far from the slice (one collection per kind: a point each is slow)."""
    x, y, near = projections(atlas, points, i, j, others)
    colour = np.array([CLASS_COLOURS.get(p["label"], "tab:gray") for p in points], dtype=object)
    sure = np.array([bool(p.get("certified")) for p in points], dtype=bool)
    for close, certified in itertools.product((False, True), repeat=2):
        sel = (near == close) & (sure == certified)
        if not sel.any():
            continue
        edge = ["k"] * int(sel.sum()) if certified else list(colour[sel])
        ax.scatter(x[sel], y[sel], s=36 if close else 14, alpha=1.0 if close else 0.3, zorder=3, linewidths=1.2,
                   facecolors=list(colour[sel]) if certified else "none", edgecolors=edge)


def _class_panel(ax, atlas, i, j, model, s, band):
    d = len(atlas["parameters"])
    g, z, u, line = predict_slice(model, d, i, j, s["others"])
    gx, gy = (_units(atlas, k, g) for k in (i, j))
    import matplotlib

    cmap = matplotlib.colors.ListedColormap([CLASS_COLOURS.get(c, "tab:gray") for c in model.classes_])
    ax.pcolormesh(gx, gy, z, cmap=cmap, alpha=0.25, shading="auto", vmin=-0.5, vmax=len(model.classes_) - 0.5)
    _boundary(ax, gx, gy, line, u, len(model.classes_), band)


def _boundary(ax, gx, gy, line, u, classes, band):
    levels = [0.5] if classes == 2 else np.arange(classes - 1) + 0.5
    if np.nanmin(line) < levels[0] < np.nanmax(line) or classes > 2:
        ax.contour(gx, gy, line, levels=levels, colors="k", linewidths=1.5)
    if np.max(u) > band:
        ax.contourf(gx, gy, u, levels=[band, 1.0], colors="none", hatches=["////"])


def _units(atlas, k, unit):
    return parameter_values(atlas["parameters"][k], unit)


def _label(atlas, k):
    p = atlas["parameters"][k]
    return f"{p['name']} [{p['unit']}]"


def _share_panel(ax, atlas, points, i, j, cls):
    total, hit = unstable_shares(atlas, points, i, j, cls)
    edges = np.linspace(0.0, 1.0, SHARE_CELLS + 1)
    share = np.where(total > 0, hit / np.maximum(total, 1), np.nan)
    ex, ey = _units(atlas, i, edges), _units(atlas, j, edges)
    mesh = ax.pcolormesh(ex, ey, share, cmap="Reds", vmin=0.0, vmax=1.0, shading="flat")
    centres = 0.5 * (edges[1:] + edges[:-1])
    for b, a in itertools.product(range(SHARE_CELLS), repeat=2):
        ax.text(_units(atlas, i, centres[a]), _units(atlas, j, centres[b]), f"{hit[b, a]}/{total[b, a]}",
                ha="center", va="center", fontsize=8)
    ax.set_title(f"share of points {cls}, whatever the other parameters\n(count {cls} / points per cell)",
                 fontsize=9)
    return mesh, {"cells": SHARE_CELLS, "points": total.tolist(), cls: hit.tolist()}


def draw_pair(atlas, points, i, j, model, field, band, folder):
    """Draws the pair (i, j)'s file; returns its record for atlas.json."""
    import matplotlib.pyplot as plt

    labels = [p["label"] for p in points]
    cls = unstable_class(atlas, labels) or "unstable"
    cuts = slices(atlas, model, labels, i, j)
    fig, axes = plt.subplots(2, len(cuts) + 1, figsize=(4.2 * (len(cuts) + 1), 8.2), constrained_layout=True,
                             squeeze=False)
    values = np.array([p["metric"] if p["metric"] is not None else math.nan for p in points], dtype=float)
    finite = values[np.isfinite(values)]
    low, high = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 1.0)
    d = len(atlas["parameters"])
    for c, s in enumerate(cuts):
        top, bottom = axes[0, c], axes[1, c]
        if model is not None:
            _class_panel(top, atlas, i, j, model, s, band)
        _scatter(top, atlas, points, i, j, s["others"])
        top.set_title(slice_title(atlas, i, j, s), fontsize=8)
        if field is not None:
            g = np.linspace(0.0, 1.0, 41)
            f = field.predict(slice_cube(d, i, j, s["others"], g)).reshape(len(g), len(g))
            bottom.pcolormesh(_units(atlas, i, g), _units(atlas, j, g), f, cmap="viridis", vmin=low, vmax=high,
                              shading="auto", alpha=0.6)
        if model is not None:
            g, _, u, line = predict_slice(model, d, i, j, s["others"])
            _boundary(bottom, _units(atlas, i, g), _units(atlas, j, g), line, u, len(model.classes_), band)
        x, y, near = projections(atlas, points, i, j, s["others"])
        bottom.scatter(x[near], y[near], c=values[near], cmap="viridis", vmin=low, vmax=high, edgecolors="k", zorder=3)
        bottom.set_title(f"{atlas['metric']} (shaded: Gaussian-process guide);\nthe points near the slice", fontsize=8)
    mesh, shares = _share_panel(axes[0, -1], atlas, points, i, j, cls)
    fig.colorbar(mesh, ax=axes[0, -1], label=f"share {cls}")
    x, y, _ = projections(atlas, points, i, j)
    sc = axes[1, -1].scatter(x, y, c=values, cmap="viridis", vmin=low, vmax=high, edgecolors="k", zorder=3)
    axes[1, -1].set_title(f"{atlas['metric']}: every point projected", fontsize=9)
    fig.colorbar(sc, ax=axes[1, -1], label=atlas["metric"])
    _finish(fig, axes, atlas, i, j, band, model is None, labels)
    name = file_name(atlas, i, j)
    path = os.path.join(folder, name)
    fig.savefig(path + ".tmp.png", dpi=90)
    plt.close(fig)
    os.replace(path + ".tmp.png", path)
    return {"file": name, "parameters": [atlas["parameters"][k]["name"] for k in (i, j)],
            "slices": [{"values": slice_values(atlas, i, j, s["others"]), "what": s["what"]} for s in cuts],
            "unstable_share": shares}


def _finish(fig, axes, atlas, i, j, band, no_model, labels):
    from matplotlib.lines import Line2D

    for ax in axes.ravel():
        ax.set_xlabel(_label(atlas, i))
        ax.set_ylabel(_label(atlas, j))
        style_axis(ax, atlas["parameters"][i], "x")
        style_axis(ax, atlas["parameters"][j], "y")
    handles = [Line2D([], [], marker="o", ls="", color=CLASS_COLOURS.get(c, "tab:gray"), label=c)
               for c in atlas["classes"] if c in labels]
    handles += [Line2D([], [], marker="o", ls="", markerfacecolor="w", markeredgecolor="k",
                       label="open: not certified"),
                Line2D([], [], marker="o", ls="", color="k", alpha=0.3, markersize=4,
                       label=f"faint: > {NEAR_SLICE:g} of a range from the slice")]
    axes[0, 0].legend(handles=handles, loc="best", fontsize=7,
                      title=f"line: boundary; hatched: uncertainty > {band:g}", title_fontsize=7)
    if no_model:
        only = labels[0] if labels else "no point"
        axes[0, 0].text(0.5, 0.5, f"every point {only}:\nno boundary found inside the ranges",
                        transform=axes[0, 0].transAxes, ha="center", va="center", fontsize=8)
    fig.suptitle(f"{atlas['name']}: {atlas['parameters'][i]['name']} x {atlas['parameters'][j]['name']}, "
                 "slices through the other parameters (columns)", fontsize=11)


def write_pair_maps(atlas, state, folder, band):
    """Every pair's file when the atlas has more than two parameters; their records ([] otherwise)."""
    if len(atlas["parameters"]) <= 2:
        return []
    import matplotlib
    matplotlib.use("Agg")

    points = done_points(state)
    labels = [p["label"] for p in points]
    units = np.array([p["unit"] for p in points], dtype=float).reshape(len(points), len(atlas["parameters"]))
    model = search.search_classifier(units, labels)[0] if len(set(labels)) > 1 and search.have_sklearn() else None
    values = [p["metric"] if p["metric"] is not None else math.nan for p in points]
    field = metric_model(units, values) if points and search.have_sklearn() else None
    return [draw_pair(atlas, points, i, j, model, field, band, folder) for i, j in pairs(atlas)]
