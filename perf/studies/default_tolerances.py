#!/usr/bin/python3
"""The shipped ball scenes' default method and rtol, chosen from measurements of the full runs.

  perf/studies/default_tolerances.py [--binary build/raceway] [--scenes 6309_R3 qj215_validation]
                             [--methods bdf bdf_sld adams] [--rtols 1e-4 ... 1e-8] [--repeats 3]
                             [--target 1e-3] [--out perf/studies/results]

perf/studies/work_precision.py compares the methods on shortened runs; this script checks its choice on the
runs as shipped (the scene's own end time and output interval: the validation runs of
docs/validation_ball_bearings.md). For each scene it runs a reference (--reference at --tight) and
a check (--check at --tight; their difference is the reference's own uncertainty), then every
method at every rtol, --repeats times each (the errors come from the first run, the rest are
identical). Cost: the median CPU time (user + system) of the repeats, the wall time of these
one-rank runs on an idle machine and far steadier than it on a shared one; the median wall time is
recorded beside it. Errors are perf/studies/work_precision.py's, over the second half of
the run: body trajectories (RMS on physical scales), the mean cage speed, the mean of the largest
rolling-element load, the pocket-force impulse.

The rule: the default is the cheapest run (median CPU time) whose errors in the trajectories,
the cage speed and the largest load are at most --target, together with every tighter rtol of its
method (the sweep shows that it has converged to the target, not that it was lucky). A measure the
reference does not resolve (its uncertainty at least half the target: the trajectories of a long
run with pocket impacts) is left out and said so; perf/studies/work_precision.py's shortened runs gate it.

Writes default_tolerances_SCENE.csv (one row per method and rtol, the wall times of every repeat)
and prints the table and the choice.
"""
import argparse
import csv
import os
import resource
import statistics
import sys
import tempfile

import work_precision as wp

GATED = ["trajectory", "cage_speed", "max_load"]   # the measures the target applies to


def measure(args, name, method, rtol, workdir):
    """Errors against the reference (from the first run) and the median wall time of --repeats runs."""
    row = {"scene": name, "method": method, "rtol": rtol, "failed": "", "wall_times_s": [], "cpu_times_s": []}
    for i in range(args.repeats):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        s = wp.run(args.binary, name, method, rtol, workdir, args.timeout, shorten=False)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        if "failed" in s:
            row["failed"] = s["failed"]
            return row
        row["wall_times_s"].append(s["wall_time_s"])
        row["cpu_times_s"].append(after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime)
        if i == 0:
            row.update({k: s[k] for k in ["rhs_evaluations", "steps", "error_test_failures", "newton_failures"]})
            data = wp.read_run(s["h5"])
            row.update({"cage_speed_rad_s": data["cage_speed"], "max_load_n": data["max_load"]})
            row["data"] = data
        os.remove(s["h5"])
    row["wall_time_s"] = statistics.median(row["wall_times_s"])
    row["cpu_s"] = statistics.median(row["cpu_times_s"])
    return row


def gated(floor, target):
    """The measures of GATED the reference resolves at the target (its uncertainty below half of it)."""
    return [m for m in GATED if floor[m] < 0.5 * target]


def choose(rows, measures, target):
    """The cheapest row meeting the target on measures with every tighter rtol of its method, and all that do."""
    ok = []
    for method in dict.fromkeys(r["method"] for r in rows):
        runs = sorted((r for r in rows if r["method"] == method), key=lambda r: r["rtol"])
        for i, r in enumerate(runs):  # tightest first
            if all(not q["failed"] and all(q[m] <= target for m in measures) for q in runs[: i + 1]):
                ok.append(r)
    return (min(ok, key=lambda r: r["cpu_s"]) if ok else None), ok


