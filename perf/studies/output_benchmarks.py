#!/usr/bin/python3
"""The output's cost and size, and what CVODE's restarts at periodic checkpoints cost, recorded in
perf/studies/results/ (perf/studies/run_output_benchmarks.sh runs it).

    output_benchmarks.py RACEWAY SCENES_DIR OUT_DIR [BASELINE_RACEWAY]

1. Output overhead at the scenes' default sampling: each scene run serially (best wall of 3);
   output_time_s / wall_time_s of the run summary (the diagnostics at output times, writing,
   flushes), of which output_write_time_s is everything but the right-hand sides at output times
   (sampling, appending, filtering, flushes, the commit: what the writer costs); the file's size
   and the compression ratio (raw bytes of the time series, 8 per value, over the file's bytes);
   rank 0's serial time as perf/calibration/replay_model.py counts it (wall time less task seconds) and the
   writer's part of it. With BASELINE_RACEWAY (a build of the previous writer) the same for it; its
   summary has no output_write_time_s, so for both the writer's part is also estimated as
   output_time_s - output samples x time_per_rhs_s ("est.").
2. Checkpoint cost: 6309 R3 and seed 002 at 40 Hz with a periodic checkpoint every 50, 100, 200
   and 500 output samples and none: steps, right-hand sides, Jacobians, wall time, the steps per
   restart, and the wall time per checkpoint split into writing (the flush with its fsync and the
   checkpoint file: output_write_time_s over the run without) and the rest (CVODE's restart).
"""
import json
import os
import re
import subprocess
import sys
import tempfile

import h5py

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
        subprocess.run([binary, "run", scene, "--output-thread", "off", "-o", out, "--summary-json", summary], check=True,
                       capture_output=True)
        s = json.load(open(summary))
        s["file_bytes"] = os.path.getsize(out)
        s["raw_series_bytes"] = raw_series_bytes(out)
        if best is None or s["wall_time_s"] < best["wall_time_s"]:
            best = s
    return best


def with_checkpoints(text, interval):
    line = f'checkpoint_interval = "{interval}"'
    if re.search(r"(?m)^\[output\]", text):
        return re.sub(r"(?m)^\[output\]", "[output]\n" + line, text, count=1)
    return text + "\n[output]\n" + line + "\n"


def raw_series_bytes(path):
    """Bytes of the file's time series (chunked datasets) as doubles, uncompressed."""
    total = 0
    with h5py.File(path, "r") as f:
        def visit(_, obj):
            nonlocal total
            if isinstance(obj, h5py.Dataset) and obj.chunks is not None:
                total += obj.size * obj.dtype.itemsize
        f.visititems(visit)
    return total


def serial_seconds(s):
    """Rank 0's serial time as perf/calibration/replay_model.py counts it: wall time less the task seconds."""
    tasks = (s["rhs_evaluations"] * s["time_per_rhs_s"] + s["jacobian_evaluations"] * s["time_per_jacobian_s"])
    return s["wall_time_s"] - tasks


def writer_estimate(s):
    return s["output_time_s"] - s["output_samples"] * s["time_per_rhs_s"]


def overhead_row(name, s, label):
    wall, serial = s["wall_time_s"], serial_seconds(s)
    write = s.get("output_write_time_s")
    measured = f"{write:.3f} ({100 * write / wall:.1f} %)" if write is not None else "-"
    est = writer_estimate(s)
    return (f"| {name} | {label} | {s['output_samples']} | {s['steps']} | {wall:.3f} | {s['output_time_s']:.3f} "
            f"({100 * s['output_time_s'] / wall:.1f} %) | {measured} | {est:.3f} | {s['file_bytes'] / 1e6:.2f} | "
            f"{s['raw_series_bytes'] / s['file_bytes']:.2f} | {serial:.3f} ({100 * serial / wall:.0f} %) | "
            f"{100 * est / serial:.0f} % |")


def overhead(work):
    lines = ["| scene | writer | samples | steps | wall s | output s (share) | writer s (share) | writer s est. | "
             "file MB | ratio | rank 0 serial s (share) | writer part of serial (est.) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for name in SCENES:
        text = open(os.path.join(scenes, name + ".toml"), encoding="utf-8").read()
        if baseline:
            lines.append(overhead_row(name, run(baseline, text, work, name + "_baseline"), "before"))
        lines.append(overhead_row(name, run(raceway, text, work, name), "this" if baseline else ""))
    return lines


def checkpoint_cost(work):
    lines = ["| scene | checkpoint every | restarts | steps | rhs | jacobians | wall s | extra steps per restart | "
             "wall ms per checkpoint: writing + rest |",
             "|---|---|---|---|---|---|---|---|---|"]
    for name in ["6309_R3", "seed002_40hz"]:
        text = open(os.path.join(scenes, name + ".toml"), encoding="utf-8").read()
        dt = re.search(r'(?m)^output_interval = "([0-9.]+) (us|ms)"', text)
        step = float(dt.group(1)) * (1e-6 if dt.group(2) == "us" else 1e-3)
        none = run(raceway, text, work, name + "_none")
        samples = none["output_samples"] - 1
        lines.append(f"| {name} | none | 0 | {none['steps']} | {none['rhs_evaluations']} | "
                     f"{none['jacobian_evaluations']} | {none['wall_time_s']:.3f} | | |")
        for every in [500, 200, 100, 50]:
            s = run(raceway, with_checkpoints(text, f"{every * step * 1e3:.6g} ms"), work, f"{name}_{every}")
            restarts = (samples - 1) // every
            extra = (s["steps"] - none["steps"]) / restarts if restarts else 0
            writing = (s["output_write_time_s"] - none["output_write_time_s"]) / restarts if restarts else 0
            rest = (s["wall_time_s"] - none["wall_time_s"]) / restarts - writing if restarts else 0
            lines.append(f"| {name} | {every} samples | {restarts} | {s['steps']} | {s['rhs_evaluations']} | "
                         f"{s['jacobian_evaluations']} | {s['wall_time_s']:.3f} | {extra:+.1f} | "
                         f"{1e3 * writing:.1f} + {1e3 * rest:.1f} |")
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
