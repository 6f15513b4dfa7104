#!/usr/bin/env python3
"""`raceway report OUT.h5`: the report of a planar (roller) or spatial (ball) bearing run.

    raceway_report.py OUT.h5 [-o DIR] [--window-start S] [--bin-width DEG] [--contact-threshold N]
                      [--no-plots] [--animate] [--animation-frames N] [--xdmf] [--vtk]

`raceway report` runs this script (found beside the executable's install prefix); it can be run
directly too. Writes into DIR (default: <stem>_report beside the file):

    summary.json   the metrics (report_summary.py): window means, peaks named as peaks
    *.png          the figures (report_plots.py), 1600 px wide, titled with the scene
    report.html    one self-contained page: figures, numbers, scene text, build (report_page.py)
    cage.mp4/.gif  with --animate: the bearing seen along its axis (report_animation.py)
and beside the .h5, for ParaView, the bodies over time (report_bodies.py: rolling elements with their
radii, cage and rings as polylines): with --xdmf OUT.xdmf and its data OUT_xdmf.h5 (report_xdmf.py),
with --vtk OUT_vtk/OUT.pvd and its VTK PolyData files (report_vtk.py).

Exit codes: 0 done (plots skipped with a warning when matplotlib is missing); 2 bad input (a
missing file or dataset, a bad option), naming the file and dataset; 3 numpy or h5py missing;
1 another failure.
"""
import argparse
import json
import math
import os
import sys
import warnings

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

try:
    import numpy as np  # noqa: F401
    import h5py  # noqa: F401
except ImportError as err:
    print(f"[raceway] error: report: {err}; install python3-numpy and python3-h5py (scripts/bootstrap.sh)",
          file=sys.stderr)
    sys.exit(3)

from report_bodies import ExportInputError, check_exportable  # noqa: E402
from report_data import ReportInputError, read_run  # noqa: E402
from report_summary import summarize  # noqa: E402


def log(level, text):
    print(f"[raceway] {level}: {text}" if level != "info" else f"[raceway] {text}", file=sys.stderr)


def finite_json(value):
    """NaN and infinities as null (docs/output_layout.md, "Run summary")."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {k: finite_json(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [finite_json(v) for v in value]
    if hasattr(value, "item"):
        return finite_json(value.item())
    return value


def write_json(path, obj):
    tmp = path + ".tmp"
    with open(tmp, "w") as fh:
        json.dump(finite_json(obj), fh, indent=2)
        fh.write("\n")
    os.replace(tmp, path)


def parse_args(argv):
    p = argparse.ArgumentParser(prog="raceway report", description=__doc__.split("\n")[0])
    p.add_argument("input")
    p.add_argument("-o", "--output-dir", default="")
    p.add_argument("--window-start", type=float, default=None)
    p.add_argument("--bin-width", type=float, default=5.0)
    p.add_argument("--contact-threshold", type=float, default=None)
    p.add_argument("--no-plots", action="store_true")
    p.add_argument("--animate", action="store_true")
    p.add_argument("--animation-frames", type=int, default=150)
    p.add_argument("--xdmf", action="store_true")
    p.add_argument("--vtk", action="store_true")
    return p.parse_args(argv)


def output_dir(args):
    if args.output_dir:
        return args.output_dir
    stem = os.path.splitext(os.path.basename(args.input))[0]
    if stem.endswith(".h5"):  # an interrupted run's OUT.h5.partial
        stem = stem[:-3]
    return os.path.join(os.path.dirname(args.input), stem + "_report")


def figures(run, summary, folder, args):
    """The plots, the page and the animation; returns the PNG names (empty when matplotlib is missing)."""
    try:
        import matplotlib  # noqa: F401
    except ImportError as err:
        log("warning", f"plots skipped: {err}; install python3-matplotlib (scripts/bootstrap.sh)")
        return []
    import report_plots
    for name in os.listdir(folder):
        if name.endswith(".png"):
            os.remove(os.path.join(folder, name))
    pngs, failures = report_plots.draw_all(run, summary, folder)
    for failure in failures:
        log("warning", f"plot failed: {failure}")
    import report_page
    page = report_page.write_page(run, summary, folder, pngs)
    log("info", f"{len(pngs)} plots and the report page {page} written")
    if args.animate:
        import report_animation
        video = report_animation.animate(run, summary, folder, frames=args.animation_frames)
        log("info", f"animation written to {video}")
    return pngs


def main(argv):
    args = parse_args(argv)
    if not (args.bin_width > 0 and args.bin_width <= 360):
        log("error", f"report: --bin-width {args.bin_width} deg is not in (0, 360]")
        return 2
    try:
        run = read_run(args.input)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)  # means of empty azimuth bins are NaN by design
            summary, lines = summarize(run, args.window_start, args.bin_width, args.contact_threshold)
        if args.xdmf or args.vtk:
            check_exportable(args.input)
    except (ReportInputError, ExportInputError) as err:
        log("error", f"report: {err}")
        return 2
    except ValueError as err:
        log("error", f"report: {args.input}: {err}")
        return 2
    for note in run.notes:
        log("warning", note)
    for line in lines:
        log("info", line)
    folder = output_dir(args)
    os.makedirs(folder, exist_ok=True)
    vibration = vibration_part(args, summary, folder)
    summary_path = os.path.join(folder, "summary.json")
    write_json(summary_path, summary)
    log("info", f"summary written to {summary_path}")
    if args.xdmf:
        import report_xdmf
        xdmf = report_xdmf.write_xdmf(args.input)
        log("info", f"ParaView file written to {xdmf} (its data: {report_xdmf.data_path(xdmf)})")
    if args.vtk:
        import report_vtk
        log("info", f"VTK time series written to {report_vtk.write_vtk(args.input)}")
    if args.no_plots:
        log("info", "plots skipped (--no-plots)" + (", and with them the animation (--animate)" if args.animate else ""))
    else:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            figures(run, summary, folder, args)
            if vibration is not None:
                try:
                    import report_vibration
                    png = report_vibration.plot(vibration, folder)
                    log("info", f"vibration spectra written to {os.path.join(folder, png)}")
                except ImportError as err:
                    log("warning", f"vibration plot skipped: {err}")
    return 0


def vibration_part(args, summary, folder):
    """With a housing: the vibration summary into `summary` (key "vibration"), the sensor's CSV, and
    the analysis for the plot; None without one."""
    import report_vibration
    start = summary.get("window", {}).get("start_s", 0.0) if isinstance(summary.get("window"), dict) else 0.0
    result = report_vibration.analyse(args.input, start or 0.0)
    if result is None:
        return None
    summary["vibration"] = report_vibration.summary_of(result)
    st = result["statistics"]
    carrying = [f"{r['name']} x{r['harmonic']}" for r in result["table"] if r["carries_energy"]]
    log("info", f"housing sensor (y): RMS {st['rms']:.4g} m/s^2, kurtosis {st['kurtosis']:.3g}, crest factor "
                f"{st['crest_factor']:.3g}; slip {100 * result['frequencies']['slip']:.3f} %; lines carrying energy in "
                f"the envelope spectrum: {', '.join(carrying) if carrying else 'none'}")
    log("info", f"sensor signal written to {report_vibration.export(args.input, folder, start or 0.0)}")
    return result


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
