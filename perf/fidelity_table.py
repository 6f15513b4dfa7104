#!/usr/bin/python3
"""The fidelity table `raceway plan` reads: what each modelling choice costs and what it changes.

  perf/fidelity_table.py [--binary build/raceway] [--scenes 6309_R3 seed002_40hz qj215_validation]
                         [--out perf/results/fidelity_table.csv]

For each scene (jobs/scenes/NAME.toml, shortened as in perf/work_precision.py) it runs the scene as
shipped (the reference) and then one variant per option of each modelling choice, each a copy of
the scene with the option's keys set (the same `section.key=value` overrides `raceway plan` prints).
Every run is repeated --repeats times and its wall time is the smallest of them. Measured against
the reference, over the second half of the shortened run (as perf/work_precision.py):

  cost_ratio          wall time of the variant / wall time of the reference
  cage_speed_change   relative change of the mean cage speed
  max_load_change     relative change of the mean of the largest rolling-element load
  pocket_force_change relative change of the pocket (cage bar) normal-force impulse

The reference's own uncertainty is a row too (choice "reference", the shipped scene at rtol / 10):
changes below it are not resolved. Ranks come from the replay model (perf/results/replay_model.txt,
perf/replay_model.py): the predicted speed-up on this machine, results bitwise the same for any rank
count (change 0); they are rows with the note "mpirun -np P" and no overrides.
"""
import argparse
import csv
import os
import re
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from work_precision import ROOT, SCENES, read_run, set_key  # noqa: E402
import subprocess  # noqa: E402

QUANTITIES = ["cage_speed", "max_load", "pocket_impulse"]
COLUMNS = ["scene", "duration_s", "choice", "option", "overrides", "wall_s", "steps", "cost_ratio",
           "cage_speed_change", "max_load_change", "pocket_force_change", "note"]

BALL_CHOICES = {
    "gravity": {"off": ["scene.gravity=false"]},
    # (traction "none" is no option: the scenes' friction keys would then be refused as without effect)
    "traction_law": {"tanh": ['contact.ball_race.traction="tanh"']},
    "traction_grid": {"3x3": ["contact.ball_race.grid=[3, 3]"], "1x1": ["contact.ball_race.grid=[1, 1]"]},
    "method": {"adams": ['solver.method="adams"', "solver.max_order=12"],
               "erk": ['solver.method="erk"', "solver.max_order=5"]},
    "tolerance": {"rtol 1e-4": ["solver.rtol=1e-4"], "rtol 1e-5": ["solver.rtol=1e-5"],
                  "rtol 1e-7": ["solver.rtol=1e-7"]},
}
# Film: the EHL rolling resistance (its traction is the choice above); only where the scene has one.
FILM = {"film": {"off": ["contact.ball_race.rolling_resistance=false"]}}
ROLLER_CHOICES = {
    "gravity": {"off": ["scene.gravity=false"]},
    "slices": {"5": ["contact.roller_race.slices=5"]},
    "method": {"adams": ['solver.method="adams"', "solver.max_order=12"],
               "erk": ['solver.method="erk"', "solver.max_order=5"], "bdf order 5": ["solver.max_order=5"]},
    "tolerance": {"rtol 1e-4": ["solver.rtol=1e-4"], "rtol 1e-6": ["solver.rtol=1e-6"],
                  "rtol 1e-7": ["solver.rtol=1e-7"]},
}


def apply(text, overrides):
    for o in overrides:
        path, value = o.split("=", 1)
        section, key = path.rsplit(".", 1)
        text = set_key(text, section, key, value)
    return text


def shortened(name):
    text = open(os.path.join(ROOT, "jobs", "scenes", name + ".toml")).read()
    for key, value in SCENES[name].items():
        text = set_key(text, "scene", key, f'"{value}"')
    return text


def choices_of(text):
    if re.search(r'^model\s*=\s*"spatial"', text, re.M):
        choices = dict(BALL_CHOICES)
        if re.search(r"^rolling_resistance\s*=\s*true", text, re.M):
            choices.update(FILM)
        return choices
    return ROLLER_CHOICES


def measure(binary, text, workdir, tag, repeats):
    scene, out = os.path.join(workdir, tag + ".toml"), os.path.join(workdir, tag + ".h5")
    with open(scene, "w") as f:
        f.write(text)
    walls, summary = [], os.path.join(workdir, tag + ".json")
    for _ in range(repeats):
        start = time.monotonic()
        p = subprocess.run([binary, "run", scene, "-o", out, "--summary-json", summary], capture_output=True, text=True)
        walls.append(time.monotonic() - start)
        if p.returncode != 0:
            return None, (p.stderr.strip().splitlines() or ["?"])[-1][:120]
    import json
    data = read_run(out)
    data["wall"], data["steps"] = min(walls), json.load(open(summary))["steps"]
    return data, ""


