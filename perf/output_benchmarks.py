#!/usr/bin/python3
"""The output's cost and size, and what CVODE's restarts at periodic checkpoints cost, recorded in
perf/results/ (perf/run_output_benchmarks.sh runs it).

    output_benchmarks.py RACEWAY SCENES_DIR OUT_DIR [BASELINE_RACEWAY]

1. Output overhead at the scenes' default sampling: each scene run serially (best wall of 3);
   output_time_s / wall_time_s of the run summary (the diagnostics at output times, writing,
   flushes), the file's size, and, with BASELINE_RACEWAY (a build of the previous writer: no
   compression, the scheduler log in serial runs), its wall time and file size.
2. Checkpoint cost: 6309 R3 and seed 002 at 40 Hz with a periodic checkpoint every 50, 100, 200
   and 500 output samples and none: steps, right-hand sides, Jacobians, wall time, and the steps
   per restart.
"""
import json
import os
import re
import subprocess
import sys
import tempfile

raceway, scenes, out_dir = sys.argv[1:4]
baseline = sys.argv[4] if len(sys.argv) > 4 else None
SCENES = ["default", "seed002_40hz", "6309_R3", "qj215_validation"]


def run(binary, scene_text, work, name, repeats=3):
    scene = os.path.join(work, name + ".toml")
    with open(scene, "w", encoding="utf-8") as fh:
        fh.write(scene_text)
    best = None
    for _ in range(repeats):
        out, summary = os.path.join(work, name + ".h5"), os.path.join(work, name + ".json")
        subprocess.run([binary, "run", scene, "-o", out, "--summary-json", summary], check=True,
                       capture_output=True)
        s = json.load(open(summary))
        s["file_bytes"] = os.path.getsize(out)
        if best is None or s["wall_time_s"] < best["wall_time_s"]:
            best = s
    return best


def with_checkpoints(text, interval):
    line = f'checkpoint_interval = "{interval}"'
    if re.search(r"(?m)^\[output\]", text):
        return re.sub(r"(?m)^\[output\]", "[output]\n" + line, text, count=1)
    return text + "\n[output]\n" + line + "\n"


def overhead(work):
    lines = ["| scene | samples | steps | wall s | output s | output share | file MB |"
             + (" previous writer: wall s, file MB |" if baseline else ""),
             "|---|---|---|---|---|---|---|" + ("---|" if baseline else "")]
    for name in SCENES:
        text = open(os.path.join(scenes, name + ".toml"), encoding="utf-8").read()
        s = run(raceway, text, work, name)
        row = (f"| {name} | {s['output_samples']} | {s['steps']} | {s['wall_time_s']:.3f} | "
               f"{s['output_time_s']:.3f} | {100 * s['output_time_s'] / s['wall_time_s']:.1f} % | "
               f"{s['file_bytes'] / 1e6:.2f} |")
        if baseline:
            b = run(baseline, text, work, name + "_baseline")
            row += f" {b['wall_time_s']:.3f}, {b['file_bytes'] / 1e6:.2f} |"
        lines.append(row)
    return lines


def checkpoint_cost(work):
    lines = ["| scene | checkpoint every | restarts | steps | rhs | jacobians | wall s | extra steps per restart |",
             "|---|---|---|---|---|---|---|---|"]
    for name in ["6309_R3", "seed002_40hz"]:
        text = open(os.path.join(scenes, name + ".toml"), encoding="utf-8").read()
        dt = re.search(r'(?m)^output_interval = "([0-9.]+) (us|ms)"', text)
        step = float(dt.group(1)) * (1e-6 if dt.group(2) == "us" else 1e-3)
        none = run(raceway, text, work, name + "_none")
        samples = none["output_samples"] - 1
        lines.append(f"| {name} | none | 0 | {none['steps']} | {none['rhs_evaluations']} | "
                     f"{none['jacobian_evaluations']} | {none['wall_time_s']:.3f} | |")
        for every in [500, 200, 100, 50]:
            s = run(raceway, with_checkpoints(text, f"{every * step * 1e3:.6g} ms"), work, f"{name}_{every}")
            restarts = (samples - 1) // every
            extra = (s["steps"] - none["steps"]) / restarts if restarts else 0
            lines.append(f"| {name} | {every} samples | {restarts} | {s['steps']} | {s['rhs_evaluations']} | "
                         f"{s['jacobian_evaluations']} | {s['wall_time_s']:.3f} | {extra:+.1f} |")
    return lines


def main():
    os.makedirs(out_dir, exist_ok=True)
    with tempfile.TemporaryDirectory() as work:
        with open(os.path.join(out_dir, "output_overhead.md"), "w", encoding="utf-8") as fh:
            fh.write("\n".join(overhead(work)) + "\n")
        with open(os.path.join(out_dir, "checkpoint_cost.md"), "w", encoding="utf-8") as fh:
            fh.write("\n".join(checkpoint_cost(work)) + "\n")


if __name__ == "__main__":
    main()
