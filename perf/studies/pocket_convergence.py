#!/usr/bin/python3
"""Convergence of the pocket (cage bar) impulse and peak force: the shipped tolerances against tight runs.

  perf/studies/pocket_convergence.py [--binary build/raceway] [--scenes 6309_R3 qj215_validation seed002_40hz]
                                     [--tight 1e-9] [--end-time SCENE=TIME ...]
                                     [--candidate LABEL:SECTION.KEY=VALUE[,...] ...]
                                     [--out perf/studies/results/pocket_convergence.tsv]

Per scene it runs the scene as shipped (its method, rtol, atol and order: "default"), the same
method at rtol --tight with the absolute tolerances following rtol ("tight", the reference), a
second method at --tight ("check": BDF for an Adams scene, Adams otherwise; its difference from
the reference is the reference's own uncertainty), and each --candidate: the shipped scene with
further keys (e.g. k30:solver.pocket_tolerance_factor=30). Each run's end time is the scene's
unless --end-time gives another.

Three measurements of the same runs, so that measurement, integration and predictability can be
told apart:
  steps    the step-resolved totals of the summary (solver/run/pocket_steps.hpp): the pocket normal
           forces at every accepted step, the impulse by trapezoids between steps, the peak the
           largest step value. Impulse: both sides together (N s); peak: the larger side's (N);
           events: the onsets. Errors in % of the tight run.
  samples  the same totals from the output samples (/segments/.../normal_force): impulse by
           trapezoids on the samples, peak the largest sample.
  impacts  contact by contact: each run of output intervals with contact on one pocket side
           (/cage/pocket_step_*) is an event, paired with the tight run's event of the same pocket
           and side that starts nearest (within 5 output intervals or --slack, 0.1 ms); events the window's
           end cuts are left out. events = matched / the tight run's / this run's; errors: sum |dJ|
           / sum J and sum |dF| / sum F over the matched events (%), then the largest single ones.
           A run whose path has drifted from the reference's (a chaotic cage) matches few events:
           the totals then compare statistics of different impacts, not the same impacts.

Cost: steps and right-hand sides, and both in % of the default run's (steps_pct, rhs_pct; the
default run is made before the candidates).

Appends one row per run and measurement to --out (TSV) and prints it. Needs h5py, numpy (Debian's
python3-*). Runs sequentially; cpu_s is the child's user + system time.
"""
import argparse
import json
import os
import re
import resource
import subprocess
import sys
import tempfile

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import work_precision as wp  # noqa: E402

ROOT = wp.ROOT
CHECK = {"adams": "bdf", "bdf": "adams"}


def scene_method(name):
    text = open(os.path.join(ROOT, "jobs", "scenes", name + ".toml")).read()
    for line in text.splitlines():
        s = line.split("#")[0].strip()
        if s.startswith("method") and "=" in s:
            return s.split("=", 1)[1].strip().strip('"')
    return "bdf"