def replay_speedups():
    """{P: speed-up} of 6309 R3 on this machine from perf/results/replay_model.txt (first table)."""
    path = os.path.join(ROOT, "perf", "results", "replay_model.txt")
    out, in_table = {}, False
    for line in open(path):
        if line.strip().startswith("P  predicted_wall_s"):
            in_table = True
            continue
        m = re.match(r"\s+(\d+)\s+[\d.]+\s+([\d.]+)\s+[\d.]+$", line)
        if in_table and m:
            out[int(m.group(1))] = float(m.group(2))
        elif in_table and out:
            break
    return out


def scene_rows(binary, name, workdir, repeats):
    base = shortened(name)
    duration = SCENES[name]["end_time"]
    ref, err = measure(binary, base, workdir, name + "_ref", repeats)
    if ref is None:
        raise SystemExit(f"{name}: the reference run failed: {err}")

    def row(choice, option, overrides, data, note=""):
        r = {"scene": name, "duration_s": duration, "choice": choice, "option": option,
             "overrides": " ".join(overrides), "note": note}
        if data is None:
            r.update({"wall_s": "", "steps": "", "cost_ratio": "", "cage_speed_change": "", "max_load_change": "",
                      "pocket_force_change": ""})
            return r
        rel = {q: abs(data[q] - ref[q]) / abs(ref[q]) if ref[q] else 0.0 for q in QUANTITIES}
        r.update({"wall_s": f"{data['wall']:.4f}", "steps": data["steps"], "cost_ratio": f"{data['wall'] / ref['wall']:.4f}",
                  "cage_speed_change": f"{rel['cage_speed']:.3e}", "max_load_change": f"{rel['max_load']:.3e}",
                  "pocket_force_change": f"{rel['pocket_impulse']:.3e}"})
        return r

    rows = [row("reference", "as shipped", [], ref)]
    rtol = float(re.search(r"^rtol\s*=\s*([0-9.eE+-]+)", base, re.M).group(1))
    tight, _ = measure(binary, apply(base, [f"solver.rtol={rtol / 10:g}"]), workdir, name + "_tight", 1)
    rows.append(row("reference", "uncertainty", [f"solver.rtol={rtol / 10:g}"], tight,
                    "the reference against itself at rtol / 10: smaller changes are not resolved"))
    for choice, options in choices_of(base).items():
        for option, overrides in options.items():
            if choice == "tolerance" and overrides == [f"solver.rtol={rtol:g}"]:
                continue
            data, err = measure(binary, apply(base, overrides), workdir, f"{name}_{choice}_{len(rows)}", repeats)
            rows.append(row(choice, option, overrides, data, f"failed: {err}" if data is None else ""))
            print(f"  {name} {choice} {option}: {rows[-1]['cost_ratio']} {rows[-1]['cage_speed_change']}", flush=True)
    if name == "6309_R3":
        for p, speedup in replay_speedups().items():
            if p in (2, 4, 8):
                rows.append({"scene": name, "duration_s": duration, "choice": "ranks", "option": str(p), "overrides": "",
                             "wall_s": f"{ref['wall'] / speedup:.4f}", "steps": ref["steps"],
                             "cost_ratio": f"{1 / speedup:.4f}", "cage_speed_change": "0", "max_load_change": "0",
                             "pocket_force_change": "0",
                             "note": f"mpirun -np {p}; predicted by perf/replay_model.py (bitwise the same results)"})
    return rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "raceway"))
    ap.add_argument("--scenes", nargs="+", default=["6309_R3", "seed002_40hz", "qj215_validation"])
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--out", default=os.path.join(ROOT, "perf", "results", "fidelity_table.csv"))
    args = ap.parse_args()
    rows = []
    if os.path.exists(args.out):  # keep the rows of scenes not measured now
        rows = [r for r in csv.DictReader(l for l in open(args.out) if not l.startswith("#"))
                if r["scene"] not in args.scenes]
    with tempfile.TemporaryDirectory() as work:
        for name in args.scenes:
            rows += scene_rows(args.binary, name, work, args.repeats)
    with open(args.out, "w", newline="") as f:
        f.write("# written by perf/fidelity_table.py; read by `raceway plan` (solver/driver/plan_command.cpp)\n")
        w = csv.DictWriter(f, fieldnames=COLUMNS, quoting=csv.QUOTE_MINIMAL)
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main()
