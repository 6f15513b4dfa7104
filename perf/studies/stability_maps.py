#!/usr/bin/python3
"""Stability maps: where the integration methods fail or crawl.

  perf/studies/stability_maps.py [--binary build/raceway] [--scenes seed002_40hz 6309_R3 qj215_validation]
                         [--timeout 60] [--out perf/studies/results]

Over a grid of (race contact damping factor) x (driven-ring speed) runs each method variant on a
short run of the scene at its own rtol (the end time shortened: perf/studies/work_precision.py's SCENES,
QJ215 further: MAP_WINDOW) and
records whether the run finishes, its cost (wall time, right-hand sides, steps) and its error-test
and Newton failures. Variants: bdf (orders 1-5), bdf_sld (with stability-limit detection), bdf2
(max_order 2, A-stable), adams, erk (Dormand-Prince) and ark (SDIRK 4(3)). A run fails when the
integrator gives up (exit 3, with its diagnosis) or takes longer than --timeout (a crawl).

Writes stability_SCENE.csv and stability_SCENE.png (one panel per variant: colour = right-hand
sides, log scale; the numbers in a cell are error-test / Newton failures; x = the integration failed
or crawled; s = the start-up found no seated state, before any method runs). --replot redraws the
PNGs from the CSV files.
"""
import argparse
import csv
import json
import os
import re
import subprocess
import tempfile

import numpy as np

import work_precision as wp

VARIANTS = {"bdf": ("bdf", {}), "bdf_sld": ("bdf", {"stability_limit_detection": "true"}),
            "bdf2": ("bdf", {"max_order": "2"}), "adams": ("adams", {}), "erk": ("erk", {}), "ark": ("ark", {})}
DAMPING = ["0.05 s/m", "0.5 s/m", "5 s/m", "50 s/m"]
# Driven-ring speeds relative to the scene's own.
SPEED_FACTORS = [0.25, 1.0, 4.0, 10.0]
CONTACT = {"seed002_40hz": "contact.roller_race", "6309_R3": "contact.ball_race",
           "qj215_validation": "contact.ball_race"}
# Shorter runs than perf/studies/work_precision.py's where the whole grid would not fit in about half an
# hour: QJ215's 0.3 s (5 revolutions) becomes 50 ms (the balls' race contacts, before the cage
# touches them at about 0.2 s), so 96 runs cost what 16 of the long ones would.
MAP_WINDOW = {"qj215_validation": {"end_time": "50 ms"}}


def scaled_speed(text, factor):
    """The [inner_ring] speed times factor (a constant speed with a unit)."""
    m = re.search(r'(\[inner_ring\][^\[]*?\nspeed = ")([\d.eE+-]+) (\w+)(")', text)
    value = float(m.group(2)) * factor
    return text[: m.start(2)] + f"{value:g}" + text[m.end(2):], f"{value:g} {m.group(3)}"


def one_run(binary, name, variant, damping, factor, workdir, timeout):
    method, keys = VARIANTS[variant]
    text = open(os.path.join(wp.ROOT, "jobs", "scenes", name + ".toml")).read()
    for key, value in {**wp.SCENES[name], **MAP_WINDOW.get(name, {})}.items():
        text = wp.set_key(text, "scene", key, f'"{value}"')
    # The solver settings the maps were measured with: the method (in the scene too: max_order's
    # bounds are checked against it), its default order, absolute
    # tolerances following rtol, seed 002 at its former rtol 1e-7.
    keys = {"method": f'"{method}"', "max_order": wp.DEFAULT_ORDER[method], "atol": "{}",
            **({"rtol": "1e-7"} if name == "seed002_40hz" else {}), **keys}
    for key, value in keys.items():
        text = wp.set_key(text, "solver", key, value)
    text = wp.set_key(text, CONTACT[name], "damping_factor", f'"{damping}"')
    text, speed = scaled_speed(text, factor)
    scene = os.path.join(workdir, "s.toml")
    with open(scene, "w") as f:
        f.write(text)
    row = {"scene": name, "variant": variant, "damping": damping, "speed": speed}
    try:
        p = subprocess.run([binary, "run", scene, "--output-thread", "off", "--method", method, "-o", os.path.join(workdir, "s.h5"),
                            "--summary-json", os.path.join(workdir, "s.json")], capture_output=True, text=True,
                           timeout=timeout)
    except subprocess.TimeoutExpired:
        return {**row, "status": f"timeout {timeout:.0f} s"}
    if p.returncode != 0:
        return {**row, "status": f"exit {p.returncode}", "diagnosis": (p.stderr.strip().splitlines() or [""])[-1][:300]}
    s = json.load(open(os.path.join(workdir, "s.json")))
    return {**row, "status": "ok", **{k: s[k] for k in ["wall_time_s", "rhs_evaluations", "steps",
                                                       "error_test_failures", "newton_failures"]}}


