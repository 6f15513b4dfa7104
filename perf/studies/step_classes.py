#!/usr/bin/python3
"""Fewer steps per revolution on the ball scenes: what each candidate saves and what it costs in accuracy.

  perf/studies/step_classes.py [--binary build/raceway] [--scenes 6309_R3 qj215_validation seed002_40hz]
                               [--candidates NAME ...] [--cache DIR] [--out perf/studies/results/step_classes.md]

Each candidate is the scene file with some [solver] keys set (CANDIDATES below; the rest of the
scene, its absolute tolerances included, as shipped) at an rtol relative to SCENES' (the rtol the
scene shipped when the study began) or at the file's own ("shipped"). Two measurements per
candidate:

  cost per revolution   the scene's own end time cut to two lengths one inner-ring revolution apart
                        (6309 R3 20 and 40 ms, QJ215 60 and 120 ms, seed 002 25 and 50 ms: the
                        windows of perf/studies/revolution_instructions.sh), its own output; the
                        difference of the two summaries: steps, right-hand sides, Jacobians, Newton
                        iterations, error-test and Newton failures. These counts do not depend on the
                        machine's load (instructions: run revolution_instructions.sh on a build).
  work-precision point  perf/studies/work_precision.py's shortened run at the scene's rtol and its four
                        errors (trajectory, cage_speed, max_load, pocket_impulse over the second half)
                        against its reference (ERK at rtol 1e-10), which is computed once per scene
                        and kept in --cache.

A candidate qualifies on a scene when every error is within the shipped point's (or better), at the
point and in the geometric means, and it takes fewer right-hand sides and Jacobians per revolution.
Results and their reading: perf/studies/results/step_classes.md. Needs h5py and numpy (Debian's python3-*).
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import work_precision as wp  # noqa: E402

ROOT = wp.ROOT
# Scene -> the rtol it shipped when the study began (the candidates' factors multiply it), the
# revolution window (seconds) of the counts, and the end times of the work-precision runs (the
# first is work_precision.py's; the second a later window).
SCENES = {"6309_R3": {"rtol": 1e-6, "window": (0.02, 0.04), "ends": ["20 ms", "40 ms"]},
          "qj215_validation": {"rtol": 1e-6, "window": (0.06, 0.12), "ends": ["0.3 s"]},
          "seed002_40hz": {"rtol": 1e-5, "window": (0.025, 0.05), "ends": ["20 ms", "40 ms"]},
          "6309_R5": {"rtol": 1e-6, "window": (0.02, 0.02 + 60 / 5800), "ends": ["20 ms", "40 ms"]},
          "6309_M24": {"rtol": 1e-6, "window": (0.02, 0.04), "ends": ["20 ms", "40 ms"]}}
# The work-precision points are taken at rtol times these factors: one point's errors scatter by
# factors of 2 to 30 with the path the chaotic cage takes (a pocket impact caught or missed), so
# candidates are compared by the geometric mean of each error over the rtols and end times.
RTOL_FACTORS = [0.5, 1.0, 2.0]
# Candidate -> [solver] keys added to the scene (TOML values); "rtol_factor" multiplies the scene's
# rtol above, or is "own": the scene file's rtol. "bdf_auto" is BDF with the automatic order (what
# 6309 R3 shipped before this study); the others named after the change they make.
BDF_AUTO = {"method": '"bdf"', "max_order": "5", "automatic_order": "true"}
CANDIDATES = {
    "shipped": {"rtol_factor": "own"},
    "bdf_auto": BDF_AUTO,
    "bdf_auto_rtol2": {**BDF_AUTO, "rtol_factor": 2},
    "bdf_auto_rtol3": {**BDF_AUTO, "rtol_factor": 3},
    "bdf_sld": {"method": '"bdf"', "max_order": "5", "stability_limit_detection": "true"},
    "bdf_order2": {"method": '"bdf"', "max_order": "2"},
    "bdf_order3": {"method": '"bdf"', "max_order": "3"},
    "bdf_order4": {"method": '"bdf"', "max_order": "4"},
    "bdf_auto_pocket10": {**BDF_AUTO, "pocket_tolerance_factor": "10"},
    "bdf_auto_velocity_atol_1e-4": {**BDF_AUTO, "atol": '{ velocity = "1e-4 m/s" }'},
    "bdf_order2_pocket10": {"method": '"bdf"', "max_order": "2", "pocket_tolerance_factor": "10"},
    "adams2": {"method": '"adams"', "max_order": "2"},
    "adams2_rtol0.3": {"method": '"adams"', "max_order": "2", "rtol_factor": 0.3},
    "adams2_rtol0.5": {"method": '"adams"', "max_order": "2", "rtol_factor": 0.5},
    "adams2_rtol2": {"method": '"adams"', "max_order": "2", "rtol_factor": 2},
    "adams2_rtol3": {"method": '"adams"', "max_order": "2", "rtol_factor": 3},
    "adams2_rtol4": {"method": '"adams"', "max_order": "2", "rtol_factor": 4},
    "adams3": {"method": '"adams"', "max_order": "3"},
    # The balls' in-plane velocities in their orbital frame (v_r, v_theta), at the scene's own
    # settings, with v_r's tolerance loosened 1, 3 and 10 times.
    "orbital": {"rtol_factor": "own", "element_velocity_frame": '"orbital"'},
    "orbital_radial3": {"rtol_factor": "own", "element_velocity_frame": '"orbital"',
                        "radial_velocity_tolerance_factor": "3"},
    "orbital_radial10": {"rtol_factor": "own", "element_velocity_frame": '"orbital"',
                         "radial_velocity_tolerance_factor": "10"},
    "orbital_radial30": {"rtol_factor": "own", "element_velocity_frame": '"orbital"',
                         "radial_velocity_tolerance_factor": "30"},
    # ... and the pocket factor (on v_theta alone in the orbital frame; on vx, vy, vz in the bearing's).
    "shipped_pocket10": {"rtol_factor": "own", "pocket_tolerance_factor": "10"},
    "shipped_pocket30": {"rtol_factor": "own", "pocket_tolerance_factor": "30"},
    "orbital_pocket30": {"rtol_factor": "own", "element_velocity_frame": '"orbital"', "pocket_tolerance_factor": "30"},
    "orbital_radial3_pocket10": {"rtol_factor": "own", "element_velocity_frame": '"orbital"',
                                 "radial_velocity_tolerance_factor": "3", "pocket_tolerance_factor": "10"},
    "orbital_radial3_pocket30": {"rtol_factor": "own", "element_velocity_frame": '"orbital"',
                                 "radial_velocity_tolerance_factor": "3", "pocket_tolerance_factor": "30"},
    "orbital_radial10_pocket30": {"rtol_factor": "own", "element_velocity_frame": '"orbital"',
                                  "radial_velocity_tolerance_factor": "10", "pocket_tolerance_factor": "30"},
    # ... with the cage's rotation rate as well (pocket_tolerance_cage): seed 002's pocket impacts
    # converge with these (perf/studies/results/pocket_convergence.md).
    "orbital_pocket30_cage": {"rtol_factor": "own", "element_velocity_frame": '"orbital"',
                              "pocket_tolerance_factor": "30", "pocket_tolerance_cage": "true"},
    "orbital_pocket10_cage_rtol2": {"rtol_factor": 2, "element_velocity_frame": '"orbital"',
                                    "pocket_tolerance_factor": "10", "pocket_tolerance_cage": "true"},
    # QJ215 (perf/studies/qj215_settings.py): the trapezoidal rule with the pocket factor on the touching
    # ball's velocities and the cage's rotation rate, at rtol 1e-6 x the factor.
    **{f"adams2_rtol{f:g}_pocket{k}_cage": {"method": '"adams"', "max_order": "2", "rtol_factor": f,
                                            "pocket_tolerance_factor": str(k), "pocket_tolerance_cage": "true"}
       for f, k in [(1, 300), (1, 500), (2, 1000), (0.5, 300), (0.3, 100), (0.2, 100), (0.1, 30), (0.1, 100)]},
    "shipped_pocket30_cage": {"rtol_factor": "own", "pocket_tolerance_factor": "30", "pocket_tolerance_cage": "true"},
}


def scene_rtol(name, keys):
    """The candidate's rtol: the scene's above times rtol_factor, or the scene file's own."""
    factor = keys.get("rtol_factor", 1)
    if factor == "own":
        text = open(os.path.join(ROOT, "jobs", "scenes", name + ".toml")).read()
        return float(re.search(r"^rtol\s*=\s*([-+.\deE]+)", text, re.M).group(1))
    return SCENES[name]["rtol"] * factor


