#!/usr/bin/env python3
"""[output] segment_every (docs/output_layout.md, "Segment diagnostics at a coarser sampling") on short
runs of 6309 R3 (jobs/scenes/6309_R3.toml, output every 20 us), one case per ctest:

    segment_every_test.py CASE RACEWAY MPIEXEC SOURCE_DIR

  rows: 5 ms at segment_every = 1 and 5 (251 samples): /segments/* hold ceil(251 / 5) = 51 rows,
    /segments/time is /time at samples 0, 5, 10, ..., each stored row is bitwise the N = 1 run's
    row at the same sample (the output does not influence the steps), every other dataset outside
    /scheduler is bitwise the N = 1 run's, the attribute sample_stride says 5 (1 in the N = 1 file),
    the segment series' dimension scale is /segments/time, and the file is smaller; the raceway
    package reads it (at the segment rows: the N = 1 values there; a table of both samplings
    refused), `raceway report` reads it at the segment rows and says so, and the ParaView export's
    frames are at segment rows with the N = 1 ball loads.
  pocket_steps: 20 ms at N = 1 and 5: `raceway report` of the N = 5 file takes the step-resolved pocket
    statistics (/cage/pocket_step_*) of every output interval, summed (their largest, for the peak)
    over the intervals between its rows: the same events, peaks, impulses and contact times as the
    N = 1 report over the same window.
  ranks: the N = 5 run at np = 2, and at np = 2 with --parallel-output (the workers write their
    segments' cells at rows of every 5th sample): the np = 1 file's bits (tests/system/parallel/
    compare_outputs.py: every dataset and stored chunk).
  resume: N = 5 with periodic checkpoints every 81 samples (not a multiple of 5), killed (SIGKILL)
    after its first checkpoint and resumed, at np = 1 and at np = 2 with --parallel-output (the
    workers see none of the rows before the checkpoint): the uninterrupted run's bits.
"""
import json
import math
import os
import signal
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

failures = []


def check(cond, what):
    print(f"{'ok' if cond else 'FAIL'}: {what}", file=sys.stderr)
    if not cond:
        failures.append(what)


def command(raceway, scene, out, every, extra=(), np_ranks=1, mpiexec=None, end="5 ms"):
    cmd = [raceway, "run", scene, "-o", out, "--set", f"scene.end_time={end}", "--set",
           f"output.segment_every={every}", *extra]
    if np_ranks > 1:
        cmd = [mpiexec, "--oversubscribe", "-np", str(np_ranks)] + cmd
    return cmd


def run(cmd):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=300, env=env)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)}: exit {r.returncode}: {r.stderr[-800:]}")
    return cmd[cmd.index("-o") + 1]


def datasets(f):
    names = []
    f.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) else None)
    return names


def case_rows(raceway, scene, work):
    one = run(command(raceway, scene, os.path.join(work, "n1.h5"), 1))
    five = run(command(raceway, scene, os.path.join(work, "n5.h5"), 5))
    with h5py.File(one, "r") as a, h5py.File(five, "r") as b:
        samples = len(a["time"])
        rows = math.ceil(samples / 5)
        check(samples == 251, f"the N = 1 run has 251 samples ({samples})")
        check(int(a["segments"].attrs["sample_stride"]) == 1 and int(b["segments"].attrs["sample_stride"]) == 5,
              "sample_stride is 1 and 5")
        check("time" not in a["segments"], "N = 1 writes no /segments/time (the file as before)")
        check(b["segments/time"][()].tobytes() == a["time"][::5].tobytes(), "/segments/time is /time at 0, 5, 10, ...")
        series = [n for n in datasets(b) if n.startswith("segments/") and b[n].ndim == 2]
        check(len(series) > 20, f"{len(series)} segment series")
        wrong_rows = [n for n in series if b[n].shape[0] != rows]
        check(not wrong_rows, f"every segment series has ceil({samples} / 5) = {rows} rows ({wrong_rows[:3]})")
        differ = [n for n in series if b[n][()].tobytes() != a[n][::5].tobytes()]
        check(not differ, f"each stored row is the N = 1 run's row at its sample, bitwise ({differ[:3]})")
        loaded = b["segments/ball_inner_groove/normal_force"][()]
        check(loaded.max() > 100, f"the rows hold the contacts (largest ball load {loaded.max():.1f} N)")
        others = [n for n in datasets(a) if not n.startswith(("segments/", "scheduler/"))]
        differ = [n for n in others if a[n][()].tobytes() != b[n][()].tobytes()]
        check(len(others) > 30 and not differ, f"the {len(others)} other datasets are bitwise the N = 1 run's "
              f"({differ[:3]})")
        scale = b["segments/ball_pocket/normal_force"].dims[0]
        check(len(scale) == 1 and scale[0].name == "/segments/time", "the segment series' scale is /segments/time")
        check(b["cage/position"].dims[0][0].name == "/time", "the bodies' scale stays /time")
    readers(one, five)
    report = os.path.join(work, "report5")
    run([raceway, "report", five, "--no-plots", "-o", report])
    with open(os.path.join(report, "summary.json"), encoding="utf-8") as f:
        notes = json.load(f).get("notes", "")
    notes = notes if isinstance(notes, str) else " ".join(notes)
    check("51 of 251 samples" in notes, f"raceway report reads the file at the segment rows and says so: {notes}")
    size_one, size_five = os.path.getsize(one), os.path.getsize(five)
    print(f"file: {size_one} bytes at N = 1, {size_five} at N = 5", file=sys.stderr)
    check(size_five < 0.85 * size_one, "the N = 5 file is smaller")


