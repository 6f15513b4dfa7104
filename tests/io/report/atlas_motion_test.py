#!/usr/bin/env python3
"""The cage motion's classification (docs/atlas.md, "Classes"): io/report/cage_motion.py on synthetic orbits.

    atlas_motion_test.py CASE RACEWAY SOURCE_DIR      exit 0 pass, 1 fail, 77 numpy missing

CASE: motion_classes (synthetic orbits land in their class), motion_thresholds (each crossed
threshold moves them), motion_growth (a growing or sustained sub-synchronous whirl against a
decaying, synchronous, tiny or wandering one).
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
import cage_motion as cm  # noqa: E402

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print(f"FAIL: {what}", file=sys.stderr)


# ---- synthetic orbits: 0.2 s at 10 kHz, cage at 50 Hz, clearance 100 um --------------------------
T = np.arange(2000) * 1e-4
OMEGA = 2 * math.pi * 50.0
C = 100e-6


def settled_centre():
    """A centre resting 30 um off the axis with 4 um of white noise."""
    rng = np.random.default_rng(7)
    return 30e-6 + 4e-6 * rng.standard_normal(T.size), 4e-6 * rng.standard_normal(T.size)


def circular_whirl(radius=0.8 * C, rate=1.0):
    """A whirl at `radius` at `rate` times the cage frequency, with 0.5 um of noise."""
    rng = np.random.default_rng(8)
    return (radius * np.cos(rate * OMEGA * T) + 0.5e-6 * rng.standard_normal(T.size),
            radius * np.sin(rate * OMEGA * T) + 0.5e-6 * rng.standard_normal(T.size))


def random_walk_with_impacts():
    """A random walk in the clearance circle, reflected at its wall: each reflection an impact."""
    p, path, hits = np.zeros(2), [], 0
    steps = 12e-6 * np.random.default_rng(9).standard_normal((T.size, 2))
    for s in steps:
        p = p + s
        r = np.hypot(*p)
        if r > C:
            p *= (2 * C - r) / r
            hits += 1
        path.append(p.copy())
    path = np.array(path)
    return path[:, 0], path[:, 1], hits


def classify(x, y, **kw):
    return cm.classify(T, x, y, C, OMEGA, pockets=9, **kw)


def case_motion_classes():
    m = classify(*settled_centre())
    print(f"settled centre: rho {m['orbit_ratio']:.3g}, CDI {m['cage_dynamics_indicator']:.3g}")
    check(m["motion_class"] == "stable", f"settled centre: {m['motion_class']} {m['reasons']}")
    check(m["orbit_ratio"] < 0.1 and m["cage_dynamics_indicator"] < 0.1, f"settled centre metrics {m}")
    m = classify(*circular_whirl())
    print(f"circular whirl: rho {m['orbit_ratio']:.3g}, whirl / cage {m['whirl_to_cage_frequency']:.4g}, "
          f"{m['whirl_turns']} turns, vortex {m['vortex_radius_ratio']:.3g}, sigma_v {m['sigma_v']:.3g}, "
          f"CDI {m['cage_dynamics_indicator']:.3g}")
    check(m["motion_class"] == "circling", f"circular whirl: {m['motion_class']} {m['reasons']}")
    check(abs(m["orbit_ratio"] - 0.8) < 0.01, f"whirl orbit ratio {m['orbit_ratio']} != 0.8")
    check(abs(m["whirl_to_cage_frequency"] - 1.0) < 0.01, f"whirl / cage frequency {m['whirl_to_cage_frequency']}")
    check(m["whirl_turns"] == 9, f"whirl turns {m['whirl_turns']} != 9 (10 turns less one sample)")
    check(m["vortex_radius_ratio"] < 0.1 and m["sigma_v"] < 0.2, f"whirl regular: {m}")
    x, y = circular_whirl()
    back = cm.classify(T, x, -y, C, -OMEGA, pockets=9)  # the same whirl with a cage turning the other way
    check(back["motion_class"] == "circling" and abs(back["whirl_to_cage_frequency"] - 1.0) < 0.01,
          f"whirl with a cage turning in -z: {back['motion_class']}, ratio {back['whirl_to_cage_frequency']}")
    check(m["cage_dynamics_indicator"] < 0.02, f"whirl indicator {m['cage_dynamics_indicator']}")
    x, y, hits = random_walk_with_impacts()
    energy = 0.5 * 0.04 * (OMEGA * C) ** 2  # each impact as energetic as a whirl at the clearance
    m = classify(x, y, impact_count=hits, impact_energies=[energy] * hits, cage_mass=0.04)
    check(m["motion_class"] == "unstable", f"random walk: {m['motion_class']} {m['reasons']}")
    check(m["cage_dynamics_indicator"] > 0.3, f"random walk indicator {m['cage_dynamics_indicator']}")
    check(abs(m["impact_rate"] - hits / (9 * 10 * 1999 / 2000)) < 1e-9, f"impact rate {m['impact_rate']}")
    check(abs(m["impact_energy_ratio"] - 1.0) < 1e-9, f"impact energy ratio {m['impact_energy_ratio']}")
    print(f"random walk: {hits} impacts, rho {m['orbit_ratio']:.3g}, vortex {m['vortex_radius_ratio']:.3g}, "
          f"sigma_v {m['sigma_v']:.3g}, CDI {m['cage_dynamics_indicator']:.3g}")


def case_motion_thresholds():
    settled, whirl = settled_centre(), circular_whirl()
    m = classify(*settled)
    rho = m["orbit_ratio"]
    below = classify(*settled, overrides={"stable_orbit_ratio": 0.9 * rho})
    check(below["motion_class"] != "stable", "settled centre: stable_orbit_ratio below its rho still stable")
    above = classify(*settled, overrides={"stable_orbit_ratio": 1.1 * rho})
    check(above["motion_class"] == "stable", "settled centre: stable_orbit_ratio above its rho not stable")
    w = classify(*whirl)
    for key, metric in (("circling_vortex_ratio", "vortex_radius_ratio"), ("circling_sigma_v", "sigma_v")):
        m = classify(*whirl, overrides={key: 0.9 * w[metric]})
        check(m["motion_class"] == "unstable", f"whirl with {key} below its {metric}: {m['motion_class']}")
    m = classify(*whirl, overrides={"circling_min_turns": w["whirl_turns"] + 1})
    check(m["motion_class"] == "unstable", "whirl with more turns asked than it makes: not unstable")
    hard = dict(impact_count=200, impact_energies=[0.2 * 0.5 * 0.04 * (OMEGA * C) ** 2] * 200, cage_mass=0.04)
    m = classify(*whirl, **hard)  # 2.2 impacts per pocket and revolution at energy ratio 0.2
    check(m["motion_class"] == "unstable", f"whirl with hard impacts: {m['motion_class']}")
    m = classify(*whirl, **hard, overrides={"impact_energy_ratio_min": 0.25})
    check(m["motion_class"] == "circling", f"whirl with impacts below the energy threshold: {m['motion_class']}")
    m = classify(*whirl, **hard, overrides={"impact_rate_max": 2.5})
    check(m["motion_class"] == "circling", f"whirl with impacts below the rate threshold: {m['motion_class']}")
    x, y, hits = random_walk_with_impacts()
    loose = {"circling_vortex_ratio": 1e3, "circling_sigma_v": 1e3, "circling_min_turns": 0, "impact_rate_max": 1e3}
    m = classify(x, y, impact_count=hits, overrides=loose)
    check(m["motion_class"] == "circling", f"random walk with every threshold loosened: {m['motion_class']}")
    try:
        cm.thresholds({"no_such": 1})
        check(False, "an unknown threshold accepted")
    except ValueError:
        pass


# ---- a sub-synchronous whirl over 2 s at 5 kHz, the cage at 20 Hz (40 revolutions) -------------------
TG = np.arange(10000) * 2e-4
OMEGA_G = 2 * math.pi * 20.0


def whirl_with_subsync(growth, amplitude, ratio=0.58):
    """A synchronous circle of 1 um plus a whirl at `ratio` of the cage speed, `amplitude` [m] at the
    start, growing `growth` per cage revolution, with 0.05 um of noise."""
    rev = OMEGA_G * TG / (2 * math.pi)
    z = 1e-6 * np.exp(1j * OMEGA_G * TG) + amplitude * np.exp(growth * rev) * np.exp(1j * ratio * OMEGA_G * TG)
    noise = 5e-8 * np.random.default_rng(11).standard_normal((2, TG.size))
    z = z + noise[0] + 1j * noise[1]
    return cm.classify(TG, z.real, z.imag, C, OMEGA_G, pockets=9)


def case_motion_growth():
    """A half-speed whirl growing 0.018 per cage revolution (as the QJ215's at 1000 N, 3000 r/min) is
    unstable, the same decaying is stable, a synchronous circle is stable, a large steady one is
    unstable; the thresholds move them."""
    m = whirl_with_subsync(0.018, 2e-6)
    print(f"growing whirl: {m['motion_class']}, growth {m['subsync_growth_per_rev']:.4g} per revolution, "
          f"amplitude {m['subsync_amplitude_ratio']:.3g} c at {m['subsync_frequency_ratio']:.3g} of the cage speed, "
          f"rho {m['orbit_ratio']:.3g}")
    check(m["motion_class"] == "unstable" and "sub-synchronous" in m["reasons"][0], f"growing whirl: {m['reasons']}")
    check(abs(m["subsync_growth_per_rev"] - 0.018) < 0.0005, f"growth {m['subsync_growth_per_rev']} != 0.018")
    check(abs(m["subsync_frequency_ratio"] - 0.58) < 0.05, f"frequency ratio {m['subsync_frequency_ratio']}")
    check(m["orbit_ratio"] < 0.2, f"the growing whirl is still inside the stable orbit ratio: {m['orbit_ratio']}")
    m = whirl_with_subsync(-0.018, 6e-6)
    print(f"decaying whirl: {m['motion_class']}, growth {m['subsync_growth_per_rev']:.4g}")
    check(m["motion_class"] == "stable" and abs(m["subsync_growth_per_rev"] + 0.018) < 0.0005, f"decaying: {m}")
    m = whirl_with_subsync(0.0, 0.0)
    print(f"synchronous circle: {m['motion_class']}, sub-synchronous amplitude {m['subsync_amplitude_ratio']:.3g} c")
    check(m["motion_class"] == "stable" and m["subsync_amplitude_ratio"] < 1e-3, f"synchronous circle: {m}")
    m = whirl_with_subsync(0.018, 0.2e-6)  # grows to 0.4 um: below 0.01 c
    check(m["motion_class"] == "stable" and m["subsync_growth_per_rev"] > 0.01, f"a tiny growing whirl: {m}")
    for overrides in ({"whirl_growth_rate": 0.02}, {"whirl_growth_min_amplitude": 0.1}):
        cls = cm.classify_metrics(whirl_with_subsync(0.018, 2e-6), overrides)[0]
        check(cls == "stable", f"growing whirl with {overrides}: {cls}")
    # A whirl that has grown: steady at 8 um (0.08 c, as the QJ215's 15 um at 7125 r/min and 3222 N)
    # is unstable; steady at 3 um (0.03 c) is stable; the threshold moves it.
    m = whirl_with_subsync(0.0, 8e-6)
    print(f"steady whirl of 8 um: {m['motion_class']}, growth {m['subsync_growth_per_rev']:.3g}, "
          f"amplitude {m['subsync_amplitude_ratio']:.3g} c")
    check(m["motion_class"] == "unstable" and "not decaying" in m["reasons"][0], f"steady 8 um whirl: {m['reasons']}")
    check(abs(m["subsync_growth_per_rev"]) < 0.001, f"steady whirl's growth {m['subsync_growth_per_rev']}")
    check(whirl_with_subsync(0.0, 3e-6)["motion_class"] == "stable", "a steady whirl of 0.03 c not stable")
    check(cm.classify_metrics(m, {"whirl_sustained_amplitude": 0.2})[0] == "stable",
          "a steady whirl of 0.08 c with whirl_sustained_amplitude 0.2: not stable")
    m = classify(*circular_whirl())  # 10 cage revolutions: fewer than 3 segments of 4, no growth measured
    check(math.isnan(m["subsync_growth_per_rev"]) and m["motion_class"] == "circling", f"short window: {m}")
    # A wandering centre (a ball-guided cage's): in each quarter of the window a line of another
    # frequency and direction (+0.75, -0.5, +0.25, -0.75 of the cage speed, as the 6205's), 2 to 5 um:
    # its strongest line grows from segment to segment but is no one whirl: not unstable by it.
    # The same amplitudes at one frequency (+0.5) are.
    for ratios, wanted in (((0.75, -0.5, 0.25, -0.75), "stable"), ((0.5,) * 4, "unstable")):
        quarter = np.minimum((4 * (TG - TG[0]) / (TG[-1] - TG[0] + 1e-12)).astype(int), 3)
        amplitude = np.array([2e-6, 3e-6, 4e-6, 5e-6])[quarter]
        ratio = np.array(ratios)[quarter]
        z = 1e-6 * np.exp(1j * OMEGA_G * TG) + amplitude * np.exp(1j * ratio * OMEGA_G * TG)
        m = cm.classify(TG, z.real, z.imag, C, OMEGA_G, pockets=9)
        print(f"segments' lines at {ratios}: {m['motion_class']}, coherent {m['subsync_coherent']}, "
              f"growth {m['subsync_growth_per_rev']:.3g}")
        check(m["motion_class"] == wanted and m["subsync_coherent"] == (wanted == "unstable"),
              f"lines at {ratios}: {m['motion_class']} (coherent {m['subsync_coherent']}), not {wanted}")


CASES = {"motion_classes": case_motion_classes, "motion_thresholds": case_motion_thresholds,
         "motion_growth": case_motion_growth}
CASES[CASE]()
sys.exit(1 if failures else 0)