def run_one(binary, name, keys, end_time, workdir, tag):
    """One run of the scene with [section] keys replaced ({"solver.rtol": "1e-9"}); its summary and file."""
    text = open(os.path.join(ROOT, "jobs", "scenes", name + ".toml")).read()
    if end_time:
        text = wp.set_key(text, "scene", "end_time", f'"{end_time}"')
    for key, value in keys.items():
        section, k = key.split(".", 1)
        text = wp.set_key(text, section, k, value)
    scene = os.path.join(workdir, f"{name}_{tag}.toml")
    open(scene, "w").write(text)
    out, summary = os.path.join(workdir, f"{name}_{tag}.h5"), os.path.join(workdir, f"{name}_{tag}.json")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    # The segment diagnostics at every sample (6309 R3 ships them at every 5th): the samples' totals
    # are taken from /segments beside /time.
    p = subprocess.run([binary, "run", scene, "--output-thread", "off", "-o", out, "--summary-json", summary,
                        "--set", "output.segment_every=1"], capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        sys.exit(f"{name} {tag}: exit {p.returncode}: {p.stderr.strip()[-400:]}")
    s = json.load(open(summary))
    s["cpu_s"] = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
    s["h5"] = out
    return s


def from_steps(s):
    t = s["pocket_step_totals"]
    return sum(t["impulse_n_s"]), max(t["peak_force_n"]), sum(t["onsets"])


def from_samples(path):
    with h5py.File(path, "r") as f:
        t = f["time"][()].ravel()
        force = wp.pocket_forces(f)
        seg = wp.segments_at_every_sample(f)
        peak = (seg["ball_pocket/normal_force"][()] if "ball_pocket" in seg else
                np.concatenate([seg["cage_bar_front/normal_force"][()], seg["cage_bar_rear/normal_force"][()]], axis=1))
    return float(np.trapz(force, t)), float(peak.max()), float("nan")


def impacts(path):
    """The pocket contacts of a run as events: per pocket and side, each maximal run of output intervals
    with contact (/cage/pocket_step_contact_time > 0); its start time, impulse (the intervals' sum)
    and peak (their largest)."""
    with h5py.File(path, "r") as f:
        t = f["time"][()].ravel()
        on = f["cage/pocket_step_contact_time"][()] > 0
        imp, peak = f["cage/pocket_step_impulse"][()], f["cage/pocket_step_peak_force"][()]
    events = []
    for p in range(on.shape[1]):
        for side in range(on.shape[2]):
            r = 0
            while r < len(t):
                if not on[r, p, side]:
                    r += 1
                    continue
                e = r
                while e < len(t) and on[e, p, side]:
                    e += 1
                events.append({"pocket": p, "side": side, "start": t[r - 1] if r > 0 else t[0], "end": t[e - 1],
                               "impulse": float(imp[r:e, p, side].sum()), "peak": float(peak[r:e, p, side].max())})
                r = e
    return events


def match_impacts(run, ref, window_end, slack):
    """Pairs each reference event with the run's event of the same pocket and side that starts nearest
    (within `slack` s); events ending within `slack` of the window's end are left out (an impact the
    window cuts). Returns the impulse-weighted errors of the matched events (%, sum |dJ| / sum J and
    sum |dF| / sum F), the largest single errors (%) and the counts (matched, reference, run)."""
    inside = lambda e: e["end"] < window_end - slack
    ref_events = [e for e in ref if inside(e)]
    run_events = [e for e in run if inside(e)]
    used, pairs = set(), []
    for r in ref_events:
        best = min((i for i, e in enumerate(run_events) if i not in used and e["pocket"] == r["pocket"]
                    and e["side"] == r["side"] and abs(e["start"] - r["start"]) <= slack),
                   key=lambda i: abs(run_events[i]["start"] - r["start"]), default=None)
        if best is not None:
            used.add(best)
            pairs.append((run_events[best], r))
    if not pairs:
        return None
    dj = sum(abs(a["impulse"] - b["impulse"]) for a, b in pairs) / sum(b["impulse"] for _, b in pairs)
    dp = sum(abs(a["peak"] - b["peak"]) for a, b in pairs) / sum(b["peak"] for _, b in pairs)
    worst_j = max(abs(a["impulse"] / b["impulse"] - 1) for a, b in pairs if b["impulse"] > 0)
    worst_p = max(abs(a["peak"] / b["peak"] - 1) for a, b in pairs if b["peak"] > 0)
    return 100 * dj, 100 * dp, 100 * worst_j, 100 * worst_p, len(pairs), len(ref_events), len(run_events)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--binary", default=os.path.join(ROOT, "build", "raceway"))
    p.add_argument("--scenes", nargs="+", default=["6309_R3", "qj215_validation", "seed002_40hz"])
    p.add_argument("--tight", type=float, default=1e-9)
    p.add_argument("--end-time", nargs="*", default=[], help="SCENE=TIME, e.g. qj215_validation='0.3 s'")
    p.add_argument("--candidate", nargs="*", default=[],
                   help="LABEL:SECTION.KEY=VALUE[,SECTION.KEY=VALUE]: a further run of the shipped scene with these keys")
    p.add_argument("--slack", type=float, default=1e-4,
                   help="s: the impacts' pairing slack (at least 5 output intervals); QJ215's runs drift by 0.1-0.3 ms "
                        "before its first contacts, which are tens of ms apart on a pocket: 2e-3 pairs them")
    p.add_argument("--out", default=os.path.join(ROOT, "perf", "studies", "results", "pocket_convergence.tsv"))
    args = p.parse_args()
    ends = dict(e.split("=", 1) for e in args.end_time)
    new = not os.path.exists(args.out)
    table = open(args.out, "a")
    if new:
        table.write("scene\tend_time\trun\tmethod\trtol\tsteps\trhs\tsteps_pct\trhs_pct\tcpu_s\tmeasure\timpulse_n_s\tpeak_n\tevents"
                    "\timpulse_err_pct\tpeak_err_pct\tworst_impulse_err_pct\tworst_peak_err_pct\n")
    with tempfile.TemporaryDirectory() as workdir:
        for name in args.scenes:
            method = scene_method(name)
            order = lambda m: "5" if m == "bdf" else "12"
            tight = {"solver.rtol": repr(args.tight), "solver.atol": "{}", "solver.max_order": order(method)}
            runs = [("tight", tight), ("default", {}),
                    ("check", {**tight, "solver.method": f'"{CHECK[method]}"', "solver.max_order": order(CHECK[method])})]
            for c in args.candidate:
                label, keys = c.split(":", 1)
                runs.append((label, dict(kv.split("=", 1) for kv in re.split(r",(?=[a-z_]+\.[a-z_.]+=)", keys) if kv)))
            ref, ref_events, default = {}, [], None
            for tag, keys in runs:
                s = run_one(args.binary, name, keys, ends.get(name), workdir, tag)
                if tag == "default":
                    default = s
                s["default"] = default
                events = impacts(s["h5"])
                with h5py.File(s["h5"], "r") as f:
                    t = f["time"][()].ravel()
                window_end, slack = t[-1], max(5 * (t[1] - t[0]), args.slack)
                if tag == "tight":
                    ref_events = events
                rows = [("steps",) + from_steps(s), ("samples",) + from_samples(s["h5"])]
                for measure, imp, peak, count in rows:
                    if tag == "tight":
                        ref[measure] = (imp, peak)
                    ri, rp = ref[measure]
                    rows_out = [f"{imp:.6g}", f"{peak:.6g}", f"{count:g}", f"{100 * (imp / ri - 1):+.2f}",
                                f"{100 * (peak / rp - 1):+.2f}", "", ""]
                    write_row(table, name, ends, tag, s, keys, measure, rows_out)
                m = match_impacts(events, ref_events, window_end, slack)
                if m:
                    dj, dp, wj, wp_, matched, n_ref, n_run = m
                    write_row(table, name, ends, tag, s, keys, "impacts",
                              ["", "", f"{matched}/{n_ref}/{n_run}", f"{dj:.2f}", f"{dp:.2f}", f"{wj:.2f}", f"{wp_:.2f}"])
                os.remove(s["h5"])


def write_row(table, name, ends, tag, s, keys, measure, values):
    d = s["default"]
    pct = lambda k: f"{100 * (s[k] / d[k] - 1):+.1f}" if d else ""
    row = [name, ends.get(name, ""), tag, s["method"], keys.get("solver.rtol", "shipped"), s["steps"],
           s["rhs_evaluations"], pct("steps"), pct("rhs_evaluations"), f"{s['cpu_s']:.2f}", measure] + values
    table.write("\t".join(str(x) for x in row) + "\n")
    table.flush()
    print("\t".join(str(x) for x in row), flush=True)


if __name__ == "__main__":
    main()
