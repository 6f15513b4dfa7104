#!/usr/bin/python3
"""Pocket convergence over realizations: pocket_convergence.py's candidates, each run with a few
Jacobian increments (the same equations and tolerances, other last bits), summarized per candidate.

  perf/studies/pocket_realizations.py run [--binary build/raceway] --scene NAME --end-time TIME
                                          [--extra SECTION.KEY=VALUE,...] [--slack S] [--candidates NAME...]
                                          [--custom LABEL:SECTION.KEY=VALUE,...] --out TSV
  perf/studies/pocket_realizations.py summary TSV...

Why: a single run's step count and its per-impact errors are lotteries on some scenes. QJ215 with
Adams of unlimited order falls into one of two step regimes by chance (docs/integration_methods.md),
and its 44 ms first push ends either within 0.5 % or about 5 % short of the tight run's impulse,
whichever way the last bits of a run fall. So each candidate is run with jacobian_perturbation 1e-7
(the default), 8e-8 and 1.25e-7 (the Newton iteration's matrix, not the equations, changes) and judged
by the realizations together: their mean steps and right-hand sides (in % of the "base" candidate's
mean: the scene as shipped, with --extra), and the per-impact impulse and peak errors (pocket_convergence.py's
"impacts" rows: sum |dJ| / sum J, sum |dF| / sum F over the paired contacts, %), their median and
largest, and the paired contacts; and each realization's window totals (the "steps" rows: the
step-resolved impulse and peak of the whole window, % against the tight run), seed 002's measure.

Candidates (CANDIDATES): the shipped scene (base), the pocket factor K = 10 and 30 in the bearing
frame (every translational velocity of the touching ball) and in the orbital frame (v_theta alone), and
the orbital frame with the radial velocity tolerance 3 times looser, with and without K; the orbital
frame at the radial factors 1, 3, 10, 30 with K = 10 or 30 and the cage's rotation rate
(orbital_rR_kK_cage); --custom adds candidates with keys of their own (another rtol). Needs h5py,
numpy (pocket_convergence.py's).
"""
import argparse
import collections
import csv
import os
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ORBITAL = 'solver.element_velocity_frame="orbital"'
CANDIDATES = {
    "base": "",
    "k10": "solver.pocket_tolerance_factor=10",
    "k30": "solver.pocket_tolerance_factor=30",
    "orbital": ORBITAL,
    "orbital_k10": ORBITAL + ",solver.pocket_tolerance_factor=10",
    "orbital_k30": ORBITAL + ",solver.pocket_tolerance_factor=30",
    "orbital_r3": ORBITAL + ",solver.radial_velocity_tolerance_factor=3",
    "orbital_r3_k10": ORBITAL + ",solver.radial_velocity_tolerance_factor=3,solver.pocket_tolerance_factor=10",
    "orbital_r3_k30": ORBITAL + ",solver.radial_velocity_tolerance_factor=3,solver.pocket_tolerance_factor=30",
}
# ... and with the cage's rotation rate tightened by the factor as well (pocket_tolerance_cage), at the
# radial factors 1, 3, 10 and 30: orbital_rR_kK_cage (R = 1: the orbital frame alone).
for _r in (1, 3, 10, 30):
    for _k in (10, 30):
        CANDIDATES[f"orbital_r{_r}_k{_k}_cage"] = (ORBITAL + f",solver.radial_velocity_tolerance_factor={_r}"
                                                   f",solver.pocket_tolerance_factor={_k},solver.pocket_tolerance_cage=true")
INCREMENTS = ["1e-7", "8e-8", "1.25e-7"]


def run(args):
    candidates = []
    custom = dict(c.split(":", 1) for c in args.custom)
    for name in args.candidates + list(custom):
        keys = custom.get(name, CANDIDATES.get(name))
        for jp in args.increments:
            all_keys = [k for k in (keys, f"solver.jacobian_perturbation={jp}", args.extra) if k]
            candidates.append(f"{name}@{jp}:" + ",".join(all_keys))
    cmd = [sys.executable, os.path.join(HERE, "pocket_convergence.py"), "--binary", args.binary, "--scenes", args.scene,
           "--end-time", f"{args.scene}={args.end_time}", "--slack", args.slack, "--out", args.out,
           "--candidate"] + candidates
    subprocess.run(cmd, check=True)


