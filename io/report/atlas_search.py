"""The atlas's adaptive search: where to run the next points (docs/atlas.md, "Search").

Points live in the unit cube [0, 1]^d (each parameter's range mapped linearly). The classes of the
points run so far train a Gaussian-process classifier (scikit-learn's GaussianProcessClassifier, a
constant times an RBF kernel, its hyperparameters fitted, a fixed random state): its class
probabilities give every candidate of a fixed pool an uncertainty u = 1 - max_k p_k (0: sure; the
boundary between two classes: 1/2). A batch is the candidates of largest u, chosen greedily, each
weighed by its distance to the points run and already chosen (a candidate closer than the spacing
d0 = 1 / (2 sqrt(n + 1)) of the n points run counts u x distance / d0), so a batch spreads along the
boundary instead of piling up at one place. Before two classes are seen the batch fills space
(the Halton points in order). A fit that collapsed (its amplitude at the lower bound, or its length
scale below d0: p near 1/2 everywhere) is not trusted: it is refit with its length scale floored at
d0 and its amplitude at 1, and part of the batch is placed by space filling, farthest from every
point (search_classifier, propose_batch). Everything is deterministic: the same points run give the
same batch, which makes a resumed atlas the uninterrupted one.
"""
import importlib.util
import math
import warnings

import numpy as np

PRIMES = (2, 3, 5, 7, 11, 13, 17, 19, 23, 29)


def have_sklearn():
    return importlib.util.find_spec("sklearn") is not None


def halton(n, d, skip=0):
    """n points of the Halton sequence in [0, 1)^d from index skip + 1."""
    out = np.empty((n, d))
    for j in range(d):
        b = PRIMES[j]
        for i in range(n):
            k, f, v = i + skip + 1, 1.0, 0.0
            while k > 0:
                f /= b
                v += f * (k % b)
                k //= b
            out[i, j] = v
    return out


def initial_design(d):
    """The first batch: the 2^d corners and the centre of the cube."""
    corners = np.array([[(i >> j) & 1 for j in range(d)] for i in range(2 ** d)], dtype=float)
    return np.vstack([corners, np.full((1, d), 0.5)])


def candidate_pool(d, size=2500):
    """The fixed candidates: a regular grid in 2-D (51 x 51), Halton points in more dimensions."""
    if d == 2:
        g = np.linspace(0.0, 1.0, 51)
        return np.array([[a, b] for b in g for a in g])
    return halton(size, d, skip=20)


#: The free fit's hyperparameter bounds: the kernel's amplitude (the latent function's variance) and
#: its RBF length scale, in the unit cube.
AMPLITUDE_BOUNDS = (1e-2, 1e3)
LENGTH_BOUNDS = (0.02, 2.0)
#: The refit of an untrusted classifier keeps its amplitude at or above this (a latent standard
#: deviation of 1: it cannot answer "either" everywhere) and its length scale at or above the points'
#: spacing (it cannot fit a label's scatter between neighbouring points).
TRUSTED_AMPLITUDE = 1.0
#: The share of a batch placed by space filling (farthest from every point) while the classifier is
#: untrusted (at least one point).
EXPLORE_SHARE = 0.5


def fit_classifier(points, labels, length_floor=None, amplitude_floor=None):
    """The Gaussian-process classifier of `labels` at `points` (at least two classes); the floors raise
    the lower bounds of the length scale and the amplitude (the refit of an untrusted classifier)."""
    from sklearn.exceptions import ConvergenceWarning
    from sklearn.gaussian_process import GaussianProcessClassifier
    from sklearn.gaussian_process.kernels import RBF, ConstantKernel

    amplitude = (max(AMPLITUDE_BOUNDS[0], amplitude_floor or 0.0), AMPLITUDE_BOUNDS[1])
    length = (max(LENGTH_BOUNDS[0], length_floor or 0.0), LENGTH_BOUNDS[1])
    kernel = ConstantKernel(max(1.0, amplitude[0]), amplitude) * RBF(length_scale=max(0.2, length[0]),
                                                                     length_scale_bounds=length)
    model = GaussianProcessClassifier(kernel=kernel, random_state=0, n_restarts_optimizer=0)
    with warnings.catch_warnings():  # hyperparameters at their bounds: the fit is still usable
        warnings.filterwarnings("ignore", category=ConvergenceWarning)
        model.fit(np.asarray(points, dtype=float), np.asarray(labels))
    return model


