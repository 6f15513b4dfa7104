#!/usr/bin/env python3
"""Friction torque of a catalogue deep groove ball bearing from raceway's runs, against the SKF
four-component model (M = M_rr + M_sl + M_seal + M_drag) with its inlet shear heating and kinematic
replenishment reduction factors.

    /usr/bin/python3 perf/studies/friction_torque.py [--raceway build/raceway] [--out DIR] \
        [--bearing 6205|6309] > perf/studies/results/friction_torque[_6309].md

raceway's torque: the drive term of the power balance (/power_balance/input_work, column `drive`,
integrated over the solver's steps) over a window after settling, divided by the inner ring's
prescribed angular speed and the window's length: M = dW_drive / (omega dt). The inner ring turns at
a prescribed speed, so the drive's power is exactly M omega; being integrated at every step, it
misses no pocket impact (a sampled moment would). The window is the second half of the run.

The SKF model is coded here from memory of SKF's published model (General Catalogue 6000 EN, 2008,
"The SKF model for calculating the frictional moment"); every formula and coefficient is quoted in
docs/validation_ball_bearings.md, "Friction torque", to be checked against the current catalogue.
"""
import argparse
import json
import math
import os
import subprocess
import sys

import h5py
import numpy as np

# SKF geometry constants for deep groove ball bearings (table "Geometry constants for rolling and
# sliding frictional moments"), quoted from memory: series -> (R1, R2, S1, S2).
SKF_CONSTANTS = {"62": (3.9e-7, 1.7, 3.23e-3, 36.5), "63": (3.7e-7, 1.7, 2.84e-3, 92.8)}
MU_BL = 0.15        # boundary sliding friction coefficient (additive package), SKF's "generally 0.15"
MU_EHL = 0.05       # full-film sliding friction coefficient, mineral oil, "other bearings"
K_RS = 3e-8         # replenishment/starvation constant: low oil level bath and oil jet
K_Z = 3.1           # bearing type constant of deep groove ball bearings
# The catalogue's bearings: bore d, outside diameter D [mm], series, radial loads [N].
BEARINGS = {"6205": (25.0, 52.0, "62", (375.0, 1000.0, 2500.0)),
            "6309": (45.0, 100.0, "63", (1000.0, 3000.0, 8000.0))}


def skf_moment(series, d, D, n_rpm, nu_mm2s, fr_n):
    """SKF frictional moment [N mm] of an open deep groove ball bearing under a radial load, no
    drag (no oil bath) and no seal: returns (M, M_rr, M_sl, phi_ish, phi_rs, mu_sl)."""
    r1, _r2, s1, _s2 = SKF_CONSTANTS[series]
    dm = 0.5 * (d + D)
    g_rr = r1 * dm ** 1.96 * fr_n ** 0.54
    g_sl = s1 * dm ** -0.26 * fr_n ** (5.0 / 3.0)
    phi_ish = 1.0 / (1.0 + 1.84e-9 * (n_rpm * dm) ** 1.28 * nu_mm2s ** 0.64)
    phi_rs = math.exp(-K_RS * nu_mm2s * n_rpm * (d + D) * math.sqrt(K_Z / (2.0 * (D - d))))
    phi_bl = math.exp(-2.6e-8 * (n_rpm * nu_mm2s) ** 1.4 * dm)
    mu_sl = phi_bl * MU_BL + (1.0 - phi_bl) * MU_EHL
    m_rr = phi_ish * phi_rs * g_rr * (nu_mm2s * n_rpm) ** 0.6
    m_sl = g_sl * mu_sl
    return m_rr + m_sl, m_rr, m_sl, phi_ish, phi_rs, mu_sl


def run_case(raceway, scene, sets, path):
    args = [raceway, "run", scene, "-o", path, "--summary-json", path + ".json", "--output-thread", "off"]
    for s in sets:
        args += ["--set", s]
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(path + ".json") as f:
        return json.load(f)


