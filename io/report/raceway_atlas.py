#!/usr/bin/env python3
"""The cage-stability atlas (docs/atlas.md): `raceway atlas FILE -o DIR` runs this script.

    raceway_atlas.py FILE -o DIR [--resume] [--ranks N] [--raceway EXE]
    raceway_atlas.py FILE --check [--raceway EXE]

reads the atlas file (a bad one: exit 2 naming the file, line, key and reason, before any point
runs), checks the base scene at the corners of the parameters' ranges, the realisations and the
convergence rtol with `raceway check`, then runs the adaptive search: batches of `batch_size`
points (default: --ranks), each point a `raceway run` of the base scene with --set overrides,
`--ranks` runs at a time. DIR gets atlas_state.json (resumable), points/, atlas.csv, atlas.json and
atlas.png (and atlas_<a>_<b>.png per pair of parameters when there are more than two). `--standin
NOISE` evaluates the tests' closed-form stand-in instead of the simulator.

A stop signal (SIGINT, SIGTERM, SIGUSR1) starts no new run and is passed on to the running ones,
whose points stay planned; the table and map are written of what is done (exit 4; --resume goes on).

Exit codes: 0 done; 1 a point failed (recorded in the table); 2 bad input (atlas file, scene,
folder); 3 numpy or scikit-learn missing; 4 stopped by a signal.
"""
import argparse
import importlib.util
import itertools
import os
import re
import signal
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

INSTALL = "the atlas needs python3-numpy, python3-h5py, python3-matplotlib and python3-sklearn (docs/atlas.md)"
if importlib.util.find_spec("numpy") is None:
    print(f"[raceway] atlas: no module numpy: {INSTALL}", file=sys.stderr)
    sys.exit(3)

from atlas_file import AtlasFileError, read_atlas_file  # noqa: E402
from atlas_models import STOP, SimulatorModel, StandinModel, set_text, stop_runs, unit_value  # noqa: E402
from atlas_output import write_outputs  # noqa: E402
from atlas_runner import AtlasStateError, run_atlas  # noqa: E402


def log(message):
    print(f"[raceway] atlas: {message}", flush=True)


def checks(atlas):
    """(atlas file key, --set overrides) of every scene checked before the atlas runs."""
    base = {k: set_text(v) for k, v in atlas["set"].items()}
    if atlas["end_time_s"] is not None:  # a window in cage revolutions: the scene's own end time here
        base["scene.end_time"] = f"{atlas['end_time_s']:.10g} s"
    params = atlas["parameters"]
    for corner in itertools.product(*[p["range"] for p in params]):
        sets = dict(base)
        sets.update({p["key"]: unit_value(v, p["unit"]) for p, v in zip(params, corner)})
        yield "corner " + ", ".join(f"{p['name']} {unit_value(v, p['unit'])}" for p, v in zip(params, corner)), sets
    c = atlas["certify"]
    for v in c["threshold_realisations"]:
        yield f"threshold realisation {c['realisation_key']} = {v}", {**base, c["realisation_key"]: v}
    for v in c["realisations"]:
        yield f"realisation {c['realisation_key']} = {v}", {**base, c["realisation_key"]: v}
    yield f"convergence rtol {c['convergence_rtol']:g}", {**base, "solver.rtol": f"{c['convergence_rtol']:g}"}


def file_key_of(atlas, scene_key):
    """The atlas file's key that set `scene_key` (for the error's line)."""
    for i, p in enumerate(atlas["parameters"]):
        if p["key"] == scene_key:
            return f"parameter[{i}].range"
    if scene_key in atlas["set"]:
        return "atlas.set"
    if scene_key == atlas["certify"]["realisation_key"]:
        return "certify.realisations"
    return {"solver.rtol": "certify.convergence_rtol", "scene.end_time": "atlas.end_time"}.get(scene_key, "atlas.scene")


def check_one(atlas, raceway, sets):
    """`raceway check` of the base scene with `sets`: None, or the first error line."""
    args = [raceway, "check", atlas["scene"]]
    for key, value in sets.items():
        args += ["--set", f"{key}={value}"]
    try:
        done = subprocess.run(args, capture_output=True, text=True, check=False)
    except OSError as err:
        return f"cannot run {raceway}: {err.strerror}"
    if done.returncode == 0:
        return None
    text = done.stderr + done.stdout
    lines = [s for s in text.splitlines() if "error" in s] or text.strip().splitlines()[-1:]
    return lines[0].split("error: ", 1)[-1] if lines else f"exit {done.returncode}"


