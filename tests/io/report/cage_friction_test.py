#!/usr/bin/env python3
"""The critical cage friction (io/report/cage_friction.py, docs/atlas.md "The critical cage friction").

    cage_friction_test.py CASE RACEWAY SOURCE_DIR      exit 0 pass, 1 fail, 77 numpy missing

CASE: closed_form (the closed form against the critical friction of the model ball by ball, which
does not use the reduction to the balls' first harmonic; the reduced roots among its eigenvalues),
limits (no friction: stable below the cage's natural frequency, unstable above it; without radial
guidance the drift grows, not the whirl; mu_c against the traction damping: 1 / c_t without ball
mass, rising then falling with it), scaling (Z and m_c enter as m_c / Z only; mu_c ~ sqrt(m_c / Z)
at rest; the speed's factor), atlas_columns (the atlas's table carries the columns; a point beyond
the criterion gets a reason, not another class), run_inputs (a short real run of the 6205: the
pocket's Hertz constant from the output against the Hertz formula for a ball in its spherical
pocket, the masses, the run's traction slope against the law's; the same run with its segment
diagnostics at every 5th sample gives the evidence of those samples), traction_slope (the run's
slope recovered from synthetic balls with a known one).
"""
import math
import os
import subprocess
import sys
import tempfile

try:
    import numpy as np
except ImportError as err:
    print(f"SKIP: {err}", file=sys.stderr)
    sys.exit(77)

CASE, RACEWAY, SOURCE = sys.argv[1], os.path.abspath(sys.argv[2]), sys.argv[3]
sys.path.insert(0, os.path.join(SOURCE, "io", "report"))
import cage_friction as cf  # noqa: E402

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print(f"FAIL: {what}", file=sys.stderr)


def near(a, b, rel):
    return abs(a - b) <= rel * abs(b)


# A 6205-like cage: 37.7 g, 9 balls of 2.06 g, pockets 5e6 N/m, traction 400 N s/m per ball, 125 rad/s.
BASE = dict(cage_mass=0.0377, balls=9, pocket_stiffness=5e6, traction_damping=400.0, cage_speed=125.0,
            guide_stiffness=1e4)


def model(**kw):
    return cf.CageBallModel(**{**BASE, **kw})


def case_closed_form():
    for kw in ({}, {"cage_speed": -125.0}, {"balls": 12, "cage_mass": 0.1}, {"traction_damping": 3000.0},
               {"pocket_stiffness": 2e5, "cage_speed": 600.0}, {"guide_stiffness": 0.0, "cage_speed": 0.0},
               {"guide_stiffness": 0.0}):
        m = model(**kw)
        closed = cf.closed_form(m)
        full = cf.critical_friction(m, cf.full_model_eigenvalues)
        check(0 < closed < cf.MU_MAX and near(full, closed, 1e-6),
              f"{kw}: closed form {closed:.8g} against the ball-by-ball model's {full:.8g}")
        reduced = cf.critical_friction(m)
        check(near(reduced, closed, 1e-6), f"{kw}: reduced model {reduced:.8g} against the closed form {closed:.8g}")
    # The reduced roots (bearing frame) are the ball-by-ball model's (cage frame) shifted by i w.
    m = model(ball_mass=0.00206, pocket_damping=0.5)
    full = cf.full_model_eigenvalues(m, 0.3)
    for lam in cf.reduced_eigenvalues(m, 0.3):
        gap = np.min(np.abs(full - (lam - 1j * m.cage_speed)))
        check(gap <= 1e-7 * abs(lam), f"reduced root {lam:.6g} not among the full model's (off by {gap:.3g})")
    mu_r, mu_f = cf.critical_friction(m), cf.critical_friction(m, cf.full_model_eigenvalues)
    check(near(mu_f, mu_r, 1e-6), f"with ball mass and pocket damping: reduced {mu_r:.8g}, full {mu_f:.8g}")
    # Just below mu_c stable, just above unstable, the unstable root a forward whirl near w_n.
    mu_c = cf.closed_form(model())
    below, above = cf.reduced_eigenvalues(model(), 0.99 * mu_c), cf.reduced_eigenvalues(model(), 1.01 * mu_c)
    check(np.max(below.real) < 0 < np.max(above.real), "the largest real part does not change sign at mu_c")
    whirl = above[np.argmax(above.real)].imag
    check(near(whirl, model().natural_frequency, 0.01),
          f"the unstable root turns at {whirl:.6g} rad/s, not w_n = {model().natural_frequency:.6g}")


