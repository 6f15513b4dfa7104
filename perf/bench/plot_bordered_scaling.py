"""Fits and plots perf/bench/results/bordered_scaling.csv (bench_bordered): time against N for the Jacobian,
setup + solve and solve of each backend, with power-law exponents fitted by least squares in log-log
over N = 8..512 and over N = 64..512 (the asymptotic part, past fixed per-call costs).
Usage: /usr/bin/python3 perf/bench/plot_bordered_scaling.py IN.csv OUT.png"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

rows = list(csv.DictReader(open(sys.argv[1])))
synthetic = [r for r in rows if r["scene"] == "synthetic"]
backends = ["petsc-bordered", "block-elimination", "sundials-dense"]
colors = {"petsc-bordered": "C0", "block-elimination": "C2", "sundials-dense": "C3"}


def series(backend, key):
    pts = sorted((int(r["N"]), float(r[key])) for r in synthetic if r["backend"] == backend)
    return np.array([p[0] for p in pts]), np.array([p[1] for p in pts])


def exponent(n, t, lo=8):
    m = n >= lo
    if m.sum() < 2:
        return float("nan")
    return np.polyfit(np.log(n[m]), np.log(t[m]), 1)[0]


print("# times: minimum over repetitions, seconds; exponents: least-squares slope in log-log")
print(f"{'quantity':42s} {'exp 8-512':>9s} {'exp 64-512':>10s}  times at N = 8, 16, 32, 64, 128, 256, 512")
fig, axes = plt.subplots(1, 3, figsize=(15, 4.8))
n, t = series("petsc-bordered", "jacobian_min_s")
print(f"{'jacobian evaluation':42s} {exponent(n, t):9.2f} {exponent(n, t, 64):10.2f}  " + ", ".join(f"{v:.3g}" for v in t))
axes[0].loglog(n, t, "o-", color="k", label=f"Jacobian (exp {exponent(n, t):.2f})")
setup_solve = {}
for b in backends:
    n, t = series(b, "setup_solve_min_s")
    if len(n) == 0:
        continue
    setup_solve[b] = dict(zip(n, t))
    print(f"{b + ' setup + solve':42s} {exponent(n, t):9.2f} {exponent(n, t, 64):10.2f}  " + ", ".join(f"{v:.3g}" for v in t))
    axes[1].loglog(n, t, "o-", color=colors[b], label=f"{b} (exp {exponent(n, t):.2f} / {exponent(n, t, 64):.2f})")
    n2, t2 = series(b, "solve_min_s")
    print(f"{b + ' solve':42s} {exponent(n2, t2):9.2f} {exponent(n2, t2, 64):10.2f}  " + ", ".join(f"{v:.3g}" for v in t2))
    axes[2].loglog(n2, t2, "o-", color=colors[b], label=f"{b} (exp {exponent(n2, t2):.2f} / {exponent(n2, t2, 64):.2f})")
for N in (8, 16, 256, 512):
    p = setup_solve.get("petsc-bordered", {}).get(N)
    e = setup_solve.get("block-elimination", {}).get(N)
    d = setup_solve.get("sundials-dense", {}).get(N)
    parts = []
    if p and d:
        parts.append(f"dense / petsc {d / p:.0f}x")
    if p and e:
        parts.append(f"petsc / block-elimination {p / e:.2f}x")
    print(f"N = {N}: setup + solve " + ", ".join(parts))
print("# real bearings (setup + solve, s): petsc / block-elimination / dense")
for scene in sorted({r["scene"] for r in rows if r["scene"] != "synthetic"}):
    t = {r["backend"]: float(r["setup_solve_min_s"]) for r in rows if r["scene"] == scene}
    N = [r["N"] for r in rows if r["scene"] == scene][0]
    print(f"{scene} (N = {N}): {t.get('petsc-bordered', 0):.3g} / {t.get('block-elimination', 0):.3g} / "
          f"{t.get('sundials-dense', 0):.3g}; petsc / block-elimination {t['petsc-bordered'] / t['block-elimination']:.2f}x")
titles = ["Jacobian evaluation", "assembly + factorisation + one solve", "one solve"]
for ax, title in zip(axes, titles):
    ax.set_title(title)
    ax.set_xlabel("balls N")
    ax.set_ylabel("s")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
fig.suptitle("Newton linear algebra of a synthetic ball bearing (6309 balls, 9 states each), exponents 8-512 / 64-512")
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=110)
print(f"plot written to {sys.argv[2]}")