def solver_keys(keys):
    """The candidate's [solver] keys (rtol_factor, a factor on the scene's rtol, is not one)."""
    return {k: v for k, v in keys.items() if k != "rtol_factor"}


def counts(binary, name, keys, window, workdir):
    """Steps and evaluations over the window: the difference of two runs of the scene as shipped."""
    base = open(os.path.join(ROOT, "jobs", "scenes", name + ".toml")).read()
    out = []
    for end in window:
        text = wp.set_key(base, "scene", "end_time", f'"{end} s"')
        for key, value in solver_keys(keys).items():
            text = wp.set_key(text, "solver", key, value)
        text = wp.set_key(text, "solver", "rtol", repr(scene_rtol(name, keys)))
        scene = os.path.join(workdir, f"count_{end}.toml")
        open(scene, "w").write(text)
        summary = os.path.join(workdir, f"count_{end}.json")
        p = subprocess.run([binary, "run", scene, "--output-thread", "off", "-o", os.path.join(workdir, "count.h5"),
                            "--summary-json", summary], capture_output=True, text=True)
        if p.returncode != 0:
            return {"failed": (p.stderr.strip().splitlines() or ["?"])[-1][:200]}
        out.append(json.load(open(summary)))
    keys = ["steps", "rhs_evaluations", "jacobian_evaluations", "newton_iterations", "error_test_failures",
            "newton_failures"]
    d = {k: out[1][k] - out[0][k] for k in keys}
    d["order_choice"] = out[1]["order_choice"]
    d["limiting"] = list(out[1]["step_limiting_states"].items())[:3]
    return d


