#!/usr/bin/python3
"""Work-precision of the integration methods: error against cost for each method over rtol.

  perf/studies/work_precision.py [--binary build/raceway] [--scenes seed002_40hz 6309_R3 qj215_validation]
                         [--methods bdf bdf_sld adams erk ark] [--rtols 1e-3 ... 1e-10] [--out perf/studies/results]
  perf/studies/work_precision.py --winners     the winners tables of the CSV files already written

For each scene (jobs/scenes/NAME.toml, its end time shortened so that the whole sweep runs in
minutes) it runs every method at every rtol (`raceway run --method M` on a copy of the scene with
rtol set; bdf_sld is bdf with stability_limit_detection = true), and compares each run with a reference solution, the run of the reference method at the
tightest rtol. The reference is checked against a second method at the same rtol: their difference
(the reference's own uncertainty) is written beside the errors and drawn as a dashed line; errors
below it are not resolved.

Errors, all over the window [end/2, end] (the second half of the shortened run), as means over its
output samples, not single samples:
  trajectory      RMS over samples and components of the body states (rings, cage, rolling
                  elements: positions, velocities, angular velocities) on physical scales: positions
                  by the pitch radius (the rolling elements' orbit radius), velocities by the
                  rolling elements' mean orbital speed, angular velocities by their mean spin speed
                  (all from the reference run)
  cage_speed      relative error of the mean cage speed about the bearing axis
  max_load        relative error of the mean over samples of the largest rolling-element load on
                  the inner race (the sum of a rolling element's inner-race segments)
  pocket_impulse  relative error of the impulse of the pocket (cage bar) normal forces: the integral
                  over the window of their sum (trapezoids on the output samples)
against the wall time and the number of right-hand sides (the model's count, from the summary).
A run that fails (an integration failure, or longer than --timeout) is recorded as failed.

Writes, per scene: work_precision_SCENE.csv (one row per run), work_precision_SCENE.png (error
against wall time and against right-hand sides, one panel per measure). Runs sequentially (timings
are wall times of a machine otherwise idle); needs h5py, numpy, matplotlib (Debian's python3-*).
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# Shortened end times and output intervals (the window is the second half).
SCENES = {
    "seed002_40hz": {"end_time": "20 ms", "output_interval": "0.05 ms"},   # 0.8 shaft revolutions
    "6309_R3": {"end_time": "20 ms", "output_interval": "20 us"},          # 1 revolution at 3000 rpm
    # QJ215: its cage starts at the kinematic speed and first touches the balls after about 0.2 s.
    "qj215_validation": {"end_time": "0.3 s", "output_interval": "0.1 ms"},  # 5 revolutions at 1000 rpm
    "default": {"end_time": "40 ms", "output_interval": "0.1 ms"},           # 1 revolution at 1500 rpm
    "6309_R5": {"end_time": "20 ms", "output_interval": "20 us"},          # 1.9 revolutions at 5800 rpm
    "6309_M24": {"end_time": "20 ms", "output_interval": "20 us"},         # 1 revolution at 3000 rpm
}
# Method variants: a name for the tables and charts -> the --method and further [solver] keys.
# bdf2: BDF of order at most 2 (A-stable), what seed 002 ships; not in the default sweep.
VARIANTS = {"bdf": ("bdf", {}), "bdf_sld": ("bdf", {"stability_limit_detection": "true"}),
            "adams": ("adams", {}), "erk": ("erk", {}), "ark": ("ark", {}), "bdf2": ("bdf", {"max_order": "2"}),
            "bdf_auto": ("bdf", {"automatic_order": "true"}),
            "adams2": ("adams", {"max_order": "2"})}
# bdf_auto: BDF whose largest order switches between 5 and 2 by probes ([solver] automatic_order, the
# default for bdf scenes that do not give max_order); not in the default sweep.
# adams2: Adams-Moulton of order at most 2 (the trapezoidal rule: A-stable and without numerical
# damping), what 6309 R3 and QJ215 ship since perf/studies/step_classes.py; not in the default sweep.
# Each method at its default max_order and the absolute tolerances following rtol, whatever the
# scene ships (seed 002 ships BDF order 2 and fixed atols for its rtol 1e-5).
DEFAULT_ORDER = {"bdf": "5", "adams": "12", "erk": "5", "ark": "4"}
# Variants on the scene as shipped: its own method, orders and absolute tolerances, with these
# [solver] keys added (rtol is the sweep's). "shipped" is the scene's own point; the others are the
# candidates of perf/studies/step_classes.py (fewer steps per revolution on the ball scenes).
# "bearing_frame": the scene as shipped with its rolling elements' velocity-frame keys at their
# defaults (the radial factor 1 is accepted in the bearing frame: a key at its neutral value): the
# bearing frame without the radial and pocket factors, as 6309 R3 and M24 shipped before they took
# the orbital frame (docs/integration_methods.md); for other scenes the same as "shipped".
SHIPPED_VARIANTS = {"shipped": {}, "bearing_frame": {"element_velocity_frame": '"bearing"',
                                                    "radial_velocity_tolerance_factor": "1",
                                                    "pocket_tolerance_factor": "1"}}

MEASURES = ["trajectory", "cage_speed", "max_load", "pocket_impulse"]
MEASURE_TITLES = {"trajectory": "body trajectories (RMS, physical scales)", "cage_speed": "mean cage speed",
                  "max_load": "mean of the largest rolling-element load", "pocket_impulse": "pocket-force impulse"}


def set_key(text, section, key, value):
    """The scene text with `key = value` in [section] (replacing the key's line, or added under the header)."""
    lines = text.splitlines()
    header = next((i for i, l in enumerate(lines) if l.strip().startswith(f"[{section}]")), None)
    if header is None:
        return text + f"\n[{section}]\n{key} = {value}\n"
    end = next((i for i in range(header + 1, len(lines)) if lines[i].strip().startswith("[")), len(lines))
    for i in range(header + 1, end):
        if re.match(rf"\s*{re.escape(key)}\s*=", lines[i]):
            lines[i] = f"{key} = {value}"
            return "\n".join(lines) + "\n"
    lines.insert(header + 1, f"{key} = {value}")
    return "\n".join(lines) + "\n"


def scene_text(name, rtol, solver_keys=None, shorten=True):
    """The scene with rtol and solver_keys set; shorten: with SCENES' end time and output interval."""
    text = open(os.path.join(ROOT, "jobs", "scenes", name + ".toml")).read()
    for key, value in (SCENES[name] if shorten else {}).items():
        text = set_key(text, "scene", key, f'"{value}"')
    for key, value in (solver_keys or {}).items():
        text = set_key(text, "solver", key, value)
    return set_key(text, "solver", "rtol", repr(rtol))


def run(binary, name, method, rtol, workdir, timeout, shorten=True):
    """One run; returns its summary (with 'h5' the output path) or a dict with 'failed'.
    shorten=False: the scene's own end time and output interval (perf/studies/default_tolerances.py)."""
    tag = f"{name}_{method}_{rtol:.0e}"
    scene = os.path.join(workdir, tag + ".toml")
    if method in SHIPPED_VARIANTS:
        solver_keys, method_args = SHIPPED_VARIANTS[method], []
    else:
        cli_method, solver_keys = VARIANTS[method]
        # The method in the scene too: max_order's bounds are checked against the scene's method.
        solver_keys = {"method": f'"{cli_method}"', "max_order": DEFAULT_ORDER[cli_method], "atol": "{}", **solver_keys}
        method_args = ["--method", cli_method]
    with open(scene, "w") as f:
        f.write(scene_text(name, rtol, solver_keys, shorten))
    out, summary = os.path.join(workdir, tag + ".h5"), os.path.join(workdir, tag + ".json")
    start = time.monotonic()
    try:
        # The segment diagnostics at every sample (6309 R3 ships them at every 5th): the errors are
        # taken at every sample (segments_at_every_sample).
        p = subprocess.run([binary, "run", scene, "--output-thread", "off", *method_args, "-o", out, "--summary-json", summary,
                            "--set", "output.segment_every=1"], capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"failed": f"longer than {timeout:.0f} s"}
    if p.returncode != 0:
        last = (p.stderr.strip().splitlines() or ["?"])[-1]
        return {"failed": f"exit {p.returncode}: {last[:200]}"}
    s = json.load(open(summary))
    s["h5"], s["elapsed_s"] = out, time.monotonic() - start
    return s


def segments_at_every_sample(f):
    """/segments of an open file, refused (SystemExit) when the run stored them once every N samples
    ([output] segment_every > 1): this study puts them beside /time."""
    seg = f["segments"]
    every = int(seg.attrs.get("sample_stride", 1))
    if every != 1:
        raise SystemExit(f"{f.filename}: the segment diagnostics are stored once every {every} samples ([output] "
                         "segment_every); this study needs them at every sample (segment_every = 1)")
    return seg


def element_loads(f, kind_prefix):
    """[T x elements] normal force of each rolling element on the inner race (segments summed per element)."""
    seg = segments_at_every_sample(f)
    if "roller_inner_race" in seg:
        return seg["roller_inner_race/normal_force"][()]
    groove = seg["ball_inner_groove"]
    balls = groove["element" if "element" in groove else "ball"][()].astype(int)  # layout 3 / 2
    force = groove["normal_force"][()]
    out = np.zeros((force.shape[0], balls.max() + 1))
    for col, b in enumerate(balls):
        out[:, b] += force[:, col]
    return out


def pocket_forces(f):
    seg = segments_at_every_sample(f)
    if "ball_pocket" in seg:
        return seg["ball_pocket/normal_force"][()].sum(axis=1)
    return seg["cage_bar_front/normal_force"][()].sum(axis=1) + seg["cage_bar_rear/normal_force"][()].sum(axis=1)


def read_run(path):
    """The quantities compared, over the window [end/2, end]."""
    with h5py.File(path, "r") as f:
        t = f["time"][()].ravel()
        w = t >= 0.5 * t[-1] - 1e-12
        spatial = "balls" in f
        elements = "balls" if spatial else "rollers"
        states = {}
        for body in ["inner_ring", "outer_ring", "cage"]:
            for q in ["position", "velocity", "angular_velocity"]:
                states[f"{body}/{q}"] = f[f"{body}/{q}"][()][w]
        states[f"{elements}/position"] = f[f"{elements}/position"][()][w]
        states[f"{elements}/velocity"] = f[f"{elements}/velocity"][()][w]
        # layout 3: angular_velocity in both kinds (planar files of layout 2 called it spin)
        spin = f[f"{elements}/angular_velocity" if f"{elements}/angular_velocity" in f else f"{elements}/spin"][()][w]
        states[f"{elements}/spin"] = spin
        cage_w = f["cage/angular_velocity"][()][w]
        cage_w = cage_w[:, 2] if cage_w.ndim == 2 and cage_w.shape[1] == 3 else cage_w.ravel()
        loads = element_loads(f, elements)[w]
        pocket = pocket_forces(f)[w]
        tw = t[w]
    return {"t": tw, "states": states, "cage_speed": cage_w.mean(), "max_load": loads.max(axis=1).mean(),
            "pocket_impulse": np.trapz(pocket, tw)}


def scales(ref):
    """Physical scales from the reference run: pitch radius, orbital speed, spin speed."""
    s = ref["states"]
    elements = "balls" if "balls/position" in s else "rollers"
    pos = s[f"{elements}/position"]
    radius = np.sqrt(pos[..., 0] ** 2 + pos[..., 1] ** 2).mean()
    vel = s[f"{elements}/velocity"]
    speed = np.sqrt(vel[..., 0] ** 2 + vel[..., 1] ** 2).mean()
    spin = np.abs(s[f"{elements}/spin"]).reshape(len(ref["t"]), -1)
    spin_scale = np.linalg.norm(s[f"{elements}/spin"], axis=-1).mean() if s[f"{elements}/spin"].ndim == 3 else spin.mean()
    return {"position": radius, "velocity": speed, "angular_velocity": spin_scale, "spin": spin_scale}


def errors(run_data, ref, sc):
    sq, count = 0.0, 0
    for key, r in ref["states"].items():
        kind = key.split("/")[1]
        d = (run_data["states"][key] - r) / sc[kind]
        sq += float(np.sum(d * d))
        count += d.size
    rel = lambda q: abs(run_data[q] - ref[q]) / abs(ref[q]) if ref[q] != 0 else float("nan")
    return {"trajectory": np.sqrt(sq / count), "cage_speed": rel("cage_speed"), "max_load": rel("max_load"),
            "pocket_impulse": rel("pocket_impulse")}


def plot(name, rows, floor, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, len(MEASURES), figsize=(5 * len(MEASURES), 8.5))
    methods = sorted({r["method"] for r in rows}, key=(list(VARIANTS) + list(SHIPPED_VARIANTS)).index)
    for col, m in enumerate(MEASURES):
        for row, (cost, label) in enumerate([("wall_time_s", "wall time [s]"), ("rhs_evaluations", "right-hand sides")]):
            ax = axes[row][col]
            for method in methods:
                pts = [r for r in rows if r["method"] == method and not r["failed"] and r[m] > 0]
                if not pts:
                    continue
                ax.loglog([p[cost] for p in pts], [p[m] for p in pts], "o-", label=method)
                for p in pts:
                    ax.annotate(f"{p['rtol']:.0e}", (p[cost], p[m]), fontsize=6, alpha=0.6)
            if floor.get(m, 0) > 0:
                ax.axhline(floor[m], ls="--", color="grey", lw=1, label="reference uncertainty")
            ax.set_xlabel(label)
            ax.set_ylabel("error")
            ax.set_title(MEASURE_TITLES[m], fontsize=9)
            ax.grid(True, which="both", alpha=0.3)
            if row == 0 and col == 0:
                ax.legend(fontsize=8)
    fig.suptitle(f"work-precision, {name} (window: second half of the run; labels: rtol)")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def sweep(args, name, workdir):
    print(f"== {name}", flush=True)
    tight = min(args.rtols)
    ref_run = run(args.binary, name, args.reference, tight, workdir, args.timeout * 4)
    if "failed" in ref_run:
        sys.exit(f"{name}: the reference run ({args.reference} at {tight:g}) failed: {ref_run['failed']}")
    ref = read_run(ref_run["h5"])
    sc = scales(ref)
    check_run = run(args.binary, name, args.check, tight, workdir, args.timeout * 4)
    floor = errors(read_run(check_run["h5"]), ref, sc) if "failed" not in check_run else {}
    print(f"   reference {args.reference} {tight:g}; {args.check} at the same rtol differs by "
          + ", ".join(f"{k} {v:.2g}" for k, v in floor.items()), flush=True)
    rows = []
    for method in args.methods:
        for rtol in args.rtols:
            s = run(args.binary, name, method, rtol, workdir, args.timeout)
            row = {"scene": name, "method": method, "rtol": rtol, "failed": s.get("failed", "")}
            if not row["failed"]:
                row.update({k: s[k] for k in ["wall_time_s", "rhs_evaluations", "steps", "jacobian_evaluations",
                                              "error_test_failures", "newton_failures"]})
                row.update(errors(read_run(s["h5"]), ref, sc))
                os.remove(s["h5"])
            rows.append(row)
            print(f"   {method:5s} {rtol:.0e}: " + (row["failed"] or
                  f"{row['wall_time_s']:.2f} s, {row['rhs_evaluations']} rhs, {row['steps']} steps; "
                  + ", ".join(f"{m} {row[m]:.2g}" for m in MEASURES)), flush=True)
    return rows, floor, {"reference": f"{args.reference} rtol {tight:g}", "check": f"{args.check} rtol {tight:g}",
                         "scales": sc, "reference_values": {q: ref[q] for q in ["cage_speed", "max_load", "pocket_impulse"]}}


def write_csv(path, rows, floor, info):
    fields = ["scene", "method", "rtol", "failed", "wall_time_s", "rhs_evaluations", "steps", "jacobian_evaluations",
              "error_test_failures", "newton_failures"] + MEASURES
    with open(path, "w", newline="") as f:
        f.write(f"# reference: {info['reference']}; checked against {info['check']}: "
                + ", ".join(f"{k} {v:.3g}" for k, v in floor.items()) + "\n")
        f.write("# reference values over the window: cage speed {cage_speed:.6g} rad/s, max load {max_load:.6g} N, "
                "pocket impulse {pocket_impulse:.6g} N s\n".format(**info["reference_values"]))
        f.write("# scales: " + ", ".join(f"{k} {v:.4g}" for k, v in info["scales"].items()) + " (SI)\n")
        w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow(r)


def read_csv(path):
    """Rows and the reference uncertainty (floor) of a table this script wrote."""
    with open(path) as f:
        first = f.readline()
        floor = {m: float(v) for m, v in re.findall(r"(\w+) ([-+.\deE]+)(?:,|$)", first.split(":", 2)[2])}
        lines = [l for l in f if not l.startswith("#")]
    rows = []
    for r in csv.DictReader(lines):
        row = {"method": r["method"], "rtol": float(r["rtol"]), "failed": r["failed"]}
        if not r["failed"]:
            for k in ["wall_time_s", "rhs_evaluations"] + MEASURES:
                row[k] = float(r[k])
        rows.append(row)
    return rows, floor


def winners(name, rows, floor):
    """Text: for each measure and accuracy target, the cheapest run (by wall time and by right-hand sides)
    that meets it together with every tighter rtol of its method (so a lucky loose run does not count);
    targets below twice the reference uncertainty are not resolved and left out."""
    out = [f"{name}: the cheapest run meeting each error target, with every tighter rtol of its method "
           "(by wall time; by right-hand sides)"]
    for m in MEASURES:
        for target in [1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7]:
            if target <= 2 * floor.get(m, 0):
                continue
            ok = []
            for method in {r["method"] for r in rows}:
                runs = sorted((r for r in rows if r["method"] == method), key=lambda r: r["rtol"])
                for i, r in enumerate(runs):  # tightest first
                    if all(not q["failed"] and q[m] <= target for q in runs[: i + 1]):
                        ok.append(r)
            if not ok:
                out.append(f"  {m:15s} <= {target:.0e}: none")
                continue
            w = min(ok, key=lambda r: r["wall_time_s"])
            h = min(ok, key=lambda r: r["rhs_evaluations"])
            out.append(f"  {m:15s} <= {target:.0e}: {w['method']} rtol {w['rtol']:.0e} ({w['wall_time_s']:.2f} s); "
                       f"{h['method']} rtol {h['rtol']:.0e} ({h['rhs_evaluations']:.0f} rhs)")
    return "\n".join(out) + "\n"


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--binary", default=os.path.join(ROOT, "build", "raceway"))
    p.add_argument("--scenes", nargs="+", default=[n for n in SCENES if n not in ("default", "6309_R5", "6309_M24")])
    p.add_argument("--methods", nargs="+", default=[v for v in VARIANTS if v not in ("bdf2", "bdf_auto", "adams2")],
                   choices=list(VARIANTS) + list(SHIPPED_VARIANTS),
                   help="bdf_sld: bdf with CVODE's stability-limit detection; bdf2: bdf of order at most 2")
    p.add_argument("--rtols", nargs="+", type=float, default=[10.0 ** -k for k in range(3, 11)])
    p.add_argument("--reference", default="erk", help="method of the reference run (at the tightest rtol)")
    p.add_argument("--check", default="bdf", help="second method the reference is checked against")
    p.add_argument("--timeout", type=float, default=300, help="seconds per run")
    p.add_argument("--out", default=os.path.join(ROOT, "perf", "studies", "results"))
    p.add_argument("--winners", action="store_true",
                   help="only print the winners table of the CSV files already in --out (no runs)")
    args = p.parse_args()
    if args.winners:
        for name in args.scenes:
            path = os.path.join(args.out, f"work_precision_{name}.csv")
            if os.path.exists(path):
                print(winners(name, *read_csv(path)))
        return
    os.makedirs(args.out, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="work_precision_") as workdir:
        for name in args.scenes:
            rows, floor, info = sweep(args, name, workdir)
            write_csv(os.path.join(args.out, f"work_precision_{name}.csv"), rows, floor, info)
            print(winners(name, rows, floor), flush=True)
            plot(name, rows, floor, os.path.join(args.out, f"work_precision_{name}.png"))


if __name__ == "__main__":
    main()