def check_scenes(atlas, raceway, workers):
    """`raceway check` of every scene of checks(), `workers` at a time (at least 8: a check mostly
    waits); AtlasFileError naming the line that set the first bad value (in the order of checks())."""
    todo = list(checks(atlas))
    with ThreadPoolExecutor(max_workers=max(8, workers)) as pool:
        answers = list(pool.map(lambda item: check_one(atlas, raceway, item[1]), todo))
    for (what, _), message in zip(todo, answers):
        if message is None:
            continue
        m = re.search(r"--set ([A-Za-z0-9_.]+)=", message)
        key = file_key_of(atlas, m[1]) if m else "atlas.scene"
        if key == "certify.realisations" and what.startswith("threshold"):
            key = "certify.threshold_realisations"
        raise AtlasFileError(f"{atlas['path']}:{atlas['lines'].of(key)}: key '{key}': the scene at {what} is "
                             f"rejected: {message}")


def pair_maps(atlas):
    """The log's list of the pair maps (more than two parameters: atlas_pairs.py), else nothing."""
    ps = atlas["parameters"]
    if len(ps) <= 2:
        return ""
    return ", " + ", ".join(f"atlas_{a['name']}_{b['name']}.png" for a, b in itertools.combinations(ps, 2))


def parse_args(argv):
    ap = argparse.ArgumentParser(prog="raceway atlas", description="the cage-stability atlas (docs/atlas.md)")
    ap.add_argument("atlas_file")
    ap.add_argument("-o", "--output-dir")
    ap.add_argument("--resume", action="store_true", help="continue the atlas in the folder")
    ap.add_argument("--check", action="store_true", help="check the atlas file and its scenes, run nothing")
    ap.add_argument("--ranks", type=int, default=1, help="points run at a time (and the default batch size)")
    ap.add_argument("--raceway", default=os.environ.get("RACEWAY_EXE", "raceway"), help="the raceway executable")
    ap.add_argument("--standin", type=float, default=None, metavar="NOISE",
                    help="evaluate the closed-form stand-in model instead of the simulator (tests)")
    args = ap.parse_args(argv)
    if not args.check and not args.output_dir:
        ap.error("-o DIR is required (or --check)")
    if args.ranks < 1:
        ap.error("--ranks must be at least 1")
    return args


def main(argv):
    args = parse_args(argv)
    try:
        atlas = read_atlas_file(args.atlas_file)
        if args.standin is None:
            check_scenes(atlas, args.raceway, args.ranks)
    except AtlasFileError as err:
        print(f"[raceway] error: {err}", file=sys.stderr)
        return 2
    # Looked for after the file's checks (a bad file is refused without it), not imported (0.8 s).
    if importlib.util.find_spec("sklearn") is None:
        print(f"[raceway] atlas: no module sklearn (scikit-learn): {INSTALL}", file=sys.stderr)
        return 3
    batch = atlas["batch_size"] or args.ranks
    log(f"{atlas['name']}: {len(atlas['parameters'])} parameters, budget {atlas['budget_points']} points, "
        f"batches of {batch}, {args.ranks} at a time")
    if args.check:
        return 0
    model = StandinModel(atlas, args.standin) if args.standin is not None else \
        SimulatorModel(args.raceway, atlas, args.output_dir)
    for signum in (signal.SIGINT, signal.SIGTERM, signal.SIGUSR1):
        signal.signal(signum, lambda number, _frame: stop_runs(number))
    start = time.monotonic()
    try:
        state = run_atlas(model, atlas, args.output_dir, args.resume, batch, args.ranks, log)
    except AtlasStateError as err:
        print(f"[raceway] error: {err}", file=sys.stderr)
        return 2
    note = write_outputs(atlas, state, args.output_dir)
    if note:
        log(note)
    failed = sum(p["status"] == "failed" for p in state["points"])
    log(f"{len(state['points'])} points ({failed} failed), {state['core_hours']:.3g} core-hours, "
        f"{time.monotonic() - start:.1f} s; {args.output_dir}/atlas.csv, atlas.json, atlas.png{pair_maps(atlas)}")
    if STOP.is_set():
        log("stopped by a signal: the finished points are kept; continue with --resume")
        return 4
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