def summary(paths):
    cols = ["scene", "end_time", "run", "method", "rtol", "steps", "rhs", "steps_pct", "rhs_pct", "cpu_s", "measure",
            "impulse_n_s", "peak_n", "events", "impulse_err_pct", "peak_err_pct", "worst_impulse_err_pct",
            "worst_peak_err_pct"]
    for path in paths:
        rows = [dict(zip(cols, r)) for r in csv.reader(open(path), delimiter="\t") if r and r[0] != "scene"]
        by = collections.OrderedDict()
        for r in rows:
            if "@" not in r["run"]:
                continue
            name = r["run"].split("@")[0]
            by.setdefault(name, {"steps": {}, "rhs": {}, "impacts": [], "totals": []})
            by[name]["steps"][r["run"]] = int(r["steps"])
            by[name]["rhs"][r["run"]] = int(r["rhs"])
            if r["measure"] == "steps":
                by[name]["totals"].append((float(r["impulse_err_pct"]), float(r["peak_err_pct"])))
            if r["measure"] == "impacts":
                matched = r["events"].split("/")
                by[name]["impacts"].append((float(r["impulse_err_pct"]), float(r["peak_err_pct"]),
                                            int(matched[0]), int(matched[1])))
        if "base" not in by:
            continue
        base_steps = statistics.mean(by["base"]["steps"].values())
        base_rhs = statistics.mean(by["base"]["rhs"].values())
        print(f"== {path}: {rows[0]['scene']} {rows[0]['end_time']}, {len(by['base']['steps'])} realizations per candidate")
        print("| candidate | steps (vs base) | rhs (vs base) | per impact impulse % median / max | peak % median / max | "
              "paired | window totals impulse % | peak % |")
        print("|---|---|---|---|---|---|---|---|")
        for name, d in by.items():
            steps, rhs = statistics.mean(d["steps"].values()), statistics.mean(d["rhs"].values())
            imp = [i[0] for i in d["impacts"]]
            peak = [i[1] for i in d["impacts"]]
            paired = " ".join(f"{i[2]}/{i[3]}" for i in d["impacts"])
            print(f"| {name} | {steps:,.0f} ({100 * (steps / base_steps - 1):+.1f} %) | {rhs:,.0f} "
                  f"({100 * (rhs / base_rhs - 1):+.1f} %) | {statistics.median(imp):.2f} / {max(imp):.2f} | "
                  f"{statistics.median(peak):.2f} / {max(peak):.2f} | {paired} | "
                  + " / ".join(f"{t[0]:+.2f}" for t in d["totals"]) + " | "
                  + " / ".join(f"{t[1]:+.2f}" for t in d["totals"]) + " |")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = p.add_subparsers(dest="command", required=True)
    r = sub.add_parser("run")
    r.add_argument("--binary", default=os.path.join(HERE, "..", "..", "build", "raceway"))
    r.add_argument("--scene", required=True)
    r.add_argument("--end-time", required=True)
    r.add_argument("--extra", default="", help="keys added to every candidate, e.g. solver.max_order=2")
    r.add_argument("--slack", default="1e-4", help="pocket_convergence.py's pairing slack, s")
    r.add_argument("--out", required=True)
    r.add_argument("--candidates", nargs="+", default=list(CANDIDATES), choices=list(CANDIDATES),
                   help="the candidates to run (default: all); base alone: the scene as shipped over realizations")
    r.add_argument("--increments", nargs="+", default=INCREMENTS,
                   help="the realizations' Jacobian increments (more: a steadier judgement of a lottery)")
    r.add_argument("--custom", nargs="*", default=[], metavar="LABEL:SECTION.KEY=VALUE,...",
                   help="further candidates with their own keys (e.g. r3_rtol2e-5:solver.rtol=2e-5,...)")
    s = sub.add_parser("summary")
    s.add_argument("tsv", nargs="+")
    args = p.parse_args()
    run(args) if args.command == "run" else summary(args.tsv)


if __name__ == "__main__":
    main()
