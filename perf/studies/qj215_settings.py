#!/usr/bin/python3
"""QJ215's solver settings: pocket convergence in every realization against the cost of the whole run.

  perf/studies/qj215_settings.py [--binary build/raceway] [--window "0.3 s"] [--slack 2e-3] [--jobs 2]
                                 [--no-full] --out TSV  LABEL:SECTION.KEY=VALUE[,...] ...

Each candidate (LABEL, the shipped scene with further keys; "base" with none is the scene as shipped) is
run in the three realizations of pocket_realizations.py (jacobian_perturbation 1e-7, 8e-8, 1.25e-7: the
same equations and tolerances, other last bits) twice:

  window  the scene cut to --window (its first pushes), its pocket contacts paired contact by contact
          with the tight run's (the scene's method at rtol 1e-9, the absolute tolerances following rtol,
          run once) as pocket_convergence.py pairs them: per impact impulse and peak errors (sum |dJ| /
          sum J, sum |dF| / sum F, %), the largest single ones, the paired / reference contacts (the
          tight run has no pocket factor, whatever the scene ships);
  full    the scene's own end time (1.2 s), its output as shipped: steps, right-hand sides (with the
          one per output sample), Jacobians, Newton iterations, and the cage speed and the largest ball
          load of the summary (the whole run's means are the work-precision study's business:
          step_classes.py).

Appends one row per run to --out (TSV). A candidate meets the pocket target when every realization
pairs all of the reference's contacts and its per impact impulse and peak errors are both within 2 %.
Needs h5py, numpy (Debian's python3-*: /usr/bin/python3).
"""
import argparse
import concurrent.futures
import csv
import json
import os
import statistics
import subprocess
import sys
import tempfile

import h5py

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pocket_convergence as pc  # noqa: E402
import work_precision as wp  # noqa: E402

ROOT = wp.ROOT
SCENE = "qj215_validation"
INCREMENTS = ["1e-7", "8e-8", "1.25e-7"]
# The tight run: Adams of unlimited order at rtol 1e-9 without the pocket factor (as the scene shipped
# before it took the factor: the reference of every earlier table).
TIGHT_FACTORS = {"solver.pocket_tolerance_factor": "1", "solver.pocket_tolerance_cage": "false"}
COLUMNS = ["label", "jacobian_perturbation", "run", "end_time", "steps", "rhs", "jacobians", "newton",
           "cage_rpm", "max_ball_load_n", "impulse_err_pct", "peak_err_pct", "worst_impulse_err_pct",
           "worst_peak_err_pct", "paired", "keys"]


def parse_keys(text):
    return dict(kv.split("=", 1) for kv in text.split(",") if kv)


def full_run(binary, keys, workdir, tag):
    """The scene as shipped (its end time and output) with `keys`: its summary."""
    text = open(os.path.join(ROOT, "jobs", "scenes", SCENE + ".toml")).read()
    for key, value in keys.items():
        section, k = key.split(".", 1)
        text = wp.set_key(text, section, k, value)
    scene, out, summary = (os.path.join(workdir, f"full_{tag}.{ext}") for ext in ("toml", "h5", "json"))
    open(scene, "w").write(text)
    p = subprocess.run([binary, "run", scene, "--output-thread", "off", "-o", out, "--summary-json", summary],
                       capture_output=True, text=True)
    if p.returncode != 0:
        return {"failed": p.stderr.strip()[-300:]}
    os.remove(out)
    return json.load(open(summary))


def window_run(binary, keys, window, workdir, tag, ref_events, slack):
    s = pc.run_one(binary, SCENE, keys, window, workdir, tag)
    events = pc.impacts(s["h5"])
    with h5py.File(s["h5"], "r") as f:
        t = f["time"][()].ravel()
    os.remove(s["h5"])
    if ref_events is None:
        return s, events
    return s, pc.match_impacts(events, ref_events, t[-1], max(5 * (t[1] - t[0]), slack))


def window_job(binary, keys, window, workdir, tag, ref_events, slack):
    try:
        s, m = window_run(binary, keys, window, workdir, tag, ref_events, slack)
    except SystemExit as e:
        return "window", {"failed": str(e)}, None
    return "window", s, m


def row(label, jp, kind, end, s, keys, m=None):
    r = {"label": label, "jacobian_perturbation": jp, "run": kind, "end_time": end}
    if "failed" in s:
        r["steps"] = "failed: " + s["failed"].replace("\t", " ").replace("\n", " ")[:200]
        return r
    r.update({"steps": s["steps"], "rhs": s["rhs_evaluations"], "jacobians": s["jacobian_evaluations"],
              "newton": s["newton_iterations"], "cage_rpm": f"{s['cage_speed_rpm']:.4f}",
              "max_ball_load_n": f"{s['max_ball_load_n']:.3f}", "keys": ",".join(f"{k}={v}" for k, v in keys.items())})
    if m:
        dj, dp, wj, wpk, matched, n_ref, _ = m
        r.update({"impulse_err_pct": f"{dj:.2f}", "peak_err_pct": f"{dp:.2f}", "worst_impulse_err_pct": f"{wj:.2f}",
                  "worst_peak_err_pct": f"{wpk:.2f}", "paired": f"{matched}/{n_ref}"})
    elif kind == "window":
        r["paired"] = "0"
    return r


