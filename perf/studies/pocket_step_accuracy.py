#!/usr/bin/env python3
"""The step-resolved pocket statistics (/cage/pocket_step_*) against the ones `raceway report` finds
in the output samples, over the report's window (the second half of the run): contact events,
peak bar force, impulse and contact time per bar (front: ahead in the cage's sense of rotation),
summed (peak: the largest) over the pockets. Samples: events are runs of samples above the
threshold (the report's default, 1 % of the peak, and 0); steps: onsets from zero force.

    /usr/bin/python3 perf/studies/pocket_step_accuracy.py RUN.h5 [RUN.h5 ...] > TABLE.tsv

perf/studies/results/pocket_step_accuracy.tsv holds its output for 6309 R3 and QJ215 (runs of
perf/studies/output_sampling_accuracy.sh's kind: one rank, --output-thread off, [solver] initial_step = "1 us";
the file column renamed to the scene).
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "io", "report"))
import report_data  # noqa: E402
import report_metrics as rm  # noqa: E402


def totals(per_pocket):
    return (sum(p["events"] for p in per_pocket), max(p["peak_n"] for p in per_pocket),
            sum(p["impulse_n_s"] for p in per_pocket), sum(p["contact_time_s"] for p in per_pocket))


print("file\toutput_interval_us\tsource\tthreshold_n\tfront_events\trear_events\tfront_peak_n\trear_peak_n\t"
      "front_impulse_n_s\trear_impulse_n_s\tfront_contact_time_ms\trear_contact_time_ms")
for path in sys.argv[1:]:
    run = report_data.read_run(path)
    w = rm.select_window(run.time)
    interval = 1e6 * float(run.time[1] - run.time[0])
    rows = []
    default = rm.default_contact_threshold(run.bar_front, run.bar_rear, w)
    for threshold in (default, 0.0):
        rows.append(("samples", threshold, [[rm.contact_stats(run.time, f[:, k], w, threshold)
                                             for k in range(run.elements)] for f in (run.bar_front, run.bar_rear)]))
    if run.pocket_steps is not None:
        rows.append(("steps", 0.0, [[rm.step_contact_stats(run.pocket_steps[bar], k, w) for k in range(run.elements)]
                                    for bar in ("front", "rear")]))
    for source, threshold, (front, rear) in rows:
        f, r = totals(front), totals(rear)
        print("\t".join([os.path.basename(path), f"{interval:g}", source, f"{threshold:.3g}", str(f[0]), str(r[0]),
                         f"{f[1]:.3f}", f"{r[1]:.3f}", f"{f[2]:.6f}", f"{r[2]:.6f}", f"{1e3 * f[3]:.4f}",
                         f"{1e3 * r[3]:.4f}"]))
