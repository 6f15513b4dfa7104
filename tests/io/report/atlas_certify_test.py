#!/usr/bin/env python3
"""A point that has not settled or sits on a class threshold (docs/atlas.md, "Certification of a
point"): the stability probe and the threshold's runs of io/report/atlas_runner.py and
atlas_certify.py, on synthetic orbits and metrics; the re-certification of a resumed atlas.

    atlas_certify_test.py CASE RACEWAY SOURCE_DIR      exit 0 pass, 1 fail, 77 numpy missing

CASE: certify_probe (a whirl growing from round-off below the floor, probed from off-centre starts:
a limit cycle above the sustained amplitude, one below it, a probe that does not decide),
certify_threshold (runs straddling the vortex radius threshold decided by their interval, or not),
certify_resume (a resumed atlas re-certifies its old uncertified points, reading the runs it has).
"""
import math
import os
import sys

try:
    import numpy as np
except ImportError as err:
    print(f"SKIP: {err}", file=sys.stderr)
    sys.exit(77)

CASE, RACEWAY, SOURCE = sys.argv[1], os.path.abspath(sys.argv[2]), sys.argv[3]
sys.path.insert(0, os.path.join(SOURCE, "io", "report"))
import atlas_certify as ac  # noqa: E402
import atlas_runner as ar  # noqa: E402
import cage_motion as cm  # noqa: E402

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print(f"FAIL: {what}", file=sys.stderr)


# ---- a cage at 20 Hz, 24 revolutions (1.2 s at 0.5 ms), the window the last 16; clearance 100 um ---
C = 100e-6
OMEGA = 2 * math.pi * 20.0
T = np.arange(2400) * 5e-4
SETTLING = 8 / 20.0


def landau(a0, growth, limit, t):
    """The whirl's amplitude over cage revolutions n: da/dn = g a (1 - (a / A)^2), from a0 (the
    amplitude equation of a whirl that saturates on a limit cycle A; A = inf: exponential)."""
    n = t * OMEGA / (2 * math.pi)
    if not math.isfinite(limit):
        return a0 * np.exp(growth * n)
    return limit / np.sqrt(1 + ((limit / a0) ** 2 - 1) * np.exp(-2 * growth * n))


class OrbitModel:
    """Evaluates a point as SimulatorModel does (the window and its blocks classified by cage_motion)
    on a synthetic orbit: a whirl at 0.55 of the cage speed whose amplitude follows landau(); the
    start offset (cage.initial_offset) is its start amplitude, the centred start `a0`. `runs`
    counts (tag, reused) of every evaluation; `have` lists the tags whose output is already there."""

    def __init__(self, a0, growth, limit, metric="cage_dynamics_indicator", have=(), probe=None, circle=0.0):
        self.a0, self.growth, self.limit, self.metric, self.circle = a0, growth, limit, metric, circle
        self.probe = probe or (growth, limit)  # the probes' (growth, limit), if not the same whirl
        self.runs, self.have = [], set(have)

    def evaluate(self, point_id, sets, tag="", reuse=False, later=0, longer=1):
        reused = reuse and tag in self.have
        self.runs.append((tag, reused))
        self.have.add(tag)  # its output is there from now on
        start = float(sets["cage.initial_offset"].split()[0]) * 1e-6 if "cage.initial_offset" in sets else self.a0
        t = np.arange(round(len(T) + (later + longer - 1) * (len(T) - SETTLING / 5e-4))) * 5e-4
        a = landau(start, *(self.probe if "cage.initial_offset" in sets else (self.growth, self.limit)), t)
        x = a * np.cos(0.55 * OMEGA * t) + self.circle * np.cos(OMEGA * t)
        y = a * np.sin(0.55 * OMEGA * t) + self.circle * np.sin(OMEGA * t)
        w = np.nonzero(t >= SETTLING + later * (T[-1] + 5e-4 - SETTLING))[0]
        m = cm.classify(t[w], x[w], y[w], C, OMEGA, pockets=9)
        blocks = []
        for s in ac.block_slices(len(w), 3):
            b = cm.classify(t[w][s], x[w][s], y[w][s], C, OMEGA, pockets=9)
            blocks.append({"metric": b[self.metric], "class": b["motion_class"], "orbit_radius_m": b["orbit_radius_m"]})
        m.update({"blocks": blocks, "wall_s": 0.0 if reused else 10.0, "output": f"points/{point_id}_{tag}.h5",
                  "settling_time_s": SETTLING, "end_time_s": float(T[-1])})
        return m


