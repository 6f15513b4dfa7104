#!/usr/bin/python3
"""The fidelity table `raceway plan` reads: what each modelling choice costs and what it changes.

  perf/calibration/fidelity_table.py [--binary build/raceway] [--scenes 6309_R3 seed002_40hz qj215_validation]
                         [--out data/fidelity_table.csv]

For each scene (jobs/scenes/NAME.toml, shortened as in perf/studies/work_precision.py) it runs the scene as
shipped (the reference) and then one variant per option of each modelling choice, each a copy of
the scene with the option's keys set (the same `section.key=value` overrides `raceway plan` prints).
Every run is repeated --repeats times and its cost is the smallest CPU time (user + system) of them:
on an idle machine the wall time of these one-rank runs, and on a shared one far steadier than the
wall time. Measured against the reference, over the second half of the shortened run (as
perf/studies/work_precision.py):

  cost_ratio          CPU time of the variant / CPU time of the reference
  cage_speed_change   relative change of the mean cage speed
  max_load_change     relative change of the mean of the largest rolling-element load
  pocket_force_change relative change of the pocket (cage bar) normal-force impulse

Then it checks the planner: for standard targets (cage speed and largest load within 0.1, 0.5, 1
and 5 %) it runs `raceway plan` on the table so far, and when the plan combines several choices
it runs that combination as a whole and adds it as a "combination" row (its overrides, measured
cost and changes), which the planner then uses instead of its product-and-sum prediction; repeated
until each plan is a single choice or a measured combination.

The reference's own uncertainty is a row too (choice "reference", the shipped scene at rtol / 10):
changes below it are not resolved. Ranks come from the replay model (perf/studies/results/replay_model.txt,
perf/calibration/replay_model.py): the predicted speed-up on this machine, results bitwise the same for any rank
count (change 0); they are rows with the note "mpirun -np P" and no overrides.
"""
import argparse
import csv
import os
import re
import resource
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "studies"))
from work_precision import ROOT, SCENES, read_run, set_key  # noqa: E402
import subprocess  # noqa: E402