def case_limits():
    m = model()
    check(cf.growth_rate(m, 0.0) < 0, "no friction, subcritical and centred: not stable")
    check(cf.critical_friction(m) > 0.1, "no friction: mu_c should be well above 0")
    # The radial guidance against the centrifugal force: k_g = 2 m_c w^2 / Z is the edge (centred
    # implies w_n > w: a centred cage is never supercritical).
    edge = 2 * BASE["cage_mass"] * BASE["cage_speed"] ** 2 / BASE["balls"]
    for factor, stable in ((0.9, False), (1.1, True)):
        g = cf.growth_rate(model(guide_stiffness=factor * edge), 0.0, cf.full_model_eigenvalues)
        check((g < 0) == stable, f"guidance {factor} x the centrifugal edge: growth {g:.3g} at mu = 0")
    loose = model(guide_stiffness=0.0)
    check(not loose.centred and cf.growth_rate(loose, 0.0, cf.full_model_eigenvalues) > 0
          and cf.growth_rate(loose, 0.0, cf.full_model_eigenvalues, whirl_only=True) < 0,
          "no radial guidance: cage and balls should drift off without friction, the whirl stay stable")
    fast = model(pocket_stiffness=100.0, guide_stiffness=0.0, cage_speed=200.0)  # w_n = 109 rad/s < w
    check(cf.closed_form(fast) == 0.0 and cf.critical_friction(fast, cf.full_model_eigenvalues) == 0.0
          and cf.growth_rate(fast, 0.0, cf.full_model_eigenvalues, whirl_only=True) > 0,
          "supercritical cage (w_n < w): the whirl should grow without friction")
    check(cf.closed_form(model(traction_damping=0.0)) == math.inf, "no traction: no critical friction")
    # Massless balls: mu_c ~ 1 / c_t (closed form and bisection alike).
    mus = [cf.critical_friction(model(traction_damping=c)) for c in (200.0, 400.0, 800.0)]
    check(near(mus[0] / mus[1], 2.0, 1e-6) and near(mus[1] / mus[2], 2.0, 1e-6), f"mu_c not ~ 1/c_t: {mus}")
    # Ball mass: mu_c rises with c_t from a flutter limit at light damping, peaks, then falls as 1/c_t.
    heavy = [cf.critical_friction(model(ball_mass=0.00206, traction_damping=c)) for c in (10, 30, 100, 1000, 1e4)]
    check(heavy[0] < heavy[1] < heavy[2] and heavy[2] > heavy[3] > heavy[4],
          f"with ball mass mu_c should rise then fall with c_t: {heavy}")
    check(near(heavy[4], cf.closed_form(model(traction_damping=1e4)), 0.15),
          f"heavy traction: mu_c {heavy[4]:.4g} should approach the massless closed form")


def case_scaling():
    # m_c and Z enter only as m_c / Z (2 m_c / Z is the cage's mass per ball pair): the ball-by-ball
    # model of 8 balls and of 16 with twice the cage, with ball mass and pocket damping.
    a = cf.critical_friction(model(balls=8, ball_mass=0.002, pocket_damping=0.4), cf.full_model_eigenvalues)
    b = cf.critical_friction(model(balls=16, cage_mass=0.0754, ball_mass=0.002, pocket_damping=0.4),
                             cf.full_model_eigenvalues)
    check(near(a, b, 1e-6), f"Z = 8 {a:.8g} against Z = 16 with twice the cage {b:.8g}")
    c = cf.critical_friction(model(balls=16, ball_mass=0.002, pocket_damping=0.4), cf.full_model_eigenvalues)
    check(c < 0.95 * a, f"more balls under the same cage: mu_c should fall ({a:.4g} -> {c:.4g})")
    # At rest (w = 0) and massless balls: mu_c = k / (c_t w_n) ~ sqrt(m_c / Z).
    r0 = cf.critical_friction(model(cage_speed=0.0), cf.full_model_eigenvalues)
    r4 = cf.critical_friction(model(cage_speed=0.0, cage_mass=4 * BASE["cage_mass"]), cf.full_model_eigenvalues)
    check(near(r4 / r0, 2.0, 1e-6), f"four times the cage mass at rest: mu_c x {r4 / r0:.6g}, not 2")
    # The cage speed raises mu_c: k / (c_t (w_n - w)).
    slow = cf.critical_friction(model(cage_speed=0.0, guide_stiffness=3e5))
    fast = cf.critical_friction(model(cage_speed=5000.0, guide_stiffness=3e5))
    wn = model(guide_stiffness=3e5).natural_frequency
    check(near(fast / slow, wn / (wn - 5000.0), 1e-6), f"speed: mu_c ratio {fast / slow:.6g} not w_n / (w_n - w)")