ATLAS = {"metric": "cage_dynamics_indicator", "classes": ["stable", "circling", "unstable"], "thresholds": {},
         "parameters": [{"key": "inner_ring.speed", "name": "speed", "range": [1000.0, 8000.0], "unit": "rpm"},
                        {"key": "cage.mass_eccentricity", "name": "unbalance", "range": [0.0, 400.0], "unit": "um"}],
         "certify": {"blocks": 3, "block_tolerance": 0.1, "growth_tolerance": 0.25, "convergence_sample": 0.25,
                     "convergence_rtol": 1e-7, "convergence_tolerance": 0.05, "realisation_key": "cage.initial_offset",
                     "realisations": ["25 um", "75 um"], "threshold_realisations": [], "ci_target": 0.1}}


def point(index=1):
    return {"id": f"p{index:04d}", "index": index, "unit": [0.5, 0.0], "status": "planned"}


def case_certify_probe():
    # A whirl growing 0.1 per cage revolution from 1e-8 of the clearance (the QJ215's at 0 um of
    # unbalance: 0.03-0.13) onto a limit cycle at 0.1 of the clearance: the window sees it grow 3x
    # at 1e-8 c (stable, its orbit growing: not settled); from 25 and 75 um it decays onto the cycle
    # (above the sustained amplitude 0.05): unstable, the centred cage linearly unstable.
    model = OrbitModel(1e-8 * C, 0.1, 0.1 * C)
    r = ar.evaluate_point(model, ATLAS, point())
    cert = r["certification"]
    print(f"limit cycle 0.1 c: {r['class']}, {r['certified_by']}; base orbit growth "
          f"{cert['probe'].get('base_growth_per_rev', math.nan):.3g}/rev, probes {cert['probe'].get('verdicts')}, "
          f"amplitudes {cert['probe'].get('probe_amplitude_ratio')}")
    check(r["metrics"]["motion_class"] == "stable" and cert["probe"]["checked"], "the base window is not stable/probed")
    check(abs(cert["probe"]["base_growth_per_rev"] - 0.1) < 0.005, "the base growth is not 0.1 per revolution")
    check(r["class"] == "unstable" and r["certified"] and cert["settled"]["ok"] and cert["realisations"]["ok"],
          f"limit cycle 0.1 c: {r['class']} certified {r['certified']}")
    check(any("linearly unstable" in s and "persists" in s for s in r["reasons"]), f"reasons {r['reasons']}")
    # The probe from 75 um decays onto the cycle at -0.0067 per revolution in its window (faster than
    # the growth rate 0.005: not "sustained"), still above the sustained amplitude: it is run once
    # more, 2 windows later, where it has settled on the cycle (unstable). The probes are the
    # realisations.
    check([t for t, _ in model.runs] == ["", "r0", "r1", "r1_later"], f"runs {model.runs}")
    check("stability probe" in r["certified_by"] and "75 um +2 windows" in r["certified_by"] and r["wall_s"] == 40.0,
          f"{r['certified_by']}, wall {r['wall_s']}")
    # The same growth onto a cycle at 0.02 of the clearance (below the sustained amplitude): the
    # probes decay to it, the point is stable (its attractor bounded below 0.05 c), certified.
    r = ar.evaluate_point(OrbitModel(1e-8 * C, 0.1, 0.02 * C), ATLAS, point())
    amps = r["certification"]["probe"]["probe_amplitude_ratio"]
    print(f"limit cycle 0.02 c: {r['class']}, {r['certified_by']}, probes end at {amps}")
    check(r["class"] == "stable" and r["certified"] and not r["certification"]["settled"]["ok"],
          f"limit cycle 0.02 c: {r['class']} certified {r['certified']}")
    check(all(a < 0.05 for a in amps) and any("decays" in s for s in r["reasons"]), f"{amps} {r['reasons']}")
    # Growing at 0.05 onto the cycle at 0.1 c: both probes still decay (-0.011, -0.014 per revolution)
    # at 0.105 c in their windows; 2 windows later both sit on the cycle: unstable.
    r = ar.evaluate_point(OrbitModel(1e-8 * C, 0.05, 0.1 * C), ATLAS, point())
    print(f"slower onto 0.1 c: {r['class']}, {r['certified_by']}, "
          f"{r['certification']['probe']['probe_growth_per_rev']}")
    check(r["class"] == "unstable" and r["certified"] and r["certification"]["probe"]["probe_later_windows"] == [2, 2],
          f"slower onto 0.1 c: {r['class']}, {r['certified_by']}")
    # Probes that decay slowly (0.01 per revolution, no cycle) from 25 and 75 um: still above the
    # sustained amplitude 2 and 6 windows later (0.075 and 0.23 c at the end), each read over the last
    # window and over the last two (the same run's output read again, not run): not decided.
    m = OrbitModel(1e-8 * C, 0.1, 0.1 * C, probe=(-0.01, math.inf))
    r = ar.evaluate_point(m, ATLAS, point())
    print(f"slow decay: {r['class']}, {r['certified_by']}")
    check(r["certification"]["probe"]["verdicts"] == ["undecided"] * 2 and not r["certified"]
          and r["class"] == "stable" and m.runs[3:] == [("r0_later", False), ("r0_later", True), ("r1_later", False),
                                                         ("r1_later", True), ("r0_later6", False), ("r0_later6", True),
                                                         ("r1_later6", False), ("r1_later6", True)],
          f"a probe still decaying above 0.05 c decides: {m.runs}")
    # Probes either side of a large limit cycle (0.35 c, growing 0.02 per revolution): from 25 um
    # the whirl grows (unstable), from 75 um it decays, still at 0.4 c: undecided alone, but the
    # cycle lies between the two, above the sustained amplitude: unstable, no longer run needed.
    m = OrbitModel(1e-8 * C, 0.1, 0.1 * C, probe=(0.02, 0.35 * C))
    r = ar.evaluate_point(m, ATLAS, point())
    p = r["certification"]["probe"]
    print(f"bracketed cycle 0.35 c: {r['class']}, {r['certified_by']}, bracket {p['cycle_bracket']}")
    check(r["class"] == "unstable" and r["certified"] and [t for t, _ in m.runs] == ["", "r0", "r1"]
          and p["probe_class"][1] != "unstable" and 0.25 < p["cycle_bracket"][0] < 0.35 < p["cycle_bracket"][1],
          f"bracketed cycle: {m.runs}, {p}")
    # A whirl growing 0.02 per revolution from 0.002 of the clearance under a synchronous circle of
    # 0.01 (a small unbalance's): the orbit hardly grows (settled), but the one whirl line grows
    # faster than the growth rate below the floor: probed (the cycle at 0.1 c: unstable).
    m = OrbitModel(0.002 * C, 0.02, 0.1 * C, probe=(0.1, 0.1 * C), circle=0.01 * C)
    r = ar.evaluate_point(m, ATLAS, point())
    cert = r["certification"]
    print(f"whirl under a circle: window {r['metrics']['motion_class']}, orbit growth "
          f"{cert['settled']['orbit_growth']:.3g}, whirl growth {r['metrics']['subsync_growth_per_rev']:.3g}: "
          f"{r['class']}, {r['certified_by']}")
    check(r["metrics"]["motion_class"] == "stable" and cert["probe"]["checked"] and r["class"] == "unstable"
          and r["certified"], f"whirl under a circle: {r['certified_by']}")
    # The same under probes that decay slowly without a cycle: the window settled, but its probe
    # does not decide: not certified (the probe, not the window, speaks for a probed point).
    r = ar.evaluate_point(OrbitModel(0.002 * C, 0.02, 0.1 * C, probe=(-0.01, math.inf), circle=0.01 * C), ATLAS,
                          point())
    check(r["certification"]["settled"]["ok"] and not r["certified"], f"undecided under a circle: {r['certified_by']}")
    # One whirl between two bins, its line hopping between them (0.483, 0.483, 0.483, 0.723 of the
    # cage speed: the QJ215 envelope's 7853 r/min point): probed; turning round (+0.75, -0.5,
    # +0.25, -0.75: a wandering centre) or two bins apart, not.
    t = cm.thresholds()
    still = {"ok": True, "orbit_growth": 1.0, "growth_tolerance": 0.25, "largest_step": 0.0, "tolerance": 0.1}
    hop = {"motion_class": "stable", "subsync_coherent": False, "subsync_growth_per_rev": 0.028,
           "subsync_frequencies": [0.483, 0.483, 0.483, 0.723], "subsync_bin": 0.24}
    check(ac.needs_probe(still, hop, t), "a whirl hopping between two bins is not probed")
    check(not ac.needs_probe(still, {**hop, "subsync_frequencies": [0.75, -0.5, 0.25, -0.75]}, t),
          "a wandering centre is probed")
    check(not ac.needs_probe(still, {**hop, "subsync_frequencies": [0.25, 0.75, 0.25, 0.75]}, t),
          "lines two bins apart are probed")
    check(not ac.needs_probe(still, {**hop, "subsync_growth_per_rev": 0.004}, t), "a whirl growing slower is probed")
    # Probes whose whirl falls from the start offset to 1e-4 of the clearance and then grows again
    # there (0.03 per revolution: the envelope's 7337 r/min, 583 N point) bound nothing: undecided.
    grow = {"motion_class": "stable", "subsync_coherent": True, "subsync_growth_per_rev": 0.028,
            "subsync_amplitude_ratio": 1.3e-4}
    check(ac.probe_verdict(grow, still, t) == "undecided" and
          ac.probe_verdict({**grow, "subsync_growth_per_rev": -0.2}, still, t) == "stable",
          "a probe growing below the floor decides")
    # A point that settles is not probed; one whose window grows with an unstable class neither.
    m = OrbitModel(0.3 * C, -0.05, math.inf)
    r = ar.evaluate_point(m, ATLAS, point())
    check(not r["certification"]["probe"]["checked"] and [t for t, _ in m.runs] == [""], f"decaying: {m.runs}")
    m = OrbitModel(0.02 * C, 0.05, math.inf)
    r = ar.evaluate_point(m, ATLAS, point())
    check(r["class"] == "unstable" and not r["certification"]["probe"]["checked"], f"growing above the floor: {r}")


