#!/usr/bin/python3
"""The critical cage friction against raceway itself (docs/atlas.md, "The critical cage friction").

  perf/studies/critical_friction.py [--binary build/raceway] [--jobs 2] [--work DIR]
                                    [--out perf/studies/results/critical_friction.json]

Runs the 6205 first scene (a pressed steel cage guided by its balls, spherical pockets) at two
inner-ring speeds and two axial loads (the radial load off: every ball loaded alike, the model's
uniform ball set) over the ball-pocket friction coefficient (contact.ball_cage.friction_coefficient),
each run SETTLE + WINDOW revolutions of its kinematic cage speed. Each run is classified with the
atlas's cage-motion analysis (io/report/cage_motion.py) over its window and gets the criterion's
inputs and mu_c (io/report/cage_friction.py) from the same window. A case's friction values run in
ascending order and stop after two runs in a row that are not stable (circling or unstable: the
onset is bracketed; such a run is the costly one, tens of times the steps). Writes one JSON record
per run (after each run); a second call skips the runs --out already holds;
--table prints the markdown table of perf/studies/results/critical_friction.md from it (with
--probes FILE, the cases' mu_c from the probes' traction slopes too); --probe runs the probes.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import threading
from concurrent.futures import ThreadPoolExecutor

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "io", "report"))

import cage_friction as cf  # noqa: E402
import cage_motion as cm  # noqa: E402

SCENE = os.path.join(ROOT, "jobs", "scenes", "6205_first_scene.toml")
SPEEDS_RPM = (1500, 6000)
AXIAL_N = (300, 3000)
MUS = (0.0, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.4, 0.5)
SETTLE, WINDOW = 4, 8  # cage revolutions (at the kinematic cage speed, 0.4 of the inner ring's)
# The probes of the races' traction slope as the run shows it (cage_friction.measured_traction_damping):
# its regression wants the balls' rattling resolved, 5000 samples per cage revolution (20 us at
# 1500 r/min); coarser sampling moves it by up to 25 % (0.5 ms: 850-1575 N s/m against 1500-1530).
PROBE_MU, PROBE_REVOLUTIONS = 0.1, (2, 2, 5000)
CAGE_RATIO = 0.398  # the 6205's kinematic cage speed / inner-ring speed (docs/atlas.md)
WHIRL_LOAD = 1.0  # N: the mean pocket load of a whirling cage (12-260 N here; at rest 0.04 N, the weight's share)


def run_one(binary, work, speed, axial, mu, settle=SETTLE, window=WINDOW, samples=200):
    name = f"n{speed}_fa{axial}_mu{mu:g}_{samples}"
    out = os.path.join(work, name + ".h5")
    period = 60.0 / (speed * CAGE_RATIO)
    end = (settle + window) * period
    sets = {"inner_ring.speed": f"{speed} rpm", "inner_ring.load.fy": "0 N", "inner_ring.load.fz": f"{axial} N",
            "contact.ball_cage.friction_coefficient": f"{mu:g}", "scene.end_time": f"{end:.6g} s",
            "scene.output_interval": f"{period / samples:.6g} s"}
    args = [binary, "run", SCENE, "-o", out]
    for k, v in sets.items():
        args += ["--set", f"{k}={v}"]
    done = subprocess.run(args, capture_output=True, text=True, check=False)
    record = {"speed_rpm": speed, "axial_n": axial, "mu": mu, "end_time_s": end, "exit": done.returncode,
              "samples_per_revolution": samples}
    if done.returncode != 0:
        record["error"] = (done.stdout + done.stderr).strip().splitlines()[-1:]
        return record
    from report_data import read_run
    run = read_run(out)
    mass = cm.output_cage_mass(out)
    m = cm.classify_run(run, settle * period, cage_mass=mass)
    record.update({k: m[k] for k in ("motion_class", "reasons", "cage_dynamics_indicator", "orbit_ratio",
                                     "whirl_to_cage_frequency", "impact_rate")})
    record.update(cf.atlas_evidence(out, settle * period, cage_mass=mass))
    record["wall_s"] = json.loads(__import__("h5py").File(out)["/"].attrs["summary_json"])["wall_time_s"]
    os.remove(out)
    return record


def finite(v):
    if hasattr(v, "item"):
        v = v.item()
    return None if isinstance(v, float) and not math.isfinite(v) else v


def record_model(r):
    """The criterion's model of a record (its stored inputs; records written before the cage's and the
    guidance's were stored take the 6205's: 0.0377 kg, 2 Q / c with c = 0.159 mm, damping 0.5 s/m x Q)."""
    q = r["mean_pocket_load_n"]
    return cf.CageBallModel(
        cage_mass=r.get("cage_mass_kg") or 0.0377, balls=9, pocket_stiffness=r["pocket_stiffness_n_m"],
        traction_damping=r["traction_damping_n_s_m"], cage_speed=r["cage_speed_rad_s"], ball_mass=r["ball_mass_kg"],
        pocket_damping=r.get("pocket_damping_n_s_m", 0.5 * q),
        guide_stiffness=r.get("guide_stiffness_n_m", 2 * q / 0.159e-3))


def table(records, probes=()):
    """The runs' table and the cases' summary (markdown); `probes`: the traction slope's probe runs."""
    lines = ["| inner ring, r/min | axial load, N | mu | class | CDI | orbit ratio | pockets in contact | mean pocket "
             "load, N | k, N/um | c_t law, N s/m | c_t run, N s/m | mu_c (run's c_t) |", "|" + "---|" * 12]
    cases = {}
    for r in sorted(records, key=lambda r: (r["speed_rpm"], r["axial_n"], r["mu"])):
        if r.get("exit"):
            lines.append(f"| {r['speed_rpm']} | {r['axial_n']} | {r['mu']:g} | failed |" + " |" * 8)
            continue
        m = record_model(r)
        law = r.get("traction_damping_law_n_s_m", r["traction_damping_n_s_m"])
        run = r.get("traction_damping_run_n_s_m") or math.nan
        lines.append(
            f"| {r['speed_rpm']} | {r['axial_n']} | {r['mu']:g} | {r['motion_class']} | "
            f"{r['cage_dynamics_indicator']:.3f} | {r['orbit_ratio']:.3f} | {r['pocket_contact_share']:.2f} | "
            f"{r['mean_pocket_load_n']:.3g} | {m.pocket_stiffness / 1e6:.2f} | {law:.0f} | {run:.0f} | "
            f"{cf.critical_friction(m):.3g} |")
        c = cases.setdefault((r["speed_rpm"], r["axial_n"]), {"stable": [], "moving": [], "models": [], "calm": [],
                                                            "whirl": []})
        if r["motion_class"] == "stable":
            c["stable"].append(r["mu"])
            c["models"].append((m, law))
        else:
            c["moving"].append(r["mu"])
        # The friction's whirl loads the pockets itself: a mean pocket load above WHIRL_LOAD.
        c["whirl" if r["mean_pocket_load_n"] > WHIRL_LOAD else "calm"].append(r["mu"])
    lines += ["", "| inner ring, r/min | axial load, N | c_t law / run / probe, N s/m | mu_c, law's c_t | "
              "mu_c, run's c_t | mu_c, probe's c_t (closed form) | first run not stable | whirl onset |",
              "|---|---|---|---|---|---|---|---|"]

    def span(values):
        return f"{min(values):.3g}-{max(values):.3g}" if values else "-"

    probe = {(p["speed_rpm"], p["axial_n"]): p for p in probes if not p.get("exit")}
    for (speed, axial), c in sorted(cases.items()):
        ms = c["models"]
        by_law = [cf.critical_friction(cf.CageBallModel(**{**m.__dict__, "traction_damping": law})) for m, law in ms]
        p = probe.get((speed, axial))
        pm = record_model(p) if p else None
        at_probe = f"{cf.critical_friction(pm):.3g} ({cf.closed_form(pm):.3g})" if pm else "-"
        slopes = f"{span([law for _, law in ms])} / {span([m.traction_damping for m, _ in ms])}"
        probe_slope = f"{pm.traction_damping:.0f}" if pm else "-"
        lines.append(f"| {speed} | {axial} | {slopes} / {probe_slope} | {span(by_law)} | "
                     f"{span([cf.critical_friction(m) for m, _ in ms])} | {at_probe} | "
                     f"{min(c['moving'], default=math.inf):g} | "
                     f"{max(c['calm'], default=math.nan):g} < mu <= {min(c['whirl'], default=math.inf):g} |")
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "raceway"))
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--work", default="/tmp/critical_friction")
    ap.add_argument("--out", default=os.path.join(HERE, "results", "critical_friction.json"))
    ap.add_argument("--table", action="store_true", help="print the table of --out and exit")
    ap.add_argument("--probes", help="with --table: the probes' file (--probe)")
    ap.add_argument("--probe", action="store_true",
                    help="the traction slope's probes: mu = PROBE_MU, PROBE_REVOLUTIONS, finely sampled, into --out")
    ap.add_argument("--mus", type=float, nargs="+", default=MUS, help="the friction values to run (ascending)")
    a = ap.parse_args()
    if a.table:
        probes = []
        if a.probes:
            with open(a.probes, encoding="utf-8") as f:
                probes = json.load(f)
        with open(a.out, encoding="utf-8") as f:
            print(table(json.load(f), probes))
        return
    os.makedirs(a.work, exist_ok=True)
    if a.probe:
        todo = [(s, f) for s in SPEEDS_RPM for f in AXIAL_N]
        with ThreadPoolExecutor(max_workers=a.jobs) as pool:
            probes = list(pool.map(lambda c: run_one(a.binary, a.work, *c, PROBE_MU, *PROBE_REVOLUTIONS), todo))
        with open(a.out, "w", encoding="utf-8") as f:
            json.dump([{k: finite(v) for k, v in x.items()} for x in probes], f, indent=1)
        return
    records, lock = [], threading.Lock()
    if os.path.exists(a.out):
        with open(a.out, encoding="utf-8") as f:
            records = json.load(f)
    done = {(r["speed_rpm"], r["axial_n"], r["mu"]): r for r in records}

    def case(speed, axial):
        moving = 0
        for mu in a.mus:
            r = done.get((speed, axial, mu))
            if r is None:
                r = run_one(a.binary, a.work, speed, axial, mu)
                with lock:
                    records.append(r)
                    with open(a.out, "w", encoding="utf-8") as f:
                        json.dump([{k: finite(v) for k, v in x.items()} for x in records], f, indent=1)
            moving = moving + 1 if r.get("motion_class") in ("circling", "unstable") else 0
            if moving == 2:
                return

    with ThreadPoolExecutor(max_workers=a.jobs) as pool:
        list(pool.map(lambda c: case(*c), [(s, f) for s in SPEEDS_RPM for f in AXIAL_N]))
    records.sort(key=lambda r: (r["speed_rpm"], r["axial_n"], r["mu"]))
    with open(a.out, "w", encoding="utf-8") as f:
        json.dump([{k: finite(v) for k, v in x.items()} for x in records], f, indent=1)
    print(table(records))


if __name__ == "__main__":
    main()