def case_atlas_columns():
    import atlas_models
    import atlas_output

    evidence = {"pocket_friction": 0.4, "critical_pocket_friction": 0.2, "pocket_friction_margin": 2.0,
                "critical_pocket_friction_applies": True}
    saved = atlas_models.cf.atlas_evidence
    atlas_models.cf.atlas_evidence = lambda *a, **k: dict(evidence)
    try:
        m = {"motion_class": "stable", "reasons": ["orbit ratio 0.1 < 0.2"]}
        atlas_models.add_friction_evidence(m, "unused.h5", 0.0, 0.04)
        low = {"motion_class": "stable", "reasons": []}
        evidence["pocket_friction_margin"] = 0.5
        atlas_models.add_friction_evidence(low, "unused.h5", 0.0, 0.04)
    finally:
        atlas_models.cf.atlas_evidence = saved
    check(m["motion_class"] == "stable", "the criterion changed the simulated class")
    check(len(m["reasons"]) == 2 and "above the linear criterion" in m["reasons"][1],
          f"margin 2: no reason added: {m['reasons']}")
    check(low["reasons"] == [], f"margin 0.5: a reason added: {low['reasons']}")
    missing = {"motion_class": "stable", "reasons": []}
    atlas_models.add_friction_evidence(missing, os.path.join(tempfile.gettempdir(), "no_such_run.h5"), 0.0, 0.04)
    check(math.isnan(missing["critical_pocket_friction"]) and "not evaluated" in
          missing["critical_pocket_friction_note"], "an unreadable output should leave NaN and a note")
    atlas = {"parameters": [{"name": "speed", "unit": "rpm"}, {"name": "mu", "unit": "-"}],
             "metric": "cage_dynamics_indicator", "window_cage_revolutions": None}
    state = {"points": [{"id": "p0000", "batch": 0, "values": {"speed": 3000, "mu": 0.4}, "status": "done",
                         "class": "stable", "label": "stable", "metric": 0.01, "metrics": m, "certification": {}}]}
    row = atlas_output.table_rows(atlas, state)[0]
    for key, want in (("critical_pocket_friction", 0.2), ("pocket_friction_margin", 2.0), ("pocket_friction", 0.4)):
        check(key in row and row[key] == want, f"table column {key}: {row.get(key)!r}, not {want}")
    with tempfile.TemporaryDirectory() as tmp:
        atlas.update({"name": "t", "scene": "s.toml", "classes": ["stable"], "certify": {}, "thresholds": {}})
        atlas_output.write_table(atlas, state, tmp)
        with open(os.path.join(tmp, "atlas.csv"), encoding="utf-8") as f:
            header = f.readline().strip().split(",")
        check("critical_pocket_friction" in header and "pocket_friction_margin" in header,
              f"atlas.csv header lacks the columns: {header}")


def case_traction_slope():
    # Synthetic balls: each orbits at 60 rad/s with a random circumferential speed wobble v; the races
    # push back with -c v plus the weight's circumferential share (once a revolution) and a constant;
    # the pocket pushes with a force of its own, partly in step with the wobble (the regression takes
    # the races' share: the ball's mass times its acceleration less the pocket's force).
    rng = np.random.default_rng(3)
    t = np.linspace(0.0, 0.5, 5001)
    c, mass, balls = 750.0, 0.002, 9
    pos, vel, acc = np.zeros((t.size, balls, 3)), np.zeros((t.size, balls, 3)), np.zeros((t.size, balls, 6))
    pocket = rng.normal(0.0, 0.05, (t.size, balls))
    for j in range(balls):
        angle = 60.0 * t + 2 * math.pi * j / balls
        e_t = np.column_stack([-np.sin(angle), np.cos(angle)])
        wobble = 1e-4 * rng.standard_normal(t.size)
        pocket[:, j] += 300.0 * wobble  # the pocket's force follows the wobble too: it must not count
        race = -c * wobble + mass * 9.81 * np.cos(angle) + 0.3
        pos[:, j, :2] = 0.02 * np.column_stack([np.cos(angle), np.sin(angle)])
        vel[:, j, :2] = (1.2 + wobble)[:, None] * e_t
        acc[:, j, :2] = ((race + pocket[:, j]) / mass)[:, None] * e_t
    out = {"balls/position": pos, "balls/velocity": vel, "balls/acceleration": acc,
           "segments/ball_pocket/circumferential_force": pocket}
    got = cf.measured_traction_damping(out, slice(None), mass)
    check(near(got, c, 0.01), f"traction slope from synthetic balls {got:.6g}, not {c}")
    check(math.isnan(cf.measured_traction_damping({}, slice(None), mass)), "no series: NaN expected")