def scene_sweep(args, name, workdir):
    print(f"== {name} (as shipped), target {args.target:g} on {', '.join(GATED)}", flush=True)
    ref_run = wp.run(args.binary, name, args.reference, args.tight, workdir, args.timeout * 4, shorten=False)
    check_run = wp.run(args.binary, name, args.check, args.tight, workdir, args.timeout * 4, shorten=False)
    if "failed" in ref_run or "failed" in check_run:
        sys.exit(f"{name}: the reference or check run failed: {ref_run.get('failed')} {check_run.get('failed')}")
    ref = wp.read_run(ref_run["h5"])
    sc = wp.scales(ref)
    floor = wp.errors(wp.read_run(check_run["h5"]), ref, sc)
    print(f"   reference {args.reference} {args.tight:g} (cage {ref['cage_speed']:.6g} rad/s, max load "
          f"{ref['max_load']:.6g} N); {args.check} {args.tight:g} differs by "
          + ", ".join(f"{k} {v:.2g}" for k, v in floor.items()), flush=True)
    rows = []
    for method in args.methods:
        for rtol in args.rtols:
            row = measure(args, name, method, rtol, workdir)
            if not row["failed"]:
                row.update(wp.errors(row.pop("data"), ref, sc))
            rows.append(row)
            row["load_average"] = os.getloadavg()[0]  # the machine's 1-minute load after the repeats
            print(f"   {method:7s} {rtol:.0e}: " + (row["failed"] or
                  f"cpu {row['cpu_s']:.2f} s (" + " ".join(f"{t:.2f}" for t in row["cpu_times_s"]) + "), wall "
                  f"{row['wall_time_s']:.2f} s (" + " ".join(f"{t:.2f}" for t in row["wall_times_s"]) + "), "
                  f"{row['steps']} steps, {row['rhs_evaluations']} rhs; cage {row['cage_speed_rad_s'] * 30 / wp.np.pi:.3f} "
                  f"r/min, max load {row['max_load_n']:.2f} N; "
                  + ", ".join(f"{m} {row[m]:.2g}" for m in wp.MEASURES) + f"; load {row['load_average']:.1f}"), flush=True)
    measures = gated(floor, args.target)
    if measures != GATED:
        print(f"   not resolved at {args.target:g} by the reference (left out of the choice): "
              + ", ".join(m for m in GATED if m not in measures), flush=True)
    best, ok = choose(rows, measures, args.target)
    print(f"   meets {args.target:g} with every tighter rtol: "
          + ", ".join(f"{r['method']} {r['rtol']:.0e} (cpu {r['cpu_s']:.2f} s)" for r in ok), flush=True)
    print(f"   choice: " + (f"{best['method']} rtol {best['rtol']:.0e}" if best else "none"), flush=True)
    header = (f"# {name} as shipped; reference {args.reference} rtol {args.tight:g}: cage speed "
              f"{ref['cage_speed']:.9g} rad/s, max load {ref['max_load']:.9g} N; {args.check} rtol {args.tight:g} "
              "differs by " + ", ".join(f"{k} {v:.3g}" for k, v in floor.items())
              + f"\n# target {args.target:g} on {' '.join(measures)}; choice: "
              + (f"{best['method']} rtol {best['rtol']:.0e}" if best else "none") + "\n")
    return rows, header


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--binary", default=os.path.join(wp.ROOT, "build", "raceway"))
    p.add_argument("--scenes", nargs="+", default=["6309_R3", "qj215_validation"])
    p.add_argument("--methods", nargs="+", default=["bdf", "bdf_sld", "adams"], choices=list(wp.VARIANTS))
    p.add_argument("--rtols", nargs="+", type=float, default=[1e-4, 1e-5, 1e-6, 1e-7, 1e-8])
    p.add_argument("--tight", type=float, default=1e-10, help="rtol of the reference and the check")
    p.add_argument("--reference", default="bdf")
    p.add_argument("--check", default="adams")
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--target", type=float, default=1e-3)
    p.add_argument("--timeout", type=float, default=300, help="seconds per run")
    p.add_argument("--out", default=os.path.join(wp.ROOT, "perf", "studies", "results"))
    args = p.parse_args()
    fields = ["scene", "method", "rtol", "failed", "cpu_s", "cpu_times_s", "wall_time_s", "wall_times_s",
              "rhs_evaluations", "steps",
              "error_test_failures", "newton_failures", "cage_speed_rad_s", "max_load_n"] + wp.MEASURES + ["load_average"]
    with tempfile.TemporaryDirectory(prefix="default_tolerances_") as workdir:
        for name in args.scenes:
            rows, header = scene_sweep(args, name, workdir)
            with open(os.path.join(args.out, f"default_tolerances_{name}.csv"), "w", newline="") as f:
                f.write(header)
                w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
                w.writeheader()
                for r in rows:
                    w.writerow({**r, **{k: " ".join(f"{t:.3f}" for t in r[k]) for k in ["wall_times_s", "cpu_times_s"]}})


if __name__ == "__main__":
    main()