def summary(paths):
    """Per candidate: mean steps and right-hand sides of the window and of the full runs (and in % of those of
    "before", the scene's former settings, or else "base"),
    per impact errors of each realization, and whether all three meet the 2 % target."""
    lines = lambda path: (line for line in open(path) if not line.startswith("#"))
    rows = [r for path in paths for r in csv.DictReader(lines(path), delimiter="\t")]
    by = {}
    for r in rows:
        by.setdefault(r["label"], {"window": [], "full": []})[r["run"]].append(r)
    mean = lambda rs, k: (statistics.mean(int(r[k]) for r in rs) if rs and all(r[k].isdigit() for r in rs)
                          else float("nan"))
    base_label = "before" if "before" in by else "base"
    base = by.get(base_label)
    print("| candidate | window steps | full steps | full rhs | per impact impulse % | per impact peak % | paired "
          "| 2 % |")
    print("|---|---|---|---|---|---|---|---|")
    for label, d in by.items():
        w, f = d["window"], d["full"]
        # Against the base's runs of the same realizations.
        same = lambda rs, brs: [b for b in brs
                                if b["jacobian_perturbation"] in {r["jacobian_perturbation"] for r in rs}]
        pct = lambda rs, brs, k: f" ({100 * (mean(rs, k) / mean(same(rs, brs), k) - 1):+.0f} %)"
        rel = lambda rs, brs, k: f"{mean(rs, k):,.0f}" + (pct(rs, brs, k) if base and label != base_label else "")
        ok = all(r["paired"] and r["paired"].split("/")[0] == r["paired"].split("/")[-1] and r["impulse_err_pct"]
                 and float(r["impulse_err_pct"]) <= 2 and float(r["peak_err_pct"]) <= 2 for r in w)
        print(f"| {label} | {rel(w, base and base['window'], 'steps')} | {rel(f, base and base['full'], 'steps')} | "
              f"{rel(f, base and base['full'], 'rhs')} | {' / '.join(r['impulse_err_pct'] or '-' for r in w)} | "
              f"{' / '.join(r['peak_err_pct'] or '-' for r in w)} | {' '.join(r['paired'] for r in w)} | "
              f"{'yes' if ok and w else 'no'} |")


def main():
    if sys.argv[1:2] == ["--summary"]:
        return summary(sys.argv[2:])
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--binary", default=os.path.join(ROOT, "build", "raceway"))
    p.add_argument("--window", default="0.3 s")
    p.add_argument("--slack", type=float, default=2e-3, help="s, the pairing slack (QJ215's runs drift 0.1-0.3 ms)")
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--increments", nargs="+", default=INCREMENTS, help="the realizations' jacobian_perturbation")
    p.add_argument("--no-full", action="store_true", help="the window runs only")
    p.add_argument("--out", required=True)
    p.add_argument("candidates", nargs="+", help="LABEL:SECTION.KEY=VALUE[,...] (base: the scene as shipped)")
    args = p.parse_args()
    binary = os.path.abspath(args.binary)
    new = not os.path.exists(args.out)
    table = open(args.out, "a")
    if new:
        table.write("\t".join(COLUMNS) + "\n")
    with tempfile.TemporaryDirectory(prefix="qj215_settings_") as workdir:
        tight = {"solver.rtol": "1e-09", "solver.atol": "{}", "solver.max_order": "12", **TIGHT_FACTORS}
        _, ref_events = window_run(binary, tight, args.window, workdir, "tight", None, args.slack)
        jobs = []
        with concurrent.futures.ProcessPoolExecutor(args.jobs) as pool:
            for c in args.candidates:
                label, _, text = c.partition(":")
                for i, jp in enumerate(args.increments):
                    keys = {**parse_keys(text), "solver.jacobian_perturbation": jp}
                    tag = f"{label}_{i}"
                    jobs.append((pool.submit(window_job, binary, keys, args.window, workdir, tag, ref_events,
                                             args.slack), label, jp, keys))
                    if not args.no_full:
                        jobs.append((pool.submit(full_run, binary, keys, workdir, tag), label, jp, keys))
            for job, label, jp, keys in jobs:
                res = job.result()
                if isinstance(res, tuple):
                    _, s, m = res
                    r = row(label, jp, "window", args.window, s, keys, m)
                else:
                    r = row(label, jp, "full", "scene", res, keys)
                table.write("\t".join(str(r.get(c, "")) for c in COLUMNS) + "\n")
                table.flush()
                print("\t".join(str(r.get(c, "")) for c in COLUMNS[:-1]), flush=True)


if __name__ == "__main__":
    main()
