#!/usr/bin/python3
"""Run shipped scenes over a short window and compare them with their committed answer files.

    scene_answers.py [--raceway BIN] [--answers DIR] SCENE.toml [SCENE.toml ...]
        run each scene over the window its answer file names and compare the chosen quantities
        with the file's values, each within its tolerance; exit 0 when every one agrees, 1 with a
        table of the quantities outside their tolerance, 2 on bad use (no answer file, a run that
        failed)
    scene_answers.py --update [--end-time TIME] SCENE.toml [...]
        run the scenes and (re)write their answer files: the values, and the tolerances from three
        more runs of each along other step sequences (NOISE_VARIANTS); the window stays the file's
        own unless --end-time gives one (required for a scene without an answer file)

Options: --set KEY=VALUE (repeatable) adds scene overrides to the run, not to the answer file (the
suite uses it to show that a changed parameter fails); --keep DIR keeps the runs' files there;
--verbose prints every quantity, not only the ones outside their tolerance.

An answer file (tests/system/scenes/answers/<scene>.json) holds the window (the `--set` overrides that
shorten the run: scene.end_time), the build that wrote it, and one line per quantity: its value (a
number or a nested list), class, measured noise and tolerance (rel, abs). A value a agrees with
the answer e when |a - e| <= abs + rel * scale, where scale is |e| for a number and max |e| over
the whole array for an array (positions of elements on a circle have components near zero, whose
own size says nothing about the accuracy). How --update sets the tolerances: NOISE_FACTOR below.
Quantities are read from the summary JSON and from the output by name, trying every spelling a
dataset has had (`/cage/angle` in planar runs and `/cage/angles` in spatial ones), so the check
does not depend on how a series is stored as long as its meaning stays.

Needs numpy and h5py (Debian's python3-numpy, python3-h5py).
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

try:
    import h5py
    import numpy as np
except ImportError as missing:  # the suite skips (77) rather than fails where they are absent
    print(f"scene_answers: skipped: {missing} (apt install python3-h5py python3-numpy)")
    sys.exit(77)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# How a tolerance is set (at --update, per scene and quantity, stored in the answer file): the
# scene is run again along other step sequences, NOISE_VARIANTS: another first step (twice), which
# is what a compiler, a BLAS or a platform that rounds differently brings about once a rounding
# difference flips one step-size decision, and rtol / 10, whose difference is the integration error
# itself (not counted for the counters: a tighter tolerance costs steps). The noise of a quantity
# is the largest difference any of them makes; its tolerance is
# NOISE_FACTOR times that, and at least the floor of its class, FLOORS (for quantities the step
# sequence does not move: they still carry rounding). A physics change of 0.5 % in speed or 5 % in
# load moves the quantities it concerns by 3 to 1000 times more than that (docs/testing.md).
NOISE_FACTOR = 4.0
NOISE_VARIANTS = ("another first step", "another first step (2)", "rtol / 10")
# class: (relative floor, absolute floor in SI, what the class holds)
FLOORS = {
    "counter": (0.02, 2.0, "CVODE steps and evaluations"),
    "exact": (1e-12, 0.0, "set by the window alone: samples, revolutions of a driven ring"),
    "speed": (1e-8, 1e-9, "cage and rolling element speeds, rpm and rad/s"),
    "slip": (0.0, 1e-8, "cage slip, 1 - cage / epicyclic speed"),
    "force": (1e-8, 1e-6, "contact forces, N"),
    "energy": (1e-9, 1e-12, "mechanical energy, J"),
    "drift": (1e-6, 1e-12, "the energy's largest drift over the window, J"),
    "position": (1e-9, 1e-12, "rolling element centres, m"),
    "displacement": (1e-7, 1e-12, "ring and cage centres (their displacements), m"),
    "velocity": (1e-7, 1e-9, "rolling element centre velocities, m/s"),
    "angle": (1e-9, 1e-12, "the cage's rotation about the bearing axis, rad"),
}

# Summary keys and their classes.
SUMMARY_KEYS = {
    "steps": "counter", "rhs_evaluations": "counter", "jacobian_evaluations": "counter",
    "output_samples": "exact", "driven_ring_revolutions": "exact",
    "cage_speed_rpm": "speed", "epicyclic_cage_speed_rpm": "speed", "cage_slip": "slip",
    "inner_ring_contact_force_n": "force",
    "energy_initial_j": "energy", "energy_final_j": "energy", "energy_max_drift_j": "drift",
}

# Series read at the last sample: quantity name, candidate dataset paths (every spelling the
# layout has used; the first present is read), how the row is reduced, class. Ring and cage centre
# velocities are left out: at a sample they are the contacts' vibration, which another step
# sequence changes by its own size.
LAST_SAMPLE = [
    ("inner_ring.position", ["inner_ring/position"], None, "displacement"),
    ("outer_ring.position", ["outer_ring/position"], None, "displacement"),
    ("cage.position", ["cage/position"], None, "displacement"),
    # Rotation about the bearing axis: the planar scalar, or the last of the spatial Cardan angles.
    ("cage.rotation", ["cage/angle", "cage/angles"], "last", "angle"),
    ("cage.angular_velocity", ["cage/angular_velocity"], None, "speed"),
    ("elements.position", ["rollers/position", "balls/position"], None, "position"),
    ("elements.velocity", ["rollers/velocity", "balls/velocity"], None, "velocity"),
    ("elements.spin", ["rollers/angular_velocity", "rollers/spin", "balls/angular_velocity"], None, "speed"),
]


def fail_usage(message):
    print(f"scene_answers: {message}", file=sys.stderr)
    sys.exit(2)


def scene_name(scene):
    return os.path.splitext(os.path.basename(scene))[0]


def run_scene(raceway, scene, overrides, workdir, tag=""):
    """Runs the scene; returns (summary dict, output path). Exits 2 with the run's last lines
    when it fails."""
    name = scene_name(scene) + (f".{tag}" if tag != "" else "")
    out, summary = os.path.join(workdir, name + ".h5"), os.path.join(workdir, name + ".json")
    command = [raceway, "run", scene, "-o", out, "--summary-json", summary]
    for override in overrides:
        command += ["--set", override]
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode != 0:
        tail = "\n".join(done.stdout.splitlines()[-5:])
        fail_usage(f"{' '.join(command)}: exit code {done.returncode}\n{tail}")
    with open(summary) as f:
        return json.load(f), out


def first_present(f, paths):
    """The first of the paths the file holds; failing that, a dataset of the same group whose
    name begins with a candidate's (a renamed `cage/angle` is still found as `cage/angle_z`)."""
    for path in paths:
        if path in f:
            return f[path]
    for path in paths:
        group, _, stem = path.rpartition("/")
        if group in f and isinstance(f[group], h5py.Group):
            names = sorted(n for n in f[group] if n.startswith(stem) and isinstance(f[group][n], h5py.Dataset))
            if names:
                return f[group][names[0]]
    return None