def window_measure(path, omega):
    """Drive torque [N mm], losses per kind [W] and the balance's residual over the second half."""
    with h5py.File(path, "r") as f:
        t = f["time"][:]
        w_in = f["power_balance/input_work"][:]
        w_loss = f["power_balance/loss_work"][:]
        stored = f["power_balance/stored_energy"][:]
        in_names = [str(c) for c in f["power_balance/input_work"].attrs["components"]]
        loss_names = [str(c) for c in f["power_balance/loss_work"].attrs["components"]]
    i = int(np.searchsorted(t, 0.5 * t[-1]))
    dt = t[-1] - t[i]
    d_in = w_in[-1] - w_in[i]
    d_loss = w_loss[-1] - w_loss[i]
    drive = d_in[in_names.index("drive")]
    residual = d_in.sum() - d_loss.sum() - (stored[-1] - stored[i])
    losses = {n: float(v) / dt for n, v in zip(loss_names, d_loss)}
    return 1e3 * drive / (omega * dt), losses, residual / d_in.sum(), (t[i], t[-1])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--raceway", default="build/raceway")
    ap.add_argument("--out", default="/tmp/friction_torque")
    ap.add_argument("--revolutions", type=float, default=6.0)
    ap.add_argument("--bearing", choices=sorted(BEARINGS), default="6205")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    scene = "jobs/scenes/6205_first_scene.toml"   # the 6309: the same scene with its designation
    d, D, series, loads = BEARINGS[a.bearing]
    base = [] if a.bearing == "6205" else [f'bearing.designation="{a.bearing}"']
    eta, rho = 0.03, 870.0          # the first scene's oil [Pa s]; the catalogue's density [kg/m^3]
    nu = 1e6 * eta / rho            # mm^2/s
    speeds = (1000.0, 3000.0, 6000.0)
    variants = (("tanh", ["contact.ball_race.traction=tanh"]),
                ("limiting_shear", ["contact.ball_race.traction=limiting_shear"]),
                ("tanh, no RR", ["contact.ball_race.traction=tanh", "contact.ball_race.rolling_resistance=false"]))
    print(f"# Friction torque, {a.bearing} (catalogue), raceway against the SKF model\n")
    print(f"nu = {nu:.2f} mm^2/s (0.03 Pa s / 870 kg/m^3); window: second half of {a.revolutions:g} "
          "inner-ring revolutions; raceway's M = drive work / (omega x window)\n")
    print("| n [r/min] | Fr [N] | ball-race law (RR: EHL rolling resistance) | raceway M [N mm] | "
          "SKF M [N mm] (M_rr + M_sl) | ratio | "
          "inner groove W | outer groove W | pockets W | balance residual | steps | wall s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    rows = []
    for n in speeds:
        for fr in loads:
            m, m_rr, m_sl, phi_ish, phi_rs, mu_sl = skf_moment(series, d, D, n, nu, fr)
            omega = 2.0 * math.pi * n / 60.0
            end = a.revolutions * 60.0 / n
            for k, (tr, variant) in enumerate(variants):
                path = os.path.join(a.out, f"{a.bearing}_{int(n)}_{int(fr)}_{k}.h5")
                sets = [f"inner_ring.speed={n:g} rpm", f"inner_ring.load.fy=-{fr:g} N",
                        f"scene.end_time={end * 1e3:.6g} ms", f"scene.output_interval={end * 1e3 / 300:.6g} ms",
                        "output.segments=false"] + base + variant
                summary = run_case(a.raceway, scene, sets, path)
                m_sim, losses, resid, win = window_measure(path, omega)
                print(f"| {n:g} | {fr:g} | {tr} | {m_sim:.3f} | {m:.2f} ({m_rr:.2f} + {m_sl:.2f}) | "
                      f"{m_sim / m:.3f} | {losses.get('ball_inner_groove', 0):.3f} | "
                      f"{losses.get('ball_outer_groove', 0):.3f} | {losses.get('ball_pocket', 0):.3f} | "
                      f"{resid:.1e} | {summary['steps']} | {summary['wall_time_s']:.2f} |", flush=True)
                rows.append(dict(n=n, fr=fr, traction=tr, m_raceway=m_sim, m_skf=m, m_rr=m_rr, m_sl=m_sl,
                                 phi_ish=phi_ish, phi_rs=phi_rs, mu_sl=mu_sl, losses=losses, residual=resid,
                                 window_s=win, steps=summary["steps"], wall_s=summary["wall_time_s"]))
    print("\nSKF factors per speed: " + "; ".join(
        f"{r['n']:g} r/min: phi_ish {r['phi_ish']:.3f}, phi_rs {r['phi_rs']:.3f}, mu_sl {r['mu_sl']:.3f}"
        for r in rows if r["fr"] == loads[0] and r["traction"] == variants[0][0]))
    with open(os.path.join(a.out, f"friction_torque_{a.bearing}.json"), "w") as f:
        json.dump(rows, f, indent=1)


if __name__ == "__main__":
    sys.exit(main())
