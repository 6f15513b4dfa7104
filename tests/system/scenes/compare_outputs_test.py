#!/usr/bin/python3
"""scripts/compare_outputs.py, the bitwise comparison for refactors, on a real output and copies of
it changed in known ways: a copy is identical; one value one bit off, a NaN, an attribute, a
dataset gone are each reported (exit 1) and named; the legitimately differing attributes (the
build's commit, wall times in the summary) are left out; --map reads a renamed dataset; two
summaries compare by value.

    compare_outputs_test.py RACEWAY SOURCE_DIR
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

try:
    import h5py
    import numpy as np
except ImportError as missing:
    print(f"compare_outputs: skipped: {missing}")
    sys.exit(77)

raceway, source_dir = sys.argv[1], sys.argv[2]
compare_script = os.path.join(source_dir, "scripts", "compare_outputs.py")
failures = 0


def compare(*args):
    done = subprocess.run([sys.executable, compare_script, *args], stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True)
    return done.returncode, done.stdout


def expect(what, args, code, *names):
    global failures
    rc, out = compare(*args)
    missing = [n for n in names if n not in out]
    if rc != code or missing:
        print(f"FAIL: {what}: exit code {rc} (expected {code}), not named: {missing}\n{out}")
        failures += 1
    else:
        print(f"ok: {what}: {out.strip().splitlines()[-1]}")


def changed_copy(work, name, change):
    path = os.path.join(work, name + ".h5")
    shutil.copy(os.path.join(work, "run.h5"), path)
    with h5py.File(path, "r+") as f:
        change(f)
    return path


def one_bit_off(f):
    values = f["rollers/position"][...]
    values.view(np.uint64)[-1, 2, 0] ^= np.uint64(1)  # the last bit of one double
    f["rollers/position"][...] = values


def one_nan(f):
    values = f["rollers/angular_velocity"][...]
    values[1, 3] = np.nan
    f["rollers/angular_velocity"][...] = values


def legitimate_differences(f):
    f.attrs["raceway_commit"] = "0123abc-dirty"
    f.attrs["scene_source"] = "/elsewhere/default.toml"
    summary = json.loads(f.attrs["summary_json"])
    summary["wall_time_s"] *= 3.0
    f.attrs["summary_json"] = json.dumps(summary)


with tempfile.TemporaryDirectory(prefix="compare_outputs.") as work:
    run = os.path.join(work, "run.h5")
    summary = os.path.join(work, "run.json")
    subprocess.run([raceway, "run", os.path.join(source_dir, "jobs", "scenes", "default.toml"), "--set",
                    "scene.end_time=2 ms", "-o", run, "--summary-json", summary],
                   stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT, check=True)
    expect("a copy", [run, changed_copy(work, "copy", lambda f: None)], 0, "identical")
    with h5py.File(run, "r") as f:
        last = f["time"].shape[0] - 1
    expect("one bit of one value", [run, changed_copy(work, "bit", one_bit_off)], 1,
           "/rollers/position: 1 of", f"[{last}, 2, 0]")
    expect("a NaN", [run, changed_copy(work, "nan", one_nan)], 1, "/rollers/angular_velocity", "NaN in one file only")
    expect("an attribute", [run, changed_copy(work, "units", lambda f: f["energy"].attrs.modify("units", "kJ"))],
           1, "/energy@units: J against kJ")
    expect("a dataset gone", [run, changed_copy(work, "gone", lambda f: f.__delitem__("cage/velocity"))], 1,
           "/cage/velocity: only in A")
    expect("build, scene path and wall time", [run, changed_copy(work, "build", legitimate_differences)], 0,
           "identical")
    expect("a counter in the summary attribute", [run, changed_copy(work, "steps", lambda f: f.attrs.modify(
        "summary_json", f.attrs["summary_json"].replace('"steps": ', '"steps": 1'))), ], 1, "summary_json.steps")
    renamed = changed_copy(work, "renamed", lambda f: f.move("cage/angles", "cage/angles_renamed"))
    expect("a renamed dataset without --map", [run, renamed], 1, "/cage/angles: only in A")
    expect("a renamed dataset with --map", [run, renamed, "--map", "/cage/angles=/cage/angles_renamed"], 0, "identical")
    other_summary = os.path.join(work, "other.json")
    with open(summary) as f:
        values = json.load(f)
    values["wall_time_s"] += 1.0
    with open(other_summary, "w") as f:
        json.dump(values, f)
    expect("summaries, wall time apart", [summary, other_summary], 0, "identical")
    values["rhs_evaluations"] += 1
    with open(other_summary, "w") as f:
        json.dump(values, f)
    expect("summaries, one counter apart", [summary, other_summary], 1, "rhs_evaluations")
if failures:
    sys.exit(1)
print("compare_outputs: passed")