def reference(binary, name, end, cache, workdir):
    """The scene's reference run (ERK at rtol 1e-10, shortened to `end`), cached."""
    os.makedirs(cache, exist_ok=True)
    path = os.path.join(cache, f"{name}_{end.replace(' ', '')}_reference.h5")
    wp.SCENES[name]["end_time"] = end
    if not os.path.exists(path):
        s = wp.run(binary, name, "erk", 1e-10, workdir, 3600)
        if "failed" in s:
            sys.exit(f"{name}: reference failed: {s['failed']}")
        os.replace(s["h5"], path)
    return wp.read_run(path)


def points(binary, name, keys, refs, workdir):
    """Each error's geometric mean over the end times and rtols, its largest value, and the runs' rhs."""
    wp.SHIPPED_VARIANTS["candidate"] = solver_keys(keys)
    logs = {m: [] for m in wp.MEASURES}
    rhs = 0
    for end, (ref, sc) in refs.items():
        wp.SCENES[name]["end_time"] = end
        for factor in RTOL_FACTORS:
            s = wp.run(binary, name, "candidate", scene_rtol(name, keys) * factor, workdir, 1200)
            if "failed" in s:
                return {"failed": s["failed"]}
            e = wp.errors(wp.read_run(s["h5"]), ref, sc)
            os.remove(s["h5"])
            rhs += s["rhs_evaluations"]
            for m in wp.MEASURES:
                logs[m].append(max(e[m], 1e-16))
            if factor == 1.0 and end == next(iter(refs)):
                point = {f"{m}_point": e[m] for m in wp.MEASURES}  # work_precision.py's point
    out = {m: float(np.exp(np.mean(np.log(v)))) for m, v in logs.items()}
    out.update({f"{m}_max": max(v) for m, v in logs.items()})
    out.update(point)
    out["wp_rhs"] = rhs
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--binary", default=os.path.join(ROOT, "build", "raceway"))
    p.add_argument("--scenes", nargs="+", default=["6309_R3", "qj215_validation", "seed002_40hz"])
    p.add_argument("--candidates", nargs="+", default=list(CANDIDATES))
    p.add_argument("--cache", default=os.path.join(tempfile.gettempdir(), "raceway_step_classes"))
    p.add_argument("--json", help="append one JSON line per (scene, candidate) to this file")
    p.add_argument("--label", default="", help="appended to the candidates' names in the output")
    p.add_argument("--rtol-factors", nargs="+", type=float, default=RTOL_FACTORS,
                   help="the work-precision points' rtol factors (more: steadier geometric means)")
    p.add_argument("--window", nargs=2, type=float, metavar=("FROM", "TO"),
                   help="the counts' window in seconds instead of SCENES' one revolution (the counts are then "
                        "per revolution of the scene's window length)")
    p.add_argument("--extra", nargs="*", default=[], metavar="KEY=VALUE",
                   help="[solver] keys added to every candidate (another realization: jacobian_perturbation=8e-8)")
    args = p.parse_args()
    RTOL_FACTORS[:] = args.rtol_factors
    for name in CANDIDATES:
        CANDIDATES[name] = {**CANDIDATES[name], **dict(kv.split("=", 1) for kv in args.extra)}
    for name in args.scenes:
        with tempfile.TemporaryDirectory(prefix="step_classes_") as workdir:
            refs = {}
            for end in SCENES[name]["ends"]:
                ref = reference(args.binary, name, end, args.cache, workdir)
                refs[end] = (ref, wp.scales(ref))
            print(f"== {name} (rtol {SCENES[name]['rtol']:g} x {RTOL_FACTORS}, ends {SCENES[name]['ends']}, "
                  f"counts over {tuple(args.window or SCENES[name]['window'])} s; errors: geometric means)", flush=True)
            for cand in args.candidates:
                keys = CANDIDATES[cand]
                c = counts(args.binary, name, keys, tuple(args.window or SCENES[name]["window"]), workdir)
                if args.window and "failed" not in c:  # per revolution: the scene's window is one
                    revolutions = (args.window[1] - args.window[0]) / (SCENES[name]["window"][1] - SCENES[name]["window"][0])
                    c.update({k: round(c[k] / revolutions) for k in c if isinstance(c[k], int)})
                e = points(args.binary, name, keys, refs, workdir) if "failed" not in c else {}
                cand += args.label
                row = {"scene": name, "candidate": cand, "keys": keys, **c, **e}
                if "failed" in c or "failed" in e:
                    print(f"  {cand:24s} failed: {c.get('failed') or e.get('failed')}", flush=True)
                else:
                    print(f"  {cand:24s} steps {c['steps']:6d} rhs {c['rhs_evaluations']:6d} jac {c['jacobian_evaluations']:4d} "
                          f"newton {c['newton_iterations']:6d} etf {c['error_test_failures']:4d} nf {c['newton_failures']:4d} | "
                          + " ".join(f"{m} {e[m]:.2g}" for m in wp.MEASURES) + " | point "
                          + " ".join(f"{e[m + '_point']:.2g}" for m in wp.MEASURES), flush=True)
                if args.json:
                    with open(args.json, "a") as f:
                        f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main()