def readers(one, five):
    """The raceway package and the ParaView export's bodies on the N = 5 file: the segment rows'
    samples, the N = 1 file's values there."""
    from raceway import RacewayOutput
    from report_bodies import read_bodies
    with RacewayOutput(five) as out:
        check(out.segment_stride == 5 and out.segment_rows == 51 and len(out.segment_time) == 51
              and len(out.time) == 251, "the reader: stride 5, 51 segment rows, 251 samples")
        check("time" not in out.segment_kinds(), "/segments/time is no segment kind")
        try:
            out.table()
            check(False, "a table of every series is refused at two samplings")
        except ValueError as e:
            check("segment_every" in str(e), f"a table of every series is refused: {e}")
    with RacewayOutput(five, at_segment_rows=True) as out, RacewayOutput(one) as full:
        pos = np.asarray(out["cage/position"])
        check(pos.shape[0] == 51 and pos.tobytes() == np.asarray(full["cage/position"])[::5].tobytes()
              and len(out.table().columns) > 100, "read at the segment rows: every series at samples 0, 5, ...")
    bodies, every = read_bodies(five, 20), read_bodies(one, 251)  # the N = 1 file at every sample
    rows = bodies.samples
    check(len(rows) > 5 and all(r % 5 == 0 for r in rows), f"the ParaView frames are at segment rows ({rows[:4]})")
    load = bodies.bodies[0].point_data["inner_race_normal_force_N"]
    ref = every.bodies[0].point_data["inner_race_normal_force_N"][rows]
    check(load.tobytes() == ref.tobytes() and load.max() > 100, "their ball loads are the N = 1 file's")


def compare(source, reference, others):
    tool = os.path.join(source, "tests", "system", "parallel", "compare_outputs.py")
    r = subprocess.run(["/usr/bin/python3", tool, reference, *others], capture_output=True, text=True, timeout=300)
    return r.returncode == 0, (r.stdout + r.stderr)[-600:]


def case_ranks(raceway, mpiexec, scene, source, work):
    one = run(command(raceway, scene, os.path.join(work, "np1.h5"), 5))
    two = run(command(raceway, scene, os.path.join(work, "np2.h5"), 5, (), 2, mpiexec))
    shared = run(command(raceway, scene, os.path.join(work, "np2p.h5"), 5, ("--parallel-output",), 2, mpiexec))
    with h5py.File(shared, "r") as f:
        check(f["segments/ball_pocket/normal_force"].shape[0] == 51, "the parallel output wrote 51 rows")
    ok, text = compare(source, one, [two, shared])
    check(ok, f"np = 2 and np = 2 --parallel-output write the np = 1 file's bits: {'' if ok else text}")


def kill_after_checkpoint(cmd, out):
    """Starts cmd in a session of its own and kills (SIGKILL) every process of it as soon as the
    first checkpoint exists; whether it was killed before its end."""
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env,
                            start_new_session=True)
    deadline = time.time() + 120
    while not os.path.exists(out + ".checkpoint") and proc.poll() is None and time.time() < deadline:
        time.sleep(0.001)
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    code = proc.wait(timeout=120)
    time.sleep(0.2)  # the ranks of a killed mpirun end with it
    return code != 0 and os.path.exists(out + ".checkpoint") and not os.path.exists(out)