WHIRL = {}


def whirl_metrics(vortex):
    """A regular whirl's metrics (circling) with its vortex radius ratio set to `vortex`."""
    if not WHIRL:
        a = 0.4 * C
        WHIRL.update(cm.classify(T, a * np.cos(OMEGA * T), a * np.sin(OMEGA * T), C, OMEGA, pockets=9))
    m = dict(WHIRL)
    m["vortex_radius_ratio"] = vortex
    m["motion_class"] = cm.classify_metrics(m)[0]
    return m


def case_certify_threshold():
    t = cm.thresholds()
    # The shipped 6205 point's four runs (7520 r/min, 1000 um): 0.737, 0.435, 0.537, 0.771.
    runs = [whirl_metrics(v) for v in (0.737, 0.435, 0.537, 0.771)]
    rec = ac.threshold_decision(runs, t, cm.classify_metrics)
    x = rec["thresholds"][0]
    print(f"four runs: {x['metric']} {x['mean']:.3f} +- {x['half_width_95']:.3f}, decided {rec['ok']}")
    check(rec["classes"] == ["unstable", "circling", "unstable", "unstable"], f"classes {rec['classes']}")
    check(x["metric"] == "vortex_radius_ratio" and abs(x["mean"] - 0.62) < 1e-3
          and abs(x["half_width_95"] - 0.256) < 2e-3
          and not rec["ok"] and rec["class"] is None, f"four runs: {rec}")
    # Ten runs about 0.62 (the same spread, 0.16): the interval clears 0.5, unstable.
    values = [0.737, 0.435, 0.537, 0.771, 0.62, 0.45, 0.80, 0.58, 0.66, 0.61]
    rec = ac.threshold_decision([whirl_metrics(v) for v in values], t, cm.classify_metrics)
    x = rec["thresholds"][0]
    print(f"ten runs: {x['mean']:.3f} +- {x['half_width_95']:.3f} -> {rec['class']}")
    check(rec["ok"] and rec["class"] == "unstable" and x["mean"] - x["half_width_95"] > 0.5, f"ten runs: {rec}")
    # Mirrored below the threshold (1 - v): circling.
    rec = ac.threshold_decision([whirl_metrics(1 - v) for v in values], t, cm.classify_metrics)
    check(rec["ok"] and rec["class"] == "circling", f"ten runs below: {rec}")
    # Through the runner: a point whose rtol rerun is circling, the realisations unstable: the
    # threshold's runs are the base, the rerun and the realisations (shared), plus the threshold's.
    class Fixed:
        runs = []

        def evaluate(self, point_id, sets, tag="", reuse=False, later=0, longer=1):
            self.runs.append(tag)
            v = {"": 0.74, "rtol": 0.43, "r0": 0.54, "r1": 0.77}.get(tag, 0.62 + 0.01 * (hash(tag) % 3))
            m = whirl_metrics(v)
            m.update({"blocks": [{"metric": m["cage_dynamics_indicator"], "class": m["motion_class"],
                                  "orbit_radius_m": 1.0}] * 3, "wall_s": 1.0})
            return m
    atlas = {**ATLAS, "certify": {**ATLAS["certify"], "threshold_realisations": ["15 um", "35 um"]}}
    r = ar.evaluate_point(Fixed(), atlas, point(index=0))
    th = r["certification"]["threshold"]
    print(f"runner: {r['class']}, {r['certified_by']}")
    check(th["checked"] and th["runs"] == 6 and Fixed.runs == ["", "rtol", "r0", "r1", "t0", "t1"],
          f"threshold runs {Fixed.runs}")
    check("threshold over 6 runs" in r["certified_by"] and (r["certified"] == th["ok"]), r["certified_by"])