QUANTITIES = ["cage_speed", "max_load", "pocket_impulse"]
COLUMNS = ["scene", "duration_s", "choice", "option", "overrides", "cpu_s", "steps", "cost_ratio",
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
# The method options of a ball scene that ships another method than bdf: bdf at its default order
# takes the shipped method's place among the options.
BDF_OPTION = {"bdf": ['solver.method="bdf"', "solver.max_order=5"]}
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
    """The scene's choices: the other gravity setting, the film law only where there is a lubricant, the
    methods other than the shipped one."""
    spatial = re.search(r'^model\s*=\s*"spatial"', text, re.M)
    choices = dict(BALL_CHOICES if spatial else ROLLER_CHOICES)
    if re.search(r"^gravity\s*=\s*false", text, re.M):
        choices["gravity"] = {"on": ["scene.gravity=true"]}
    if spatial and not re.search(r'^traction\s*=\s*"limiting_shear"', text, re.M):
        del choices["traction_law"]  # tanh already; the film law needs a lubricant
    if spatial and re.search(r"^rolling_resistance\s*=\s*true", text, re.M):
        choices.update(FILM)
    shipped = re.search(r'^method\s*=\s*"(\w+)"', text, re.M)
    if spatial and shipped and shipped.group(1) in choices["method"]:
        choices["method"] = {**BDF_OPTION, **{k: v for k, v in choices["method"].items() if k != shipped.group(1)}}
    return choices


def measure(binary, text, workdir, tag, repeats):
    scene, out = os.path.join(workdir, tag + ".toml"), os.path.join(workdir, tag + ".h5")
    with open(scene, "w") as f:
        f.write(text)
    cpu_times, summary = [], os.path.join(workdir, tag + ".json")
    for _ in range(repeats):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        # The segment diagnostics at every sample (6309 R3 ships them at every 5th): read_run takes the
        # loads at every sample, as perf/studies/work_precision.py.
        p = subprocess.run([binary, "run", scene, "--output-thread", "off", "-o", out, "--summary-json", summary,
                            "--set", "output.segment_every=1"], capture_output=True, text=True)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu_times.append(after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime)
        if p.returncode != 0:
            return None, (p.stderr.strip().splitlines() or ["?"])[-1][:120]
    import json
    data = read_run(out)
    data["cpu"], data["steps"] = min(cpu_times), json.load(open(summary))["steps"]
    return data, ""


def scene_rows(binary, name, workdir, repeats):
    base = shortened(name)
    duration = SCENES[name]["end_time"]
    ref, err = measure(binary, base, workdir, name + "_ref", repeats)
    if ref is None:
        raise SystemExit(f"{name}: the reference run failed: {err}")
    REFERENCE_DATA[name] = ref

    def row(choice, option, overrides, data, note=""):
        r = {"scene": name, "duration_s": duration, "choice": choice, "option": option,
             "overrides": " ".join(overrides), "note": note}
        if data is None:
            r.update({"cpu_s": "", "steps": "", "cost_ratio": "", "cage_speed_change": "", "max_load_change": "",
                      "pocket_force_change": ""})
            return r
        rel = {q: abs(data[q] - ref[q]) / abs(ref[q]) if ref[q] else 0.0 for q in QUANTITIES}
        r.update({"cpu_s": f"{data['cpu']:.4f}", "steps": data["steps"], "cost_ratio": f"{data['cpu'] / ref['cpu']:.4f}",
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
    # Rank counts are not a row here: their predicted speed-up is data/rank_table.csv
    # (perf/calibration/replay_model.py --table), the one table `raceway plan` and `raceway campaign` read.
    return rows


STANDARD_TARGETS = [0.001, 0.005, 0.01, 0.05]


def write_table(path, rows):
    with open(path, "w", newline="") as f:
        f.write("# written by perf/calibration/fidelity_table.py; read by `raceway plan` (solver/driver/plan_command.cpp)\n")
        w = csv.DictWriter(f, fieldnames=COLUMNS, quoting=csv.QUOTE_MINIMAL)
        w.writeheader()
        w.writerows(rows)


def planned_overrides(binary, name, table, tolerance):
    """The --set overrides (unquoted) and the labels of the choices `raceway plan` recommends."""
    scene = os.path.join(ROOT, "jobs", "scenes", name + ".toml")
    target = f"{tolerance * 100:g}%"
    p = subprocess.run([binary, "plan", scene, "--table", table, "--target", f"cage_speed={target}",
                        "--target", f"max_load={target}"], capture_output=True, text=True, check=True)
    sets, labels, measured = [], [], "recommended: measured" in p.stdout
    for line in p.stdout.splitlines():
        if line.startswith("    --set "):
            value = line[len("    --set "):]
            sets.append(value[1:-1].replace("'\\''", "'") if value.startswith("'") else value)
        elif re.match(r"  [a-z_]+: ", line) and not line.startswith(("  ranks:", "  note:")):
            labels.append(line.strip())
    return sets, labels, measured


def check_combinations(binary, name, rows, workdir, repeats):
    """Measures the multi-choice combinations the planner recommends for the standard targets."""
    table = os.path.join(workdir, "table.csv")
    ref = next(r for r in rows if r["scene"] == name and r["choice"] == "reference" and r["option"] == "as shipped")
    base = shortened(name)
    for tolerance in STANDARD_TARGETS:
        for _ in range(4):
            write_table(table, rows)
            sets, labels, measured = planned_overrides(binary, name, table, tolerance)
            if measured or len(labels) < 2:
                break
            data, err = measure(binary, apply(base, sets), workdir, f"{name}_combination_{len(rows)}", repeats)
            row = {"scene": name, "duration_s": ref["duration_s"], "choice": "combination", "option": " + ".join(labels),
                   "overrides": " ".join(sets), "note": f"failed: {err}" if data is None else "measured as a whole"}
            if data is None:
                row.update({k: "" for k in ["cpu_s", "steps", "cost_ratio", "cage_speed_change", "max_load_change",
                                            "pocket_force_change"]})
                rows.append(row)
                break
            ref_data = REFERENCE_DATA[name]
            rel = {q: abs(data[q] - ref_data[q]) / abs(ref_data[q]) if ref_data[q] else 0.0 for q in QUANTITIES}
            row.update({"cpu_s": f"{data['cpu']:.4f}", "steps": data["steps"],
                        "cost_ratio": f"{data['cpu'] / ref_data['cpu']:.4f}",
                        "cage_speed_change": f"{rel['cage_speed']:.3e}", "max_load_change": f"{rel['max_load']:.3e}",
                        "pocket_force_change": f"{rel['pocket_impulse']:.3e}"})
            rows.append(row)
            print(f"  {name} combination {row['option']}: {row['cost_ratio']} {row['max_load_change']}", flush=True)


REFERENCE_DATA = {}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "raceway"))
    ap.add_argument("--scenes", nargs="+", default=["6309_R3", "seed002_40hz", "qj215_validation"])
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--out", default=os.path.join(ROOT, "data", "fidelity_table.csv"))
    ap.add_argument("--combinations-only", action="store_true",
                    help="keep the table's rows of the scenes, re-measure their reference and add the combinations")
    args = ap.parse_args()
    rows = []
    if os.path.exists(args.out):  # keep the rows of scenes not measured now
        rows = [r for r in csv.DictReader(l for l in open(args.out) if not l.startswith("#"))
                if r["scene"] not in args.scenes]
    with tempfile.TemporaryDirectory() as work:
        for name in args.scenes:
            if args.combinations_only:
                old = [r for r in csv.DictReader(l for l in open(args.out) if not l.startswith("#"))
                       if r["scene"] == name and r["choice"] != "combination"]
                ref, _ = measure(args.binary, shortened(name), work, name + "_ref", args.repeats)
                REFERENCE_DATA[name] = {**ref, "cpu": float(old[0]["cpu_s"])}  # the table's costs are against it
                new = old
            else:
                new = scene_rows(args.binary, name, work, args.repeats)
            check_combinations(args.binary, name, new, work, args.repeats)
            rows += new
    write_table(args.out, rows)


if __name__ == "__main__":
    main()