def case_resume(raceway, mpiexec, scene, source, work):
    # 81 samples of 20 us; 20 ms, so that a kill after the first checkpoint lands before the end
    # (a 5 ms run of the shipped scene can end within milliseconds of its first checkpoint).
    every = ("--set", "output.checkpoint_interval=1.62 ms", "--set", "scene.end_time=20 ms")
    whole = run(command(raceway, scene, os.path.join(work, "whole.h5"), 5, every))
    out = os.path.join(work, "killed.h5")
    check(kill_after_checkpoint(command(raceway, scene, out, 5, every), out),
          "the run was killed after a checkpoint, before its end")
    run(command(raceway, scene, out, 5, every + ("--resume",)))
    shared = os.path.join(work, "shared.h5")
    parallel = every + ("--parallel-output",)
    check(kill_after_checkpoint(command(raceway, scene, shared, 5, parallel, 2, mpiexec), shared),
          "the np = 2 --parallel-output run was killed after a checkpoint, before its end")
    run(command(raceway, scene, shared, 5, parallel + ("--resume",), 2, mpiexec))
    ok, text = compare(source, whole, [out, shared])
    check(ok, f"killed after a checkpoint and resumed (np = 1, and np = 2 with --parallel-output): the "
              f"uninterrupted run's bits: {'' if ok else text}")


def case_pocket_steps(raceway, scene, work):
    """The report of a file read at the segment rows takes the step-resolved pocket statistics of every
    output interval: 20 ms of 6309 R3 (its first ball-bar impacts), the second half (samples 501-1000,
    rows 101-200 at N = 5: the same intervals) reported at N = 1 and N = 5."""
    from report_data import coarse_intervals
    summaries = {}
    for every in (1, 5):
        out = run(command(raceway, scene, os.path.join(work, f"p{every}.h5"), every, end="20 ms"))
        report = os.path.join(work, f"report{every}")
        run([raceway, "report", out, "--no-plots", "-o", report])
        with open(os.path.join(report, "summary.json"), encoding="utf-8") as f:
            summaries[every] = json.load(f)["pocket_forces"]
    for bar in ("front", "rear"):
        a, b = summaries[1][bar], summaries[5][bar]
        check(a["events"] > 0 and a["events"] == b["events"], f"{bar}: {b['events']} events at N = 5, {a['events']} at 1")
        check(a["peak_n"] == b["peak_n"], f"{bar}: peak {b['peak_n']} N at N = 5, {a['peak_n']} at 1")
        for q in ("impulse_n_s", "contact_time_s"):
            check(abs(a[q] - b[q]) <= 1e-12 * abs(a[q]), f"{bar}: {q} {b[q]} at N = 5, {a[q]} at 1")
    # The intervals' rows against a plain loop over each block of samples.
    with h5py.File(os.path.join(work, "p1.h5"), "r") as f:
        impulse, peak = f["cage/pocket_step_impulse"][()], f["cage/pocket_step_peak_force"][()]
    rows = math.ceil(len(impulse) / 5)
    blocks = [slice(0, 1)] + [slice(5 * j - 4, 5 * j + 1) for j in range(1, rows)]
    check(np.allclose(coarse_intervals(impulse, 5, rows, False), [impulse[s].sum(axis=0) for s in blocks],
                      rtol=1e-12, atol=0) and
          np.array_equal(coarse_intervals(peak, 5, rows, True), [peak[s].max(axis=0) for s in blocks]),
          "the intervals between every 5th sample: sums and largest values")


def main():
    if len(sys.argv) != 5:
        print(__doc__, file=sys.stderr)
        return 2
    case, raceway, mpiexec, source = sys.argv[1:]
    scene = os.path.join(source, "jobs", "scenes", "6309_R3.toml")
    sys.path.insert(0, os.path.join(source, "io", "report"))
    with tempfile.TemporaryDirectory() as work:
        if case == "rows":
            case_rows(raceway, scene, work)
        elif case == "pocket_steps":
            case_pocket_steps(raceway, scene, work)
        elif case == "ranks":
            case_ranks(raceway, mpiexec, scene, source, work)
        else:
            case_resume(raceway, mpiexec, scene, source, work)
    if failures:
        print(f"{case}: FAILED ({len(failures)})", file=sys.stderr)
        return 1
    print(f"{case}: passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