def case_certify_resume():
    # An old record (no rule stamp), not certified: its window grew. Re-certified on resume: its
    # base and rtol outputs are read again (not run), the probes run; a certified point untouched.
    model = OrbitModel(1e-8 * C, 0.1, 0.1 * C, have={"", "rtol"})
    old = ar.evaluate_point(OrbitModel(1e-8 * C, 0.1, 0.1 * C), ATLAS, point(index=0))
    old.update(point(index=0))
    old["certification"].pop("rule")
    old.update({"status": "done", "class": "stable", "certified": False, "wall_s": 20.0})
    good = {**point(index=1), "status": "done", "class": "stable", "certified": True, "wall_s": 5.0,
            "certification": {"settled": {"ok": True}}}
    state = {"points": [old, good], "core_hours": 25.0 / 3600}
    log = []
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        ar.recertify(model, ATLAS, state, tmp, 2, log.append)
        ar.recertify(model, ATLAS, state, tmp, 2, log.append)  # nothing left to do
        saved = os.path.exists(os.path.join(tmp, ar.STATE))
    print(f"re-certified: {log}, runs {model.runs}, core-hours {state['core_hours'] * 3600:.1f} s")
    check(model.runs == [("", True), ("r0", False), ("r1", False), ("r1_later", False), ("rtol", True)],
          f"runs {model.runs}")
    check(old["class"] == "unstable" and old["certified"] and old["wall_s"] == 50.0 and saved, f"old point {old}")
    check(abs(state["core_hours"] * 3600 - 55.0) < 1e-9 and len(log) == 1, f"core-hours {state['core_hours']}")
    check(good == {**point(index=1), "status": "done", "class": "stable", "certified": True, "wall_s": 5.0,
                   "certification": {"settled": {"ok": True}}}, "a certified point was touched")
    # The certification's later keys are no part of the atlas's identity: the folder resumes.
    import json
    with tempfile.TemporaryDirectory() as tmp:
        scene = os.path.join(tmp, "s.toml")
        with open(scene, "w") as f:
            f.write("x = 1\n")
        a = {**ATLAS, "scene": scene, "name": "a"}
        b = {**a, "certify": {**a["certify"], "threshold_realisations": ["15 um"]}}
        check(ar.identity(a) == ar.identity(b), "threshold_realisations changes the identity")
        check(ar.identity(a) != ar.identity({**a, "certify": {**a["certify"], "ci_target": 0.2}}),
              "ci_target does not change the identity")
        json.dumps(old)  # the record is JSON


CASES = {"certify_probe": case_certify_probe, "certify_threshold": case_certify_threshold,
         "certify_resume": case_certify_resume}

if __name__ == "__main__":
    CASES[CASE]()
    sys.exit(1 if failures else 0)
