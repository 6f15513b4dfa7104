#!/usr/bin/env python3
"""The power balance with the thermal network on: drive work = losses + change of the stored
mechanical energy (/power_balance, integrated over the solver's steps), and the losses = the heat
the network took in (its stored heat's change, sum C_k dT_k from the integrated temperatures, plus
the heat it gave to the shaft and the air, the trapezoid of the sampled /thermal/link_flow), over
the whole run and over its second half, on a ball and a roller scene.

    /usr/bin/python3 perf/studies/thermal_power_balance.py [--raceway build/raceway] \
        > perf/studies/results/thermal_power_balance.md

The network's heat is each segment's power_loss; the supports' and nodes' dampers are outside the
bearing and not in it (docs/lubrication.md, "Thermal network"), so the comparison is with the losses
less those two columns (which are zero in both scenes here: the table says so).
"""
import argparse
import os
import subprocess
import sys

import h5py
import numpy as np

CASES = (
    ("6205_first_scene (ball, 3000 r/min, 375 N), 10 revolutions", "jobs/scenes/6205_first_scene.toml",
     ["scene.end_time=200 ms", "scene.output_interval=0.5 ms"]),
    ("seed002_100hz (planar roller, 100 Hz, 1 kN), 20 revolutions", "jobs/scenes/seed002_100hz.toml",
     ["scene.output_interval=0.5 ms"]),
)


def balance(path, i, j):
    with h5py.File(path, "r") as f:
        t = f["time"][:]
        w_in = f["power_balance/input_work"][:]
        w_loss = f["power_balance/loss_work"][:]
        loss_names = [str(c) for c in f["power_balance/loss_work"].attrs["components"]]
        stored = f["power_balance/stored_energy"][:]
        temp = f["thermal/temperature"][:]
        cap = f["thermal"].attrs["heat_capacity"]
        flow = f["thermal/link_flow"][:]
        links = [str(c) for c in f["thermal/link_flow"].attrs["components"]]
    out_cols = [links.index("inner_ring-shaft"), links.index("housing-ambient")]
    q_out = flow[:, out_cols].sum(axis=1)
    s = slice(i, j + 1)
    to_ambient = float(np.sum(0.5 * (q_out[s][1:] + q_out[s][:-1]) * np.diff(t[s])))
    stored_heat = float(np.dot(cap, temp[j] - temp[i]))
    d_in = w_in[j] - w_in[i]
    d_loss = w_loss[j] - w_loss[i]
    outside = sum(d_loss[loss_names.index(n)] for n in ("supports", "nodes") if n in loss_names)
    bearing_loss = d_loss.sum() - outside
    heat = stored_heat + to_ambient
    return dict(window=(t[i], t[j]), inputs=d_in.sum(), drive=d_in[0], losses=d_loss.sum(), outside=outside,
                stored_change=stored[j] - stored[i], heat=heat, stored_heat=stored_heat, to_ambient=to_ambient,
                drive_vs_losses=(d_in.sum() - d_loss.sum()) / d_loss.sum(), mech_residual=(d_in.sum() - d_loss.sum() - (stored[j] - stored[i])) / d_in.sum(),
                heat_residual=(bearing_loss - heat) / bearing_loss)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--raceway", default="build/raceway")
    ap.add_argument("--out", default="/tmp/thermal_power_balance")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    print("| scene, window | inputs J (drive J) | losses J (supports, nodes J) | stored mech. change J | "
          "(inputs - losses - change) / inputs | heat into network J (stored heat + to shaft and air) | "
          "(bearing losses - heat) / losses | (inputs - losses) / losses |")
    print("|---|---|---|---|---|---|---|---|")
    for name, scene, sets in CASES:
        path = os.path.join(a.out, os.path.basename(scene).replace(".toml", ".h5"))
        args = [a.raceway, "run", scene, "-o", path, "--output-thread", "off",
                "--set", "thermal.ambient_temperature=293.15 K", "--set", "output.segments=false"]
        for s_ in sets:
            args += ["--set", s_]
        subprocess.run(args, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        with h5py.File(path, "r") as f:
            rows = len(f["time"])
        for label, i in (("whole run", 0), ("second half", (rows - 1) // 2)):
            b = balance(path, i, rows - 1)
            print(f"| {name}, {label} {1e3 * b['window'][0]:.1f}-{1e3 * b['window'][1]:.1f} ms | "
                  f"{b['inputs']:.6g} ({b['drive']:.6g}) | {b['losses']:.6g} ({b['outside']:.3g}) | "
                  f"{b['stored_change']:.3g} | {b['mech_residual']:.2e} | {b['heat']:.6g} "
                  f"({b['stored_heat']:.6g} + {b['to_ambient']:.3g}) | {b['heat_residual']:.2e} | "
                  f"{b['drive_vs_losses']:.2e} |", flush=True)


if __name__ == "__main__":
    sys.exit(main())