def point_spacing(n):
    """The spacing d0 = 1 / (2 sqrt(n + 1)) of n points: the batch's damping distance and the floor of
    a trusted classifier's length scale (the search's resolution at n points)."""
    return 0.5 / math.sqrt(n + 1)


def hyperparameters(model):
    """(amplitude, length scale, log marginal likelihood) of a fitted classifier: with more than two
    classes (one binary classifier per class against the rest), the smallest amplitude and length scale."""
    base = model.base_estimator_
    fits = getattr(base, "estimators_", [base])
    params = [f.kernel_.get_params() for f in fits]
    return (min(float(p["k1__constant_value"]) for p in params),
            min(float(np.min(p["k2__length_scale"])) for p in params), float(model.log_marginal_likelihood_value_))


def _fit_record(model):
    amplitude, length, lml = hyperparameters(model)
    return {"amplitude": amplitude, "length_scale": length, "log_marginal_likelihood": lml}


def collapse_reasons(model, n):
    """Why the fitted classifier of n points is not to be trusted ([]: trusted): its amplitude at the
    lower bound (p near 1/2 everywhere: "either" everywhere) or its length scale below the points'
    spacing (it fits the labels' scatter point by point, and far from the points falls back to 1/2)."""
    amplitude, length, _ = hyperparameters(model)
    reasons = []
    if amplitude <= 1.01 * AMPLITUDE_BOUNDS[0]:
        reasons.append(f"amplitude {amplitude:.3g} at its lower bound {AMPLITUDE_BOUNDS[0]:g}")
    if length < point_spacing(n):
        reasons.append(f"length scale {length:.3g} below the points' spacing {point_spacing(n):.3g}")
    return reasons


def search_classifier(points, labels):
    """The classifier the search uses, and its record: the free fit if trusted, else the refit with its
    length scale floored at the points' spacing and its amplitude at TRUSTED_AMPLITUDE."""
    model = fit_classifier(points, labels)
    reasons = collapse_reasons(model, len(points))
    record = {"trained_on": len(points), "fit": _fit_record(model), "trusted": not reasons, "reasons": reasons}
    if reasons:
        model = fit_classifier(points, labels, length_floor=point_spacing(len(points)),
                               amplitude_floor=TRUSTED_AMPLITUDE)
        record["refit"] = _fit_record(model)
    return model, record


def uncertainty(model, points):
    """1 - max class probability at each point, and the predicted class."""
    p = model.predict_proba(np.asarray(points, dtype=float))
    return 1.0 - p.max(axis=1), model.classes_[np.argmax(p, axis=1)]


#: The uncertainty band: where u = 1 - max_k p_k exceeds this (the map hatches it).
BAND_UNCERTAINTY = 0.2


def band_share(model, pool):
    """Share of the candidate pool inside the uncertainty band: the search's stopping measure (the
    largest u is no measure: next to the boundary it is always 1/2 or more)."""
    u, _ = uncertainty(model, pool)
    return float(np.mean(u > BAND_UNCERTAINTY))


def _distances_to(pool, points):
    """Each pool candidate's distance to the nearest of `points` (inf with none)."""
    near = np.full(len(pool), np.inf)
    for t in points:
        near = np.minimum(near, np.linalg.norm(pool - np.asarray(t, dtype=float), axis=1))
    return near


def _greedy(pool, near, count, weight_of):
    """`count` picks, each the pool's largest weight_of(distances to everything placed so far)."""
    picks = []
    for _ in range(count):
        weight = weight_of(near)
        k = int(np.argmax(weight))
        if not weight[k] > 0:
            break
        picks.append(pool[k].copy())
        near = np.minimum(near, np.linalg.norm(pool - pool[k], axis=1))
    return picks


def _spread_pick(scores, pool, taken, count, spacing):
    """Greedy: the pool's best score damped by closeness to `taken` and to the picks so far."""
    return _greedy(pool, _distances_to(pool, taken), count, lambda near: scores * np.minimum(1.0, near / spacing))