def case_run_inputs():
    import cage_motion as cm
    from raceway import RacewayOutput

    scene = os.path.join(SOURCE, "jobs", "scenes", "6205_first_scene.toml")
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "run.h5")
        args = [RACEWAY, "run", scene, "-o", out, "--set", "scene.end_time=40 ms", "--set", "inner_ring.load.fy=0 N",
                "--set", "inner_ring.load.fz=1000 N", "--set", "scene.output_interval=0.1 ms"]
        done = subprocess.run(args, capture_output=True, text=True, check=False)
        check(done.returncode == 0, f"the run failed: {done.stderr[-300:]}")
        if done.returncode:
            return
        mass = cm.output_cage_mass(out)
        m, ev = cf.run_inputs(out, 0.02, cage_mass=mass)
        with RacewayOutput(out) as f:
            p = f.summary["scene_parameters"]
            b = f.bearing
            q = np.asarray(f["segments/ball_pocket/normal_force"])[f.time[:] >= 0.02]
        # Hertz for a ball of radius R in a spherical pocket of radius R + c/2 (steel on steel):
        # K = 4/3 E* sqrt(R_eff), 1 / R_eff = 1 / R - 1 / (R + c / 2), E* = E / (2 (1 - nu^2)).
        r, c = b["element_radius"], b["pocket_clearance"]
        e = p["materials.steel.youngs_modulus"]["value"]
        nu = p["materials.steel.poisson_ratio"]["value"]
        hertz = 4.0 / 3.0 * e / (2 * (1 - nu * nu)) * math.sqrt(1.0 / (1.0 / r - 1.0 / (r + c / 2)))
        load = float(np.mean(q))
        want_k = 1.5 * hertz ** (2 / 3) * load ** (1 / 3)
        check(m is not None and near(m.pocket_stiffness, want_k, 0.01),
              f"pocket stiffness {getattr(m, 'pocket_stiffness', None)} against Hertz {want_k:.6g}")
        check(m is not None and m.balls == 9 and near(m.cage_mass, 0.0377, 0.01) and near(m.ball_mass, 0.002057, 0.01),
              "balls, cage or ball mass wrong")
        # The races' slope as the run shows it: positive, taken by the model, and at most the tanh law's
        # at the contacts' centres (a spinning contact's cells slide every way: its net force answers
        # the ball's speed less).
        run, law = ev["traction_damping_run_n_s_m"], ev["traction_damping_law_n_s_m"]
        check(m is not None and 0 < run <= law and m.traction_damping == run,
              f"traction slope: run {run:.4g}, law {law:.4g}, model {getattr(m, 'traction_damping', None)}")
        check(near(ev["mean_pocket_load_n"], load, 1e-9), "mean pocket load")
        # The atlas writes the evidence into its state file as it is: plain JSON types only.
        import json
        try:
            json.dumps(cf.atlas_evidence(out, 0.02, cage_mass=mass), allow_nan=True)
        except TypeError as err:
            check(False, f"the atlas's evidence is not JSON: {err}")
        strided_inputs(args, out, tmp, mass)


def strided_inputs(args, full, tmp, mass):
    """The same run with the segment diagnostics at every 5th sample ([output] segment_every): the
    criterion reads every series at the segment rows, so its evidence is the every-sample run's
    computed from samples 0, 5, 10, ... alone (the integration is the same, bit for bit)."""
    out = os.path.join(tmp, "strided.h5")
    done = subprocess.run(args[:4] + [out] + args[5:] + ["--set", "output.segment_every=5"], capture_output=True,
                          text=True, check=False)
    check(done.returncode == 0, f"the strided run failed: {done.stderr[-300:]}")
    if done.returncode:
        return
    _, ev = cf.run_inputs(out, 0.02, cage_mass=mass)
    from raceway import RacewayOutput
    with RacewayOutput(full) as f:
        every = {name: np.asarray(f[name])[::5] for name in
                 ("time", "balls/position", "balls/velocity", "balls/acceleration",
                  "segments/ball_pocket/circumferential_force", "segments/ball_pocket/normal_force")}
    window = every["time"] >= 0.02
    load = float(np.mean(every["segments/ball_pocket/normal_force"][window]))
    check(ev.get("mean_pocket_load_n") == load, f"strided: mean pocket load {ev.get('mean_pocket_load_n')} against {load}")
    slope = cf.measured_traction_damping(every, window, ev.get("ball_mass_kg", math.nan))
    check(ev.get("traction_damping_run_n_s_m") == slope,
          f"strided: the run's traction slope {ev.get('traction_damping_run_n_s_m')} against {slope} at the same samples")


if __name__ == "__main__":
    cases = {name[5:]: fn for name, fn in globals().items() if name.startswith("case_")}
    if CASE not in cases:
        print(f"unknown case {CASE} (known: {', '.join(cases)})", file=sys.stderr)
        sys.exit(2)
    cases[CASE]()
    print(f"{CASE}: {'FAIL' if failures else 'ok'}")
    sys.exit(1 if failures else 0)