def last_segment_row_is_last_sample(f):
    """Whether /segments' last row holds the last output sample (docs/output_layout.md, "Segment
    diagnostics at a coarser sampling": row r is sample r N)."""
    segments = f["segments"]
    if int(segments.attrs.get("sample_stride", 1)) == 1:
        return True
    return "time" in segments and segments["time"].shape[0] > 0 and segments["time"][-1] == f["time"][-1]


def quantities(summary, output):
    """Every chosen quantity of a run: {name: (value, class)}; a value is a float or a list."""
    found = {}
    for key, cls in SUMMARY_KEYS.items():
        if key in summary and summary[key] is not None:
            found["summary." + key] = (summary[key], cls)
    with h5py.File(output, "r") as f:
        for name, paths, reduce, cls in LAST_SAMPLE:
            dataset = first_present(f, paths)
            if dataset is None:
                continue
            row = np.asarray(dataset[-1], dtype=float)
            if reduce == "last":
                row = row.reshape(-1)[-1]
            found["last." + name] = (row.tolist(), cls)
        segments = f.get("segments")
        for kind in sorted(segments.keys()) if segments is not None else []:
            # Groups only (/segments/time is a dataset); the last row is the last sample's when every
            # sample stores the segments ([output] segment_every = 1), or, at a stride, when the
            # last sample is one of the stored ones (/segments/time ends at /time's end).
            if isinstance(segments[kind], h5py.Group) and "normal_force" in segments[kind] \
                    and last_segment_row_is_last_sample(f):
                forces = np.abs(np.asarray(segments[kind]["normal_force"][-1], dtype=float))
                found[f"last.{kind}.max_normal_force"] = (float(forces.max()), "force")
    return found


def within(expected, actual, rel, abs_):
    """(ok, worst index, |diff|, allowed at that index, elements outside) of actual against
    expected, tolerance abs_ + rel * scale (|e| of a number, max |e| of an array)."""
    e, a = np.asarray(expected, dtype=float), np.asarray(actual, dtype=float)
    if e.shape != a.shape:
        return False, None, float("nan"), float("nan"), -1
    scale = np.abs(e) if e.ndim == 0 else (np.max(np.abs(e)) if e.size else 0.0)
    allowed = abs_ + rel * scale * np.ones_like(e)
    diff = np.abs(a - e)
    bad = ~(diff <= allowed)  # NaN is outside every tolerance
    excess = np.where(np.isnan(diff), np.inf, diff - allowed)
    worst = np.unravel_index(int(np.argmax(excess)), e.shape) if e.ndim else ()
    return not bad.any(), worst, float(diff[worst]), float(allowed[worst]), int(bad.sum())


