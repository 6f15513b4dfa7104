#!/usr/bin/python3
"""How far two raceway outputs of the same scene differ, for changes that may move results by
round-off (scripts/compare_outputs.py is the bitwise check).

    roundoff_compare.py A.h5 B.h5 [--all]

For each floating-point dataset of A also in B with the same shape: the largest difference over
the dataset's scale, max |a - b| / max |a| (a dataset of zeros in A: the absolute difference),
over the first 10 %, 50 % and all of the samples, so that a difference that grows along the run
(chaotic divergence) shows as growing columns. Prints the body states (positions, velocities,
angles, angular velocities of the balls or rollers, cage and rings) and the largest 15 others
(--all: every dataset), and the largest body-state difference last.
"""
import sys

import h5py
import numpy as np

STATES = ("position", "velocity", "angles", "angular_velocity")


def datasets(f):
    out = {}
    f.visititems(lambda name, obj: out.__setitem__("/" + name, obj) if isinstance(obj, h5py.Dataset) else None)
    return out


def spread(a, b):
    """max |a - b| / max |a| over the first 10 %, 50 %, 100 % of the rows."""
    out = []
    for share in (0.1, 0.5, 1.0):
        n = max(1, int(round(share * a.shape[0])))
        x, y = a[:n], b[:n]
        scale = np.max(np.abs(x)) if x.size else 0.0
        diff = np.max(np.abs(x - y)) if x.size else 0.0
        out.append(diff / scale if scale > 0 else diff)
    return out


def main(argv):
    args = [a for a in argv if not a.startswith("--")]
    if len(args) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    with h5py.File(args[0], "r") as fa, h5py.File(args[1], "r") as fb:
        da, db = datasets(fa), datasets(fb)
        rows = []
        for name, d in da.items():
            if name not in db or d.dtype.kind != "f" or d.shape != db[name].shape or d.ndim == 0 or d.shape[0] == 0:
                continue
            a, b = d[()], db[name][()]
            if not (np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
                continue
            rows.append((name, spread(a, b)))
    states = [r for r in rows if r[0].rsplit("/", 1)[-1] in STATES and not r[0].startswith("/segments")]
    others = sorted((r for r in rows if r not in states), key=lambda r: -r[1][2])
    if "--all" not in argv:
        others = others[:15]
    print(f"{'dataset':60s} {'10 %':>9s} {'50 %':>9s} {'100 %':>9s}")
    for title, part in (("body states", states), ("others, largest first", others)):
        print(f"# {title}")
        for name, s in part:
            print(f"{name:60s} " + " ".join(f"{v:9.1e}" for v in s))
    worst = max((s[2] for _, s in states), default=0.0)
    print(f"largest body-state difference over its scale: {worst:.1e}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
