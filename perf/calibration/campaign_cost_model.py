#!/usr/bin/python3
"""The cost model of `raceway campaign` (solver/driver/campaign_plan.cpp) against measured campaigns.

    perf/calibration/campaign_cost_model.py [--binary build/raceway] [--tables DIR] [--table data/campaign_cost_model.csv] \
        > perf/calibration/results/campaign_cost_model.txt

DIR holds <campaign>/campaign_table.csv of the three QJ215 campaigns as run (default docs/campaigns).

1. Fits the two power laws of the model to the QJ215 speed sweep as run (docs/campaigns/qj215_speed/
   campaign_table.csv: 8 scenes, 1000..8000 r/min, 20 revolutions, one rank each):
     steps per revolution = a (n / 1000 r/min)^b        wall per step = c (n / 1000 r/min)^d
   (least squares in logarithms). With --table it writes them, rounded to three digits, as the
   cost model `raceway campaign` reads (data/campaign_cost_model.csv, shipped in share/raceway/data).
2. Asks `raceway campaign check` for its predictions of every scene of the three QJ215 campaigns
   and compares them with the steps and wall times the campaigns recorded (docs/campaigns/*/):
   the error of each scene, the mean absolute error, and how well the predicted order (the
   dispatcher's, longest first) matches the measured one (Spearman's rank correlation).
"""
import argparse
import csv
import os
import re
import subprocess

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CAMPAIGNS = ["qj215_speed", "qj215_axial", "qj215_radial"]


def measured(tables, name):
    with open(os.path.join(tables, name, "campaign_table.csv"), encoding="utf-8") as f:
        return {r["scene"]: r for r in csv.DictReader(f)}


def predicted(binary, name):
    """{scene: (predicted steps, predicted wall s, speed r/min)} from `raceway campaign check`."""
    text = subprocess.run([binary, "campaign", "check", os.path.join(ROOT, "jobs", "campaigns", name + ".toml")],
                          check=True, capture_output=True, text=True).stdout
    out = {}
    for m in re.finditer(r"^\s+(s\d+)\s.*predicted (\d+) steps, ([\d.]+) s", text, re.M):
        out[m.group(1)] = (float(m.group(2)), float(m.group(3)))
    return out


def ranks(x):
    return np.argsort(np.argsort(np.asarray(x)))


def spearman(a, b):
    if len(a) < 2 or np.all(np.asarray(a) == a[0]):
        return float("nan")
    return float(np.corrcoef(ranks(a), ranks(b))[0, 1])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "raceway"))
    ap.add_argument("--tables", default=os.path.join(ROOT, "docs", "campaigns"))
    ap.add_argument("--table", help="write the fitted constants here (the shipped model: data/campaign_cost_model.csv)")
    args = ap.parse_args()
    speed = measured(args.tables, "qj215_speed")
    rpm = np.array([float(r["speed"].split()[0]) for r in speed.values()])
    steps = np.array([float(r["steps"]) for r in speed.values()])
    wall = np.array([float(r["wall_time_s"]) for r in speed.values()])
    b, log_a = np.polyfit(np.log(rpm / 1000), np.log(steps / 20), 1)
    d, log_c = np.polyfit(np.log(rpm / 1000), np.log(wall / steps), 1)
    print(f"# fit to {args.tables}/qj215_speed (20 revolutions, 1000..8000 r/min, 15 balls, one rank):")
    print(f"steps per revolution = {np.exp(log_a):.4g} (n / 1000 r/min)^{b:.3f}")
    print(f"wall per step        = {np.exp(log_c):.4g} s (n / 1000 r/min)^{d:.3f}")
    if args.table:
        with open(args.table, "w", encoding="utf-8") as f:
            f.write(f"# The campaign cost model (solver/driver/campaign_plan.hpp), read by `raceway campaign`: the fit of\n"
                    f"# perf/calibration/campaign_cost_model.py to {os.path.relpath(args.tables, ROOT)}/qj215_speed, "
                    f"rounded to three digits.\n")
            f.write("reference_rpm,reference_rolling_elements,steps_per_revolution,steps_per_revolution_exponent,"
                    "wall_per_step_s,wall_per_step_exponent\n")
            f.write(f"1000,15,{np.exp(log_a):.3g},{b:.3f},{np.exp(log_c):.3g},{d:.3f}\n")
    print()
    print("campaign      scene  speed  steps: predicted measured error   wall: predicted measured error")
    all_steps, all_wall = [], []
    for name in CAMPAIGNS:
        got, pred = measured(args.tables, name), predicted(args.binary, name)
        ps, ms, pw, mw = [], [], [], []
        for sid, row in got.items():
            p_steps, p_wall = pred[sid]
            m_steps, m_wall = float(row["steps"]), float(row["wall_time_s"])
            ps.append(p_steps), ms.append(m_steps), pw.append(p_wall), mw.append(m_wall)
            axis = list(row)[1]
            print(f"{name:13s} {sid}  {row[axis]:>9s}  {p_steps:9.0f} {m_steps:9.0f} {100 * (p_steps / m_steps - 1):+6.0f} %"
                  f"   {p_wall:8.1f} {m_wall:8.1f} {100 * (p_wall / m_wall - 1):+6.0f} %")
        e_steps = np.abs(np.array(ps) / np.array(ms) - 1)
        e_wall = np.abs(np.array(pw) / np.array(mw) - 1)
        all_steps += list(e_steps)
        all_wall += list(e_wall)
        print(f"{name}: mean |error| steps {100 * e_steps.mean():.0f} % (largest {100 * e_steps.max():.0f} %), "
              f"wall {100 * e_wall.mean():.0f} % (largest {100 * e_wall.max():.0f} %); rank correlation of the "
              f"predicted and measured wall (the dispatch order) {spearman(pw, mw):.2f}, of the steps "
              f"{spearman(ps, ms):.2f}")
    print(f"all {len(all_steps)} scenes: mean |error| steps {100 * np.mean(all_steps):.0f} %, "
          f"wall {100 * np.mean(all_wall):.0f} %")


if __name__ == "__main__":
    main()
