"""The atlas's outputs (docs/atlas.md, "Outputs"): DIR/atlas.csv and DIR/atlas.json (every point with
its parameters, class, indicator, metrics and certification evidence) and DIR/atlas.png (the map of
class and indicator over the first two parameters: the points, the classifier's boundary and its
uncertainty band; the metric at the points over a Gaussian-process regression of them); with more than two parameters
also DIR/atlas_<a>_<b>.png, every pair's map on slices through the others (atlas_pairs.py). Files
are written beside and renamed."""
import csv
import json
import math
import os

import numpy as np

import atlas_pairs as pairs
from atlas_file import parameter_values, style_axis
import atlas_search as search

METRIC_COLUMNS = ("orbit_ratio", "whirl_turns", "whirl_to_cage_frequency", "vortex_radius_ratio", "sigma_v",
                  "spectral_peak_share", "cage_dynamics_indicator", "impact_rate", "impact_energy_j",
                  "impact_energy_ratio", "subsync_growth_per_rev", "subsync_amplitude_ratio", "subsync_frequency_ratio",
                  "pocket_friction", "critical_pocket_friction", "pocket_friction_margin",
                  "critical_pocket_friction_applies")
WINDOW_COLUMNS = ("settling_time_s", "end_time_s")  # with a window in cage revolutions: each point's own
CLASS_COLOURS = {"stable": "tab:green", "circling": "tab:blue", "unstable": "tab:red"}
BAND_UNCERTAINTY = search.BAND_UNCERTAINTY  # the band drawn round the boundary


def _finite(value):
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(v) for v in value]
    if hasattr(value, "item"):
        return _finite(value.item())
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def _replace(path, write):
    with open(path + ".tmp", "w", encoding="utf-8", newline="") as f:
        write(f)
    os.replace(path + ".tmp", path)


def table_rows(atlas, state):
    """One row per point: id, batch, parameters (in their units), status, class, metric, certification."""
    rows = []
    for p in state["points"]:
        row = {"id": p["id"], "batch": p["batch"]}
        row.update({f"{q['name']}_{q['unit'].replace(' ', '')}": p.get("values", {}).get(q["name"])
                    for q in atlas["parameters"]})
        row.update({"status": p["status"], "class": p.get("class", ""), "map_class": p.get("label", ""),
                    atlas["metric"]: p.get("metric")})
        m = p.get("metrics", {})
        row.update({k: m.get(k) for k in METRIC_COLUMNS if k != atlas["metric"]})
        if atlas.get("window_cage_revolutions") is not None:
            row.update({k: m.get(k) for k in WINDOW_COLUMNS})
        cert = p.get("certification", {})
        row.update({"certified": p.get("certified"), "certified_by": p.get("certified_by", p.get("error", "")),
                    "settled_largest_step": cert.get("settled", {}).get("largest_step"),
                    "rtol_difference": cert.get("converged", {}).get("difference"),
                    "ci_half_width_95": cert.get("realisations", {}).get("half_width_95"),
                    "output": p.get("output", "")})
        rows.append(row)
    return rows


def shown_path(path):
    """`path` relative to the working folder where it lies inside it (a table made in a repository
    names its scene as the repository does, wherever the repository lies), else as it is."""
    relative = os.path.relpath(path)
    return path if relative.startswith("..") else relative