def space_filling(taken, count, d):
    """The next `count` Halton points not already run (the search before two classes are seen)."""
    taken = {tuple(np.round(t, 12)) for t in taken}
    picks, skip = [], 0
    while len(picks) < count:
        for p in halton(64, d, skip=skip):
            if tuple(np.round(p, 12)) not in taken and len(picks) < count:
                picks.append(p)
        skip += 64
    return picks


def farthest_points(pool, taken, count):
    """Space filling on the pool: greedily the candidate farthest from `taken` and the picks so far."""
    return _greedy(pool, _distances_to(pool, taken), count, lambda near: near)


def propose_batch(points, labels, count, pool=None, taken=None, model=None, record=None):
    """The next `count` points (unit cube) given the points run and their classes, and the decision's
    record (which rule placed them, and why). `taken`: every point already placed (default: `points`;
    the atlas adds its failed ones, never proposed again); `model`, `record`: search_classifier's, if
    already fitted. A trusted classifier places the batch by its uncertainty; an untrusted one (refit)
    places ceil(EXPLORE_SHARE x count) points by space filling, farthest from every point, the rest by
    the refit's uncertainty."""
    points = np.asarray(points, dtype=float)
    d = points.shape[1]
    taken = points if taken is None else np.asarray(taken, dtype=float)
    if len(set(labels)) < 2:
        return space_filling(taken, count, d), {"rule": "space filling: one class seen", "trained_on": len(points)}
    pool = candidate_pool(d) if pool is None else pool
    if model is None:
        model, record = search_classifier(points, labels)
    explore = 0 if record["trusted"] else min(count, max(1, math.ceil(EXPLORE_SHARE * count)))
    u, _ = uncertainty(model, pool)
    picks = _spread_pick(u, pool, taken, count - explore, point_spacing(len(points)))
    far = farthest_points(pool, list(taken) + picks, explore)
    rule = "uncertainty" if record["trusted"] else "refit's uncertainty and space filling (classifier untrusted)"
    return picks + far, {**record, "rule": rule, "band_share": float(np.mean(u > BAND_UNCERTAINTY)),
                         "by_uncertainty": len(picks), "explored": len(far)}


def propose(points, labels, count, pool=None, taken=None):
    """The next `count` points of propose_batch (without its record)."""
    return propose_batch(points, labels, count, pool, taken)[0]


def misclassified_share(model_or_points, labels_or_none, truth, grid):
    """Share of `grid` (unit-cube points) where the classifier's class differs from truth(grid)."""
    model = model_or_points if labels_or_none is None else fit_classifier(model_or_points, labels_or_none)
    predicted = model.predict(np.asarray(grid, dtype=float))
    return float(np.mean(predicted != truth(grid)))


def regular_grid(n, d):
    """n^d points of a regular grid over the unit cube (first parameter fastest)."""
    axes = np.meshgrid(*[np.linspace(0.0, 1.0, n)] * d, indexing="ij")
    return np.stack([a.ravel(order="F") for a in axes], axis=1)


def standin_classes(points):
    """A cheap stand-in for the simulator with a known boundary (the tests' model): on (speed, load) in
    the unit square, "unstable" where load < standin_boundary(speed) (the cage is driven too little
    for its speed), "stable" above. (`raceway_atlas.py --standin NOISE` adds a ripple to the boundary:
    atlas_models.StandinModel.)"""
    points = np.atleast_2d(np.asarray(points, dtype=float))
    return np.where(points[:, 1] < standin_boundary(points[:, 0]), "unstable", "stable")


#: The stand-in's boundary moves by this much load per unit of a third parameter (its tilt).
STANDIN_TILT = 0.3


def standin_boundary(speed, third=None):
    """The stand-in's boundary: the load at which the class changes, per speed (unit square); with a
    third parameter (the three-parameter stand-in), shifted by STANDIN_TILT (third - 0.5)."""
    load = 0.15 + 0.7 * np.asarray(speed, dtype=float) ** 2
    return load if third is None else load + STANDIN_TILT * (np.asarray(third, dtype=float) - 0.5)