def pick(value, index):
    return float(np.asarray(value, dtype=float)[index]) if index is not None else float("nan")


def compare(answer, actual, verbose):
    """Rows of the comparison table, and the number of quantities outside their tolerance."""
    rows, failures = [], 0
    for name, entry in answer["quantities"].items():
        if name not in actual:
            rows.append((name, "", entry["value"] if np.ndim(entry["value"]) == 0 else "[...]", "missing",
                         "", "", "FAIL"))
            failures += 1
            continue
        ok, index, diff, allowed, outside = within(entry["value"], actual[name][0], entry["rel"], entry["abs"])
        failures += not ok
        if ok and not verbose:
            continue
        where = "shape" if outside < 0 else ("" if not index else str(list(index)))
        status = "ok" if ok else ("FAIL" if outside <= 1 else f"FAIL ({outside} elements)")
        rows.append((name, where, pick(entry["value"], index) if outside >= 0 else np.shape(entry["value"]),
                     pick(actual[name][0], index) if outside >= 0 else np.shape(actual[name][0]),
                     diff, allowed, status))
    for name in sorted(set(actual) - set(answer["quantities"])):
        if verbose:
            rows.append((name, "", "(not in the answer file)", "", "", "", "new"))
    return rows, failures


def table(rows):
    head = ("quantity", "index", "expected", "actual", "|diff|", "allowed", "")
    digits = (None, None, 10, 10, 3, 3, None)  # values in full enough to see the change, sizes short
    cells = [head] + [tuple(f"{c:.{d}g}" if isinstance(c, float) else str(c) for c, d in zip(r, digits))
                      for r in rows]
    widths = [max(len(r[i]) for r in cells) for i in range(len(head))]
    return "\n".join("  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip() for r in cells)


def answer_path(answers_dir, scene):
    return os.path.join(answers_dir, scene_name(scene) + ".json")


def load_answer(path):
    try:
        with open(path) as f:
            return json.load(f)
    except FileNotFoundError:
        return None
    except (OSError, ValueError) as error:
        fail_usage(f"{path}: cannot read the answer file: {error}")


def build_of(raceway):
    done = subprocess.run([raceway, "--version"], stdout=subprocess.PIPE, text=True)
    return done.stdout.splitlines()[0] if done.returncode == 0 and done.stdout else "unknown"


def relative_scene(scene):
    """A path inside the repository relative to its root, others absolute."""
    path = os.path.abspath(scene)
    return os.path.relpath(path, ROOT) if path.startswith(ROOT + os.sep) else path


def round_up(x):
    """x rounded up to two significant digits (a tolerance never ends below what it was set to)."""
    if x <= 0 or not math.isfinite(x):
        return x
    exponent = math.floor(math.log10(x)) - 1
    return float(f"{math.ceil(x / 10.0 ** exponent - 1e-9)}e{exponent}")


def magnitude(value):
    return float(np.max(np.abs(np.asarray(value, dtype=float)))) if np.size(value) else 0.0


def noise_runs(raceway, scene, window, summary, workdir):
    """The NOISE_VARIANTS as their --set overrides, from the resolved parameters of the run."""
    parameters = summary.get("scene_parameters", {})
    rtol = parameters.get("solver.rtol", {}).get("value", 1e-6)
    first_step = parameters.get("solver.initial_step", {}).get("value", 0.0)
    steps = [s for s in (1e-7, 1e-6, 3e-7) if not math.isclose(s, first_step)][:2]
    overrides = [[f"solver.initial_step={steps[0]} s"], [f"solver.initial_step={steps[1]} s"],
                 [f"solver.rtol={rtol / 10:.6g}"]]
    for index, (name, extra) in enumerate(zip(NOISE_VARIANTS, overrides)):
        variant_summary, variant_output = run_scene(raceway, scene, window + extra, workdir, tag=f"noise{index}")
        yield name, extra, quantities(variant_summary, variant_output)


def answer_entry(value, cls, noise):
    rel_floor, abs_floor, _ = FLOORS[cls]
    scale = magnitude(value)
    rel = max(rel_floor, NOISE_FACTOR * noise / scale) if scale > 0 else rel_floor
    abs_ = abs_floor if scale > 0 else max(abs_floor, NOISE_FACTOR * noise)
    return {"value": value, "class": cls, "noise": round_up(noise), "rel": round_up(rel), "abs": round_up(abs_)}


def write_answer(path, answer):
    """The answer file, one line per quantity (a change shows as the lines of what changed)."""
    lines = [f" {json.dumps(k)}: {json.dumps(v)}," for k, v in answer.items() if k != "quantities"]
    lines += [' "quantities": {']
    items = list(answer["quantities"].items())
    lines += [f"  {json.dumps(k)}: {json.dumps(v)}{',' if i + 1 < len(items) else ''}"
              for i, (k, v) in enumerate(items)]
    with open(path + ".tmp", "w") as f:
        f.write("{\n" + "\n".join(lines) + "\n }\n}\n")
    json.load(open(path + ".tmp"))  # it reads back
    os.replace(path + ".tmp", path)


def update(args, scene, workdir):
    path = answer_path(args.answers, scene)
    old = load_answer(path)
    if args.end_time:
        window = [f"scene.end_time={args.end_time}"]
    elif old is not None:
        window = old["window"]
    else:
        fail_usage(f"{path}: no answer file yet: give the window with --end-time (1-5 s of run here)")
    summary, output = run_scene(args.raceway, scene, window, workdir)
    found = quantities(summary, output)
    noise = {name: 0.0 for name in found}
    variants = []
    for variant, extra, other in noise_runs(args.raceway, scene, window, summary, workdir):
        variants.append(f"{variant}: --set {' '.join(extra)}")
        for name, (value, cls) in found.items():
            if cls == "counter" and variant == "rtol / 10":
                continue  # a tighter tolerance costs steps: that is the method's work, not noise
            if name in other and np.shape(other[name][0]) == np.shape(value):
                difference = np.abs(np.asarray(other[name][0], float) - np.asarray(value, float))
                noise[name] = max(noise[name], float(np.max(difference)) if difference.size else 0.0)
    answer = {
        "scene": relative_scene(scene),
        "window": window,
        "written_by": build_of(args.raceway),
        "regenerate": f"scripts/scene_answers.py --update {relative_scene(scene)}",
        "tolerance": (f"|actual - expected| <= abs + rel * scale (scale: |expected|, or max |expected| "
                      f"of an array); rel and abs: {NOISE_FACTOR:g} x noise, at least the class's floor "
                      f"(scripts/scene_answers.py FLOORS); noise: the largest difference of these runs: "
                      + "; ".join(variants)),
        "quantities": {name: answer_entry(value, cls, noise[name]) for name, (value, cls) in found.items()},
    }
    write_answer(path, answer)
    print(f"{path}: {len(found)} quantities, window {' '.join(window)}")
    return 0


def check(args, scene, workdir):
    path = answer_path(args.answers, scene)
    answer = load_answer(path)
    if answer is None:
        fail_usage(f"{path}: no answer file for {scene}; write it with "
                   f"scripts/scene_answers.py --update --end-time TIME {relative_scene(scene)}")
    summary, output = run_scene(args.raceway, scene, answer["window"] + args.set, workdir)
    rows, failures = compare(answer, quantities(summary, output), args.verbose)
    header = (f"{scene_name(scene)} ({' '.join(answer['window'] + [f'--set {s}' for s in args.set])}; "
              f"answers {relative_scene(path)}, written by {answer.get('written_by', '?')})")
    if failures:
        print(f"{header}: {failures} of {len(answer['quantities'])} quantities outside their tolerance\n"
              f"{table(rows)}\n(allowed: abs + rel * scale, with each quantity's noise, rel and abs in "
              f"the answer file; if the change is intended: "
              f"scripts/scene_answers.py --update {relative_scene(scene)})")
        return 1
    print(f"{header}: all {len(answer['quantities'])} quantities agree")
    if rows:
        print(table(rows))
    return 0


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("scenes", nargs="+", metavar="SCENE.toml")
    parser.add_argument("--raceway", default=os.path.join(ROOT, "build", "raceway"))
    parser.add_argument("--answers", default=os.path.join(ROOT, "tests", "system", "scenes", "answers"))
    parser.add_argument("--update", action="store_true")
    parser.add_argument("--end-time", help="the window of a new answer file, e.g. '5 ms' (with --update)")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE")
    parser.add_argument("--keep", metavar="DIR")
    parser.add_argument("--verbose", action="store_true")
    args = parser.parse_args(argv)
    if args.end_time and not args.update:
        fail_usage("--end-time goes with --update")
    if args.update and args.set:
        fail_usage("--set does not go with --update (an answer file holds its window only)")
    if not os.access(args.raceway, os.X_OK):
        fail_usage(f"{args.raceway}: no raceway executable (build it, or give --raceway)")
    for scene in args.scenes:
        if not os.path.isfile(scene):
            fail_usage(f"{scene}: no such scene file")
    status = 0
    with tempfile.TemporaryDirectory(prefix="scene_answers.") as scratch:
        workdir = args.keep or scratch
        os.makedirs(workdir, exist_ok=True)
        for scene in args.scenes:
            status = max(status, (update if args.update else check)(args, scene, workdir))
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