def write_table(atlas, state, folder, maps=()):
    rows = table_rows(atlas, state)
    columns = list(rows[0]) if rows else ["id"]

    def write_csv(f):
        w = csv.DictWriter(f, fieldnames=columns)
        w.writeheader()
        for r in rows:
            w.writerow({k: ("" if v is None else f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})

    _replace(os.path.join(folder, "atlas.csv"), write_csv)
    doc = {"name": atlas["name"], "scene": shown_path(atlas["scene"]), "metric": atlas["metric"], "classes": atlas["classes"],
           "parameters": atlas["parameters"], "certify": atlas["certify"], "thresholds": atlas["thresholds"],
           "stop": state.get("stop"), "core_hours": state.get("core_hours"), "batches": state.get("batches", []),
           "points": state["points"]}
    if maps:  # more than two parameters: the map of every pair (atlas_pairs.py)
        doc["maps"] = list(maps)
    _replace(os.path.join(folder, "atlas.json"), lambda f: json.dump(_finite(doc), f, indent=1))


def _grid(atlas, n=81):
    """A grid over the first two parameters (unit cube; the others at their range's middle)."""
    g = np.linspace(0.0, 1.0, n)
    a, b = np.meshgrid(g, g)
    cube = np.full((n * n, len(atlas["parameters"])), 0.5)
    cube[:, 0], cube[:, 1] = a.ravel(), b.ravel()
    return g, cube


def _axis(atlas, k, unit):
    p = atlas["parameters"][k]
    return parameter_values(p, unit), f"{p['name']} ({p['key']}) [{p['unit']}]"


def metric_field(units, values, cube):
    """The metric over the grid `cube`: a Gaussian-process regression of the points' values (constant x
    RBF plus white noise, normalised, fixed random state: atlas_pairs.metric_model); None with fewer
    than 3 finite points."""
    model = pairs.metric_model(units, values)
    return None if model is None else model.predict(cube)


def write_map(atlas, state, folder):
    """DIR/atlas.png; returns a note when the map could not be drawn (no matplotlib)."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return "no map: matplotlib is missing"
    done = [p for p in state["points"] if p["status"] == "done" and p.get("label")]
    units = np.array([p["unit"] for p in done]) if done else np.zeros((0, len(atlas["parameters"])))
    labels = [p["label"] for p in done]
    fig, axes = plt.subplots(1, 2, figsize=(12, 5), constrained_layout=True)
    g, cube = _grid(atlas)
    gx, xlabel = _axis(atlas, 0, g)
    gy, ylabel = _axis(atlas, 1, g)
    if len(set(labels)) > 1 and search.have_sklearn():
        model = search.search_classifier(units, labels)[0]  # the refit where the free fit is untrusted
        u, predicted = search.uncertainty(model, cube)
        index = {c: i for i, c in enumerate(model.classes_)}
        z = np.array([index[c] for c in predicted], dtype=float).reshape(len(g), len(g))
        # Two classes: the boundary is where their probabilities are equal (smooth); more: class changes.
        line = model.predict_proba(cube)[:, 1].reshape(z.shape) if len(index) == 2 else z
        for ax in axes:
            ax.contour(gx, gy, line, levels=[0.5] if len(index) == 2 else np.arange(len(index) - 1) + 0.5,
                       colors="k", linewidths=1.5)
            ax.contourf(gx, gy, u.reshape(len(g), len(g)), levels=[BAND_UNCERTAINTY, 1.0], colors="none",
                        hatches=["////"])
        cmap = matplotlib.colors.ListedColormap([CLASS_COLOURS[c] for c in model.classes_])
        axes[0].pcolormesh(gx, gy, z, cmap=cmap, alpha=0.25, shading="auto", vmin=-0.5, vmax=len(index) - 0.5)
    elif len(set(labels)) == 1:  # one class seen: nothing to separate, no boundary drawn
        axes[0].text(0.5, 0.02, f"every point {labels[0]}: no boundary found inside the ranges",
                     transform=axes[0].transAxes, ha="center", va="bottom", fontsize=9)
    px, _ = _axis(atlas, 0, units[:, 0]) if len(units) else (np.array([]), "")
    py, _ = _axis(atlas, 1, units[:, 1]) if len(units) else (np.array([]), "")
    for cls in [c for c in CLASS_COLOURS if c in labels]:
        sel = [i for i, c in enumerate(labels) if c == cls]
        axes[0].scatter(px[sel], py[sel], c=CLASS_COLOURS[cls], edgecolors="k", label=cls, zorder=3)
    values = [p["metric"] if p["metric"] is not None else math.nan for p in done]
    field = metric_field(units, values, cube) if search.have_sklearn() and len(done) else None
    finite = [v for v in values if math.isfinite(v)]
    low, high = (min(finite), max(finite)) if finite else (0.0, 1.0)
    if field is not None:
        axes[1].pcolormesh(gx, gy, field.reshape(len(g), len(g)), cmap="viridis", vmin=low, vmax=high,
                           shading="auto", alpha=0.6)
    sc = axes[1].scatter(px, py, c=values, cmap="viridis", vmin=low, vmax=high, edgecolors="k", zorder=3)
    fig.colorbar(sc, ax=axes[1], label=atlas["metric"])
    axes[0].legend(title=f"class (hatched: uncertainty > {BAND_UNCERTAINTY:g})", loc="best", fontsize=8)
    others = "" if len(atlas["parameters"]) == 2 else "\n(the other parameters at their range's middle)"
    axes[0].set_title(f"{atlas['name']}: class, boundary (line) and its uncertainty band{others}", fontsize=10)
    axes[1].set_title(f"{atlas['metric']}: the points and a Gaussian-process fit of them (shaded)", fontsize=10)
    for ax in axes:
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        style_axis(ax, atlas["parameters"][0], "x")
        style_axis(ax, atlas["parameters"][1], "y")
    path = os.path.join(folder, "atlas.png")
    fig.savefig(path + ".tmp.png", dpi=110)
    plt.close(fig)
    os.replace(path + ".tmp.png", path)
    return None


def write_outputs(atlas, state, folder):
    """The table, atlas.json, atlas.png and, with more than two parameters, every pair's map (listed in
    atlas.json's `maps`); returns a note when a map could not be drawn."""
    try:
        maps = pairs.write_pair_maps(atlas, state, folder, BAND_UNCERTAINTY)
    except ImportError:
        maps = []
    write_table(atlas, state, folder, maps)
    return write_map(atlas, state, folder)