def plot(name, rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    speeds = list(dict.fromkeys(r["speed"] for r in rows))
    variants = list(dict.fromkeys(r["variant"] for r in rows))
    ok = [float(r["rhs_evaluations"]) for r in rows if r["status"] == "ok"]
    vmin, vmax = np.log10(min(ok)), np.log10(max(ok))
    fig, axes = plt.subplots(1, len(variants), figsize=(3.3 * len(variants), 3.8), squeeze=False)
    for ax, v in zip(axes[0], variants):
        grid = np.full((len(DAMPING), len(speeds)), np.nan)
        for r in rows:
            if r["variant"] != v:
                continue
            i, j = DAMPING.index(r["damping"]), speeds.index(r["speed"])
            if r["status"] == "ok":
                grid[i, j] = np.log10(float(r["rhs_evaluations"]))
                ax.text(j, i, f"{r['error_test_failures']}/{r['newton_failures']}", ha="center", va="center", fontsize=7)
            elif "start-up" in (r.get("diagnosis") or ""):
                ax.text(j, i, "s", ha="center", va="center", fontsize=11, color="grey")
            else:
                ax.text(j, i, "x", ha="center", va="center", fontsize=14, color="red")
        im = ax.imshow(grid, origin="lower", cmap="viridis", vmin=vmin, vmax=vmax, aspect="auto")
        ax.set_xticks(range(len(speeds)), speeds, fontsize=7, rotation=30)
        ax.set_yticks(range(len(DAMPING)), DAMPING if v == variants[0] else [], fontsize=7)
        ax.set_title(v, fontsize=9)
        ax.set_xlabel("driven-ring speed", fontsize=8)
    axes[0][0].set_ylabel("race damping factor", fontsize=8)
    fig.colorbar(im, ax=axes[0].tolist(), label="log10 right-hand sides", shrink=0.8)
    fig.suptitle(f"stability map, {name}: colour = cost, numbers = error-test / Newton failures, x = failed, "
                 "s = no start-up state (before any method runs)",
                 fontsize=10)
    fig.savefig(path, dpi=90, bbox_inches="tight")
    plt.close(fig)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--binary", default=os.path.join(wp.ROOT, "build", "raceway"))
    p.add_argument("--scenes", nargs="+", default=["seed002_40hz", "6309_R3"])
    p.add_argument("--variants", nargs="+", default=list(VARIANTS), choices=list(VARIANTS))
    p.add_argument("--timeout", type=float, default=60)
    p.add_argument("--out", default=os.path.join(wp.ROOT, "perf", "studies", "results"))
    p.add_argument("--replot", action="store_true", help="only redraw the PNGs from the CSV files in --out")
    args = p.parse_args()
    if args.replot:
        for name in args.scenes:
            with open(os.path.join(args.out, f"stability_{name}.csv")) as f:
                plot(name, list(csv.DictReader(f)), os.path.join(args.out, f"stability_{name}.png"))
        return
    for name in args.scenes:
        rows = []
        with tempfile.TemporaryDirectory(prefix="stability_") as workdir:
            for v in args.variants:
                for d in DAMPING:
                    for f in SPEED_FACTORS:
                        r = one_run(args.binary, name, v, d, f, workdir, args.timeout)
                        rows.append(r)
                        print(f"{name} {v:7s} damping {d:8s} speed {r['speed']:10s}: {r['status']}"
                              + (f", {r['rhs_evaluations']} rhs, {r['steps']} steps, {r['error_test_failures']} etf, "
                                 f"{r['newton_failures']} nf, {r['wall_time_s']:.2f} s" if r["status"] == "ok" else
                                 f" {r.get('diagnosis', '')}"), flush=True)
        fields = ["scene", "variant", "damping", "speed", "status", "wall_time_s", "rhs_evaluations", "steps",
                  "error_test_failures", "newton_failures", "diagnosis"]
        with open(os.path.join(args.out, f"stability_{name}.csv"), "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=fields)
            w.writeheader()
            w.writerows(rows)
        plot(name, rows, os.path.join(args.out, f"stability_{name}.png"))


if __name__ == "__main__":
    main()
