#!/usr/bin/python3
"""Seed 002 steps per inner-ring revolution against settings, and whether the physics moved.

  perf/studies/seed002_fewer_steps.py [--binary build/raceway] [--out perf/studies/results/seed002_fewer_steps.txt]
                              [--only LABEL ...]

Runs jobs/scenes/seed002_40hz.toml for 50 ms (two inner-ring revolutions at 40 Hz; output every
0.1 ms) with the solver settings it shipped with before (BDF up to order 5, rtol 1e-7) at rtol
1e-6 .. 1e-9 (the convergence sweep), then with each candidate setting and as shipped now. Over the second revolution [25 ms, 50 ms] it measures

  cage speed      the mean cage angular speed [rpm]
  max load        the mean over samples of the largest roller load on the inner race [N]
  load sum        the mean over samples of the sum of the rollers' inner-race loads [N]
  light load      the mean outer-race load of the rollers outside the load zone (no inner-race
                  load) over the samples [N]: rollers held by their centrifugal force (1.2 N, a
                  contact approach of about 8 nm, the most sensitive to the position tolerance)
                  and bouncing under gravity

The convergence window of a quantity is [min, max] over the rtol sweep; a candidate keeps the
physics if each of its quantities lies inside the window widened by the window's own width (the
sweep's spread is the quantity's measured uncertainty; a candidate is as good as any of the sweep's
runs if it differs from their mean by no more than they differ from each other). Prints a table
with steps per revolution, error-test failures, wall time and the three quantities.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from work_precision import ROOT, element_loads, segments_at_every_sample, set_key  # noqa: E402

END_S, REVOLUTIONS = 0.05, 2.0
SWEEP = [1e-6, 1e-7, 1e-8, 1e-9]
# The solver settings the scene shipped with before (BDF up to order 5, rtol 1e-7, absolute
# tolerances from rtol): the sweep varies their rtol; every candidate starts from them.
BEFORE = {("solver", "max_order"): "5", ("solver", "rtol"): "1e-7", ("solver", "atol"): "{}"}
# label -> {(section, key): value}; applied on top of BEFORE (None: the scene as shipped now).
CANDIDATES = [
    ("as shipped now (rtol 1e-5, max_order 2, atol position 1e-9 m, velocity 1e-4 m/s)", None),
    ("as shipped before (rtol 1e-7, max_order 5)", {}),
    ("rtol 1e-5", {("solver", "rtol"): "1e-5"}),
    ("atol velocity 1e-4 m/s", {("solver", "atol"): '{ velocity = "1e-4 m/s" }'}),
    ("atol position 1e-8 m, velocity 1e-4 m/s",
     {("solver", "atol"): '{ position = "1e-8 m", velocity = "1e-4 m/s" }'}),
    ("rtol 1e-6, atol velocity 1e-4 m/s", {("solver", "rtol"): "1e-6", ("solver", "atol"): '{ velocity = "1e-4 m/s" }'}),
    ("rtol 1e-5, atol velocity 1e-4 m/s", {("solver", "rtol"): "1e-5", ("solver", "atol"): '{ velocity = "1e-4 m/s" }'}),
    ("rtol 1e-5, atol velocity 1e-3 m/s", {("solver", "rtol"): "1e-5", ("solver", "atol"): '{ velocity = "1e-3 m/s" }'}),
    ("rtol 1e-5, atol position 1e-8 m, velocity 1e-3 m/s",
     {("solver", "rtol"): "1e-5", ("solver", "atol"): '{ position = "1e-8 m", velocity = "1e-3 m/s" }'}),
    ("rtol 1e-4", {("solver", "rtol"): "1e-4"}),
    ("max_order 2", {("solver", "max_order"): "2"}),
    ("rtol 1e-6, max_order 2", {("solver", "rtol"): "1e-6", ("solver", "max_order"): "2"}),
    ("rtol 3e-6, max_order 2", {("solver", "rtol"): "3e-6", ("solver", "max_order"): "2"}),
    ("rtol 1e-5, max_order 2", {("solver", "rtol"): "1e-5", ("solver", "max_order"): "2"}),
    ("rtol 2e-5, max_order 2", {("solver", "rtol"): "2e-5", ("solver", "max_order"): "2"}),
    ("rtol 5e-5, max_order 2", {("solver", "rtol"): "5e-5", ("solver", "max_order"): "2"}),
    ("rtol 1e-5, max_order 2, stability_limit_detection",
     {("solver", "rtol"): "1e-5", ("solver", "max_order"): "2", ("solver", "stability_limit_detection"): "true"}),
    ("rtol 1e-5, max_order 2, atol velocity 1e-4 m/s", {("solver", "rtol"): "1e-5", ("solver", "max_order"): "2",
                                                        ("solver", "atol"): '{ velocity = "1e-4 m/s" }'}),
    ("rtol 1e-5, max_order 2, atol position 1e-9 m", {("solver", "rtol"): "1e-5", ("solver", "max_order"): "2",
                                                      ("solver", "atol"): '{ position = "1e-9 m" }'}),
    ("rtol 1e-5, max_order 2, atol position 1e-8 m, velocity 1e-4 m/s",
     {("solver", "rtol"): "1e-5", ("solver", "max_order"): "2",
      ("solver", "atol"): '{ position = "1e-8 m", velocity = "1e-4 m/s" }'}),
    ("rtol 1e-6, max_order 1", {("solver", "rtol"): "1e-6", ("solver", "max_order"): "1"}),
    ("rtol 1e-6, max_order 3", {("solver", "rtol"): "1e-6", ("solver", "max_order"): "3"}),
]


def scene_text(settings):
    text = open(os.path.join(ROOT, "jobs", "scenes", "seed002_40hz.toml")).read()
    text = set_key(text, "scene", "end_time", f'"{END_S * 1e3:g} ms"')
    text = set_key(text, "scene", "output_interval", '"0.1 ms"')
    for (section, key), value in ({} if settings is None else {**BEFORE, **settings}).items():
        text = set_key(text, section, key, value)
    return text


def run(binary, settings, workdir, tag):
    scene, out, summary = (os.path.join(workdir, tag + ext) for ext in (".toml", ".h5", ".json"))
    with open(scene, "w") as f:
        f.write(scene_text(settings))
    start = time.monotonic()
    p = subprocess.run([binary, "run", scene, "--output-thread", "off", "-o", out, "--summary-json", summary], capture_output=True, text=True)
    wall = time.monotonic() - start
    if p.returncode != 0:
        return {"failed": (p.stderr.strip().splitlines() or ["?"])[-1][:160]}
    s = json.load(open(summary))
    with h5py.File(out, "r") as f:
        t = f["time"][()].ravel()
        w = t >= 0.5 * END_S - 1e-12
        cage = f["cage/angular_velocity"][()][w]
        cage = cage[:, 2] if cage.ndim == 2 and cage.shape[1] == 3 else cage.ravel()
        loads = element_loads(f, "rollers")[w]
        outer = segments_at_every_sample(f)["roller_outer_race/normal_force"][()][w]
    os.remove(out)
    return {"steps": s["steps"], "etf": s["error_test_failures"], "rhs": s["rhs_evaluations"], "wall": wall,
            "cage_rpm": cage.mean() * 60 / (2 * np.pi), "max_load": loads.max(axis=1).mean(),
            "load_sum": loads.sum(axis=1).mean(), "light_load": outer[loads <= 0].mean(), "limits": s.get("step_limiting_states")}


QUANTITIES = [("cage_rpm", "cage speed [rpm]"), ("max_load", "max load [N]"), ("load_sum", "load sum [N]"),
              ("light_load", "light load [N]")]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "raceway"))
    ap.add_argument("--out", default=None)
    ap.add_argument("--only", nargs="*", default=None, help="candidate labels to run (default: all)")
    args = ap.parse_args()
    lines = []

    def emit(s=""):
        print(s, flush=True)
        lines.append(s)

    with tempfile.TemporaryDirectory() as work:
        sweep = {rtol: run(args.binary, {("solver", "rtol"): f"{rtol:g}"}, work, f"sweep{rtol:g}") for rtol in SWEEP}
        emit(f"# seed 002, {END_S * 1e3:g} ms = {REVOLUTIONS:g} inner-ring revolutions; window: the second revolution")
        emit("## convergence sweep (the settings shipped before: BDF order 5, atol from rtol; rtol varied)")
        emit("| rtol | steps/rev | error-test failures | wall [s] | " + " | ".join(t for _, t in QUANTITIES) + " |")
        emit("|---|---|---|---|" + "---|" * len(QUANTITIES))
        for rtol, r in sweep.items():
            emit(f"| {rtol:g} | {r['steps'] / REVOLUTIONS:.0f} | {r['etf']} | {r['wall']:.2f} | "
                 + " | ".join(f"{r[q]:.4f}" for q, _ in QUANTITIES) + " |")
        window = {}
        for q, title in QUANTITIES:
            v = np.array([r[q] for r in sweep.values()])
            window[q] = (v.min(), v.max(), v.mean())
            emit(f"window {title}: [{v.min():.4f}, {v.max():.4f}], mean {v.mean():.4f}, width {v.max() - v.min():.4f} "
                 f"({(v.max() - v.min()) / abs(v.mean()) * 100:.3f} %)")
        emit()
        emit("## candidates (inside: within the window widened by its width on each side)")
        emit("| setting | steps/rev | error-test failures | wall [s] | " + " | ".join(t for _, t in QUANTITIES)
             + " | inside |")
        emit("|---|---|---|---|" + "---|" * len(QUANTITIES) + "---|")
        for i, (label, settings) in enumerate(CANDIDATES):
            if args.only and label not in args.only:
                continue
            r = run(args.binary, settings, work, f"cand{i}")
            if "failed" in r:
                emit(f"| {label} | failed: {r['failed']} |")
                continue
            inside = all(lo - (hi - lo) <= r[q] <= hi + (hi - lo) for q, (lo, hi, _) in window.items())
            emit(f"| {label} | {r['steps'] / REVOLUTIONS:.0f} | {r['etf']} | {r['wall']:.2f} | "
                 + " | ".join(f"{r[q]:.4f}" for q, _ in QUANTITIES) + f" | {'yes' if inside else 'NO'} |")
    if args.out:
        with open(args.out, "w") as f:
            f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
