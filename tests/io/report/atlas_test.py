#!/usr/bin/env python3
"""The cage-stability atlas (docs/atlas.md): io/report/cage_motion.py, atlas_certify.py,
atlas_search.py, atlas_file.py and `raceway atlas`.

    atlas_test.py CASE RACEWAY SOURCE_DIR      exit 0 pass, 1 fail, 77 numpy / scikit-learn missing

CASE (the cage motion's classes on synthetic orbits are in atlas_motion_test.py): certify (block agreement, the rtol sample, Student's t interval by hand),
search_accuracy (the adaptive search locates the stand-in's boundary with at least 3x fewer points
than a grid of the same accuracy), search_resume (a killed atlas resumed loses no finished point and
gives the uninterrupted atlas), search_stop (SIGTERM: exit 4, resumed likewise), search_ends (the
uncertainty band small enough; a failed point), bad_files (file,
line, key, reason, exit 2, nothing created),
run_6205 (a tiny real atlas through the executable: table, map, certification), shipped_files
(every atlas file of jobs/atlas/ passes --check).
"""
import csv
import json
import math
import os
import signal
import subprocess
import sys
import tempfile
import time
import tomllib

try:
    import numpy as np
except ImportError as err:
    print(f"SKIP: {err}", file=sys.stderr)
    sys.exit(77)

CASE, RACEWAY, SOURCE = sys.argv[1], os.path.abspath(sys.argv[2]), sys.argv[3]
sys.path.insert(0, os.path.join(SOURCE, "io", "report"))
import atlas_certify as ac  # noqa: E402
import atlas_search as search  # noqa: E402
import cage_motion as cm  # noqa: E402
from atlas_test_support import STANDIN_ATLAS, boundary_error  # noqa: E402

NEEDS_SKLEARN = {"search_accuracy", "search_resume", "search_stop", "search_ends", "run_6205", "shipped_files"}
if CASE in NEEDS_SKLEARN and not search.have_sklearn():
    print("SKIP: scikit-learn (python3-sklearn) is missing", file=sys.stderr)
    sys.exit(77)

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print(f"FAIL: {what}", file=sys.stderr)


def case_certify():
    s = ac.settled([0.10, 0.12, 0.11], ["stable"] * 3, "stable", 0.05)
    check(s["ok"] and abs(s["largest_step"] - 0.02) < 1e-12, f"blocks within tolerance: {s}")
    s = ac.settled([0.10, 0.30, 0.31], ["stable"] * 3, "stable", 0.05)
    check(not s["ok"], "blocks 0.2 apart passed a tolerance of 0.05")
    s = ac.settled([0.10, 0.16, 0.22], ["stable", "stable", "unstable"], "stable", 0.05)
    check(not s["ok"] and abs(s["largest_step"] - 0.06) < 1e-12 and not s["classes_agree"],
          f"a metric drifting 0.06 a block passed a tolerance of 0.05: {s}")
    s = ac.settled([0.10, 0.10, float("nan")], ["stable"] * 3, "stable", 0.05)
    check(not s["ok"], "a block without a metric passed")
    # A whirl still growing (its radius doubling over the window) keeps a small metric and small
    # steps: the orbit's growth catches it; a steady orbit with noise passes.
    s = ac.settled([0.010, 0.012, 0.014], ["stable"] * 3, "stable", 0.05, [3.0e-6, 4.3e-6, 6.1e-6], 0.25)
    check(not s["ok"] and abs(s["orbit_growth"] - 6.1 / 3.0) < 1e-12, f"a growing orbit passed: {s}")
    s = ac.settled([0.010, 0.010, 0.010], ["stable"] * 3, "stable", 0.05, [3.0e-6, 2.97e-6, 3.02e-6], 0.25)
    check(s["ok"] and s["orbit_growth"] == 1.0, f"a steady orbit failed: {s}")
    s = ac.settled([0.010, 0.010, 0.010], ["stable"] * 3, "stable", 0.05, [3.0e-6, 3.3e-6, 3.6e-6], 0.25)
    check(s["ok"] and abs(s["orbit_growth"] - 1.2) < 1e-12, f"growth 1.2 failed a tolerance of 0.25: {s}")
    s = ac.settled([0.010, 0.012, 0.014], ["unstable"] * 3, "unstable", 0.05, [3.0e-6, 4.3e-6, 6.1e-6], 0.25)
    check(s["ok"] and abs(s["orbit_growth"] - 6.1 / 3.0) < 1e-12, f"an unstable point's growth unsettled it: {s}")
    check([i for i in range(10) if ac.in_convergence_sample(i, 0.25)] == [0, 4, 8], "every 4th point rerun")
    check(not any(ac.in_convergence_sample(i, 0.0) for i in range(10)), "a zero sample reruns points")
    c = ac.converged("unstable", 0.40, "unstable", 0.43, 1e-7, 0.05)
    check(c["ok"] and abs(c["difference"] - 0.03) < 1e-12, f"rtol rerun within tolerance: {c}")
    check(not ac.converged("unstable", 0.40, "circling", 0.41, 1e-7, 0.05)["ok"], "another class converged")
    # 1, 2, 3: mean 2, sample std 1, half-width t(2) / sqrt(3) = 4.303 / 1.732 = 2.4843.
    r = ac.confidence([1.0, 2.0, 3.0], 2.5)
    check(abs(r["mean"] - 2.0) < 1e-12 and abs(r["half_width_95"] - 4.303 / math.sqrt(3)) < 1e-9 and r["ok"],
          f"confidence of 1, 2, 3: {r}")
    check(not ac.confidence([1.0, 2.0, 3.0], 2.4)["ok"], "a half-width of 2.48 passed a target of 2.4")
    cert = {"settled": {"ok": True}, "converged": {"checked": False}, "realisations": r}
    check(ac.certified(cert) and "3 realisations" in ac.summary(cert), f"summary {ac.summary(cert)}")


def case_windows():
    """A window in cage revolutions: each point's settling and end time from its kinematic cage speed."""
    from atlas_file import read_atlas_file
    from atlas_models import PointFailed, revolution_times
    speed = 2 * math.pi * 20.0  # 20 cage revolutions a second: 0.05 s each
    for s in (speed, -speed):
        settling, end = revolution_times(s, 10, 30)
        check(abs(settling - 0.5) < 1e-12 and abs(end - 2.0) < 1e-12, f"10 + 30 revolutions at {s}: {settling}, {end}")
    settling, end = revolution_times(8 * speed, 10, 30)  # eight times the speed: an eighth of the time
    check(abs(settling - 0.0625) < 1e-12 and abs(end - 0.25) < 1e-12, f"at 8 times the speed: {settling}, {end}")
    try:
        revolution_times(0.0, 10, 30)
        check(False, "a cage at rest got a window in revolutions")
    except PointFailed:
        pass
    with tempfile.TemporaryDirectory() as tmp:
        text = STANDIN_ATLAS.replace('end_time = "20 ms"\nsettling_time = "10 ms"',
                                     'settling_cage_revolutions = 10\nwindow_cage_revolutions = 30')
        a = read_atlas_file(write_atlas(tmp, text))
        check(a["settling_cage_revolutions"] == 10 and a["window_cage_revolutions"] == 30 and a["end_time_s"] is None,
              f"revolution keys read: {a['settling_cage_revolutions']}, {a['window_cage_revolutions']}")
        a = read_atlas_file(write_atlas(tmp, STANDIN_ATLAS))
        check(a["window_cage_revolutions"] is None and abs(a["end_time_s"] - 0.02) < 1e-15, "end_time read")


def case_search_accuracy():
    """Accuracy: the boundary's load within 0.01 of the range at every speed. The adaptive search's
    points until it gets there, against every regular n x n grid with fewer than 3x as many."""
    target, points = 0.01, list(search.initial_design(2))
    labels = list(search.standin_classes(np.array(points)))
    start = time.monotonic()
    while True:
        error = boundary_error(search.fit_classifier(points, labels))
        if error <= target or len(points) > 150:
            break
        new = search.propose(points, labels, 8)
        points += new
        labels += list(search.standin_classes(np.array(new)))
    adaptive = len(points)
    print(f"adaptive: {adaptive} points, boundary error {error:.4f} ({time.monotonic() - start:.1f} s)")
    check(error <= target, f"adaptive search did not reach {target} in {adaptive} points")
    n = 2
    while (n + 1) ** 2 < 3 * adaptive:
        n += 1
        g = search.regular_grid(n, 2)
        e = boundary_error(search.fit_classifier(g, search.standin_classes(g)))
        print(f"grid {n} x {n} = {n * n} points: boundary error {e:.4f}")
        check(e > target, f"a {n} x {n} grid ({n * n} points, < 3 x {adaptive}) reaches {e:.4f} <= {target}")


def atlas_script(args, env=None, **kw):
    cmd = ["/usr/bin/python3", os.path.join(SOURCE, "io", "report", "raceway_atlas.py")] + args
    return subprocess.Popen(cmd, env={**os.environ, **(env or {})}, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, **kw)


def wait_done(state_path, count, timeout=30):
    """Polls the state file until `count` points are done (or the timeout)."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        try:
            with open(state_path) as f:
                if sum(q["status"] == "done" for q in json.load(f)["points"]) >= count:
                    return
        except (OSError, ValueError):
            pass
        time.sleep(0.01)


def case_search_stop():
    """SIGTERM: no new point, exit 4, the table of what is done; --resume: the uninterrupted atlas."""
    with tempfile.TemporaryDirectory() as tmp:
        path = write_atlas(tmp, STANDIN_ATLAS, "standin.toml")
        whole, cut = os.path.join(tmp, "whole"), os.path.join(tmp, "cut")
        atlas_script([path, "-o", whole, "--standin", "0.02"]).communicate()
        p = atlas_script([path, "-o", cut, "--standin", "0.02"], env={"RACEWAY_ATLAS_STANDIN_DELAY": "0.02"})
        wait_done(os.path.join(cut, "atlas_state.json"), 7)
        p.send_signal(signal.SIGTERM)
        out, _ = p.communicate()
        check(p.returncode == 4, f"stopped atlas exit {p.returncode}, not 4: {out[-300:]}")
        with open(os.path.join(cut, "atlas.json")) as f:
            doc = json.load(f)
        done = sum(q["status"] == "done" for q in doc["points"])
        check(7 <= done < 21 and "signal" in (doc["stop"] or ""), f"stopped with {done} done, stop {doc['stop']!r}")
        r = atlas_script([path, "-o", cut, "--standin", "0.02", "--resume"])
        r.communicate()
        check(r.returncode == 0, f"resume after the stop: exit {r.returncode}")
        tables = []
        for folder in (whole, cut):
            with open(os.path.join(folder, "atlas.csv")) as f:
                tables.append(f.read())
        check(tables[0] == tables[1], "the atlas resumed after a stop differs from the uninterrupted one")
        print(f"stopped by SIGTERM after {done} of 21 points; resumed to the uninterrupted atlas")


def case_search_ends():
    """The search's other ends: the uncertainty band small enough; a failed point."""
    with tempfile.TemporaryDirectory() as tmp:
        # stop_band_share: the search ends when the uncertainty band covers less of the map, before the
        # budget (measured by hand: the band covers 0.052 of it at 41 points, 0.0499 at 45).
        sure = write_atlas(tmp, STANDIN_ATLAS.replace("budget_points = 21",
                                                      "budget_points = 200\nstop_band_share = 0.05"), "sure.toml")
        atlas_script([sure, "-o", os.path.join(tmp, "sure"), "--standin", "0"]).communicate()
        with open(os.path.join(tmp, "sure", "atlas.json")) as f:
            doc = json.load(f)
        check(len(doc["points"]) < 120 and "stop_band_share" in (doc["stop"] or ""),
              f"stop_band_share 0.05: {len(doc['points'])} points, stop {doc['stop']!r}")
        print(f"stop_band_share 0.05: {len(doc['points'])} points, {doc['stop']}")
        # A failed point: recorded with its error, the others run, exit 1.
        failing = write_atlas(tmp, STANDIN_ATLAS.replace("budget_points = 21", "budget_points = 9"), "failing.toml")
        p = atlas_script([failing, "-o", os.path.join(tmp, "failing"), "--standin", "0"],
                         env={"RACEWAY_ATLAS_STANDIN_FAIL": "p0002"})
        p.communicate()
        with open(os.path.join(tmp, "failing", "atlas.csv")) as f:
            rows = {r["id"]: r for r in csv.DictReader(f)}
        check(p.returncode == 1 and len(rows) == 9 and rows["p0002"]["status"] == "failed"
              and "RACEWAY_ATLAS_STANDIN_FAIL" in rows["p0002"]["certified_by"]
              and sum(r["status"] == "done" for r in rows.values()) == 8,
              f"a failed point: exit {p.returncode}, rows {[(k, r['status']) for k, r in rows.items()]}")


def case_search_resume():
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "standin.toml")
        with open(path, "w") as f:
            f.write(STANDIN_ATLAS.format(scene=os.path.join(SOURCE, "jobs", "scenes", "6205_first_scene.toml")))
        whole, cut = os.path.join(tmp, "whole"), os.path.join(tmp, "cut")
        out, _ = atlas_script([path, "-o", whole, "--standin", "0.02"]).communicate()
        evals = os.path.join(tmp, "evaluations.txt")
        env = {"RACEWAY_ATLAS_STANDIN_DELAY": "0.02", "RACEWAY_ATLAS_STANDIN_LOG": evals}
        p = atlas_script([path, "-o", cut, "--standin", "0.02"], env=env)
        state_path, done_before = os.path.join(cut, "atlas_state.json"), []
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline:
            try:
                with open(state_path) as f:
                    done_before = [q for q in json.load(f)["points"] if q["status"] == "done"]
            except (OSError, ValueError):
                pass
            if len(done_before) >= 7:
                break
            time.sleep(0.01)
        p.send_signal(signal.SIGKILL)
        p.communicate()
        with open(state_path) as f:
            done_before = [q for q in json.load(f)["points"] if q["status"] == "done"]
        check(7 <= len(done_before) < 21, f"killed with {len(done_before)} points done (wanted 7..20)")
        with open(evals) as f:
            before = f.read().split()
        refused = atlas_script([path, "-o", cut, "--standin", "0.02"])
        refused.communicate()
        check(refused.returncode == 2, f"a second call without --resume: exit {refused.returncode}, not 2")
        resumed = atlas_script([path, "-o", cut, "--standin", "0.02", "--resume"], env=env)
        rout, _ = resumed.communicate()
        check(resumed.returncode == 0, f"resume exit {resumed.returncode}: {rout[-500:]}")
        with open(evals) as f:
            after = f.read().split()[len(before):]
        again = sorted({q["id"] for q in done_before} & set(after))
        check(not again, f"finished points evaluated again after the resume: {again}")
        tables = []
        for folder in (whole, cut):
            with open(os.path.join(folder, "atlas.csv")) as f:
                tables.append(list(csv.reader(f)))
        check(len(tables[0]) == 22, f"uninterrupted atlas: {len(tables[0]) - 1} rows, not 21")
        check(tables[0] == tables[1], "the resumed atlas's table differs from the uninterrupted one")
        check(os.path.getsize(os.path.join(cut, "atlas.png")) > 10000, "no map")
        print(f"killed after {len(done_before)} of 21 points; resumed: {len(set(after))} points evaluated")
        # A finished atlas of 13 points (the first batch of 5, two of 4) resumed with a budget of 21
        # goes on to the uninterrupted atlas of 21; another setting changed is refused.
        short = os.path.join(tmp, "short.toml")
        with open(path) as f:
            text = f.read()
        with open(short, "w") as f:
            f.write(text.replace("budget_points = 21", "budget_points = 13"))
        grown = os.path.join(tmp, "grown")
        atlas_script([short, "-o", grown, "--standin", "0.02"]).communicate()
        with open(os.path.join(grown, "atlas.csv")) as f:
            check(len(list(csv.reader(f))) == 14, "the atlas of budget 13 has not 13 rows")
        other = os.path.join(tmp, "other.toml")
        with open(other, "w") as f:
            f.write(text.replace('range = [100, 2000]', 'range = [100, 2500]'))
        refused = atlas_script([other, "-o", grown, "--standin", "0.02", "--resume"])
        refused.communicate()
        check(refused.returncode == 2, f"a changed parameter range resumed: exit {refused.returncode}, not 2")
        extended = atlas_script([path, "-o", grown, "--standin", "0.02", "--resume"])
        extended.communicate()
        with open(os.path.join(grown, "atlas.csv")) as f:
            check(list(csv.reader(f)) == tables[0], "the atlas extended from 13 to 21 points differs from the "
                  "uninterrupted one")


def write_atlas(tmp, text, name="bad.toml"):
    path = os.path.join(tmp, name)
    with open(path, "w") as f:
        f.write(text.format(scene=os.path.join(SOURCE, "jobs", "scenes", "6205_first_scene.toml")))
    return path


def bad_in_file(text, line, key, words):
    """The parser (atlas_file.py) refuses the file: its error names file, line, key and reason."""
    from atlas_file import AtlasFileError, read_atlas_file
    with tempfile.TemporaryDirectory() as tmp:
        path = write_atlas(tmp, text)
        try:
            read_atlas_file(path)
            check(False, f"bad atlas file ({key}) accepted")
        except AtlasFileError as err:
            msg = str(err)
            check(msg.startswith(f"{path}:{line}: key '{key}': ") and all(w in msg for w in words),
                  f"bad atlas file ({key}): {msg!r}")


def bad_by_executable(text, line, key, words):
    """`raceway atlas` refuses the file: exit 2, the error on stderr, the folder never created."""
    with tempfile.TemporaryDirectory() as tmp:
        path = write_atlas(tmp, text)
        folder = os.path.join(tmp, "out")
        p = subprocess.run([RACEWAY, "atlas", path, "-o", folder, "--ranks", "2"], capture_output=True, text=True)
        msg = p.stderr.strip()
        ok = (p.returncode == 2 and f"{path}:{line}: key '{key}': " in msg
              and all(w in msg for w in words) and not os.path.exists(folder))
        check(ok, f"bad atlas file ({key}): exit {p.returncode}, message {msg!r}, folder "
                  f"{'created' if os.path.exists(folder) else 'not created'}")


def case_bad_files():
    good = STANDIN_ATLAS
    bad_in_file(good.replace('settling_time = "10 ms"', 'settling_time = "30 ms"'), 5, "atlas.settling_time",
                ["shorter"])
    bad_in_file(good.replace('budget_points = 21', 'budget_points = 0'), 7, "atlas.budget_points", ["at least 1"])
    bad_in_file(good.replace('classes = ["stable", "unstable"]', 'classes = ["stable", "wobbly"]'), 6,
                "atlas.classes", ["two or more"])
    bad_in_file(good.replace('range = [100, 2000]', 'range = [2000, 100]'), 22, "parameter[1].range", ["below"])
    bad_in_file(good.replace('range = [100, 2000]', 'range = [100, inf]'), 22, "parameter[1].range", ["finite"])
    bad_in_file(good.replace('unit = "rpm"\n', ''), 14, "parameter[0].unit", ["unit"])
    bad_in_file(good.replace('batch_size = 4', 'batch_size = 4\nbugdet = 3'), 9, "atlas.bugdet", ["unknown key"])
    bad_in_file(good.split("[[parameter]]\nkey = \"inner_ring.load.fz\"")[0], 14, "parameter[0]", ["at least two"])
    bad_in_file(good.replace('realisations = ["10 um", "20 um"]', 'realisations = ["10 um"]'), 12,
                "certify.realisations", ["at least two"])
    bad_in_file(good.replace('realisations = ["10 um", "20 um"]', 'realisations = ["10 um", "20 um"]\n'
                             'threshold_realisations = ["15 um", "20 um"]'), 13, "certify.threshold_realisations",
                ["given twice"])
    bad_in_file(good.replace('realisations = ["10 um", "20 um"]', 'threshold_realisations = "15 um"'), 12,
                "certify.threshold_realisations", ["must be a list"])
    bad_in_file(good.replace('realisations = ["10 um", "20 um"]', 'threshold_realisations = ["15 um"]'), 12,
                "certify.threshold_realisations", ["needs the realisations"])
    bad_in_file(good.replace('unit = "N"', 'unit = "N"\nscale = "cubic"'), 24, "parameter[1].scale", ["\"log\""])
    bad_in_file(good.replace('unit = "N"', 'unit = "N"\nscale = "log"').replace('[100, 2000]', '[0, 2000]'), 24,
                "parameter[1].scale", ["above 0"])
    scaled = good.replace('unit = "N"', 'unit = "N"\nscale = "log"')
    with tempfile.TemporaryDirectory() as tmp:
        from atlas_file import parameter_unit, parameter_value, read_atlas_file
        p = read_atlas_file(write_atlas(tmp, scaled))["parameters"]
        v = [parameter_value(p[1], u) for u in (0, 0.5, 1)]
        check(abs(v[0] - 100) < 1e-9 and abs(v[1] - math.sqrt(100 * 2000)) < 1e-9 and abs(v[2] - 2000) < 1e-9
              and abs(parameter_unit(p[1], v[1]) - 0.5) < 1e-12 and "scale" not in p[0]
              and parameter_value(p[0], 0.5) == 4500, f"log scale values {v}")
    bad_in_file(good.replace('end_time = "20 ms"', 'end_time = "20 ms'), 4, "(syntax)", ["not TOML"])
    bad_in_file(good + "\n[thresholds]\nwobble = 1\n", 26, "thresholds.wobble", ["unknown key", "stable_orbit_ratio"])
    bad_in_file(good + "\n[thresholds]\ncircling_sigma_v = -1\n", 26, "thresholds.circling_sigma_v", ["at least 0"])
    bad_in_file(good.replace('batch_size = 4', 'batch_size = 4\nset = {{ "inner_ring.speed" = "1 rpm" }}'), 9,
                "atlas.set", ["also a parameter"])
    revolutions = good.replace('end_time = "20 ms"\nsettling_time = "10 ms"',
                               'settling_cage_revolutions = 10\nwindow_cage_revolutions = 30')
    bad_in_file(revolutions.replace('window_cage_revolutions = 30', 'window_cage_revolutions = 0'), 5,
                "atlas.window_cage_revolutions", ["greater than 0"])
    bad_in_file(revolutions.replace('window_cage_revolutions = 30\n', ''), 4, "atlas.settling_cage_revolutions",
                ["needs window_cage_revolutions"])
    bad_in_file(revolutions.replace('window_cage_revolutions = 30', 'window_cage_revolutions = 30\nend_time = "1 s"'),
                6, "atlas.end_time", ["kinematic cage speed"])
    # Through the executable: exit 2 before anything is created; values the scene refuses, found by
    # `raceway check` before any point, name the line that set them.
    bad_by_executable(good.replace('end_time = "20 ms"', 'end_time = "20"'), 4, "atlas.end_time", ["positive time"])
    bad_by_executable(good.replace('"20 um"]', '"-5 um"]'), 12, "certify.realisations",
                      ["rejected", "cage.initial_offset"])
    bad_by_executable(good.replace('realisations = ["10 um", "20 um"]', 'realisations = ["10 um", "20 um"]\n'
                                   'threshold_realisations = ["-15 um"]'), 13, "certify.threshold_realisations",
                      ["rejected", "cage.initial_offset"])
    bad_by_executable(good.replace('unit = "N"', 'unit = "furlongs"'), 22, "parameter[1].range", ["rejected", "corner"])


TINY_ATLAS = """[atlas]
scene = "{scene}"
end_time = "10 ms"
settling_time = "5 ms"
budget_points = 3
batch_size = 3
set = {{ "scene.output_interval" = "0.1 ms", "scene.gravity" = true }}

[thresholds]
stable_orbit_ratio = 0.25

[certify]
blocks = 2
convergence_sample = 0.34
realisation_key = "cage.initial_offset"
realisations = ["10 um", "30 um"]

[[parameter]]
key = "inner_ring.speed"
range = [2000, 6000]
unit = "rpm"

[[parameter]]
key = "inner_ring.load.fy"
name = "load"
range = [-400, -100]
unit = "N"
"""


def case_run_6205():
    with tempfile.TemporaryDirectory() as tmp:
        path = write_atlas(tmp, TINY_ATLAS, "tiny.toml")
        p = subprocess.run([RACEWAY, "atlas", path, "--check"], capture_output=True, text=True)
        check(p.returncode == 0 and not os.path.exists(os.path.join(tmp, "out")), f"--check exit {p.returncode}")
        folder = os.path.join(tmp, "out")
        p = subprocess.run([RACEWAY, "atlas", path, "-o", folder, "--ranks", "2"], capture_output=True, text=True)
        check(p.returncode == 0, f"atlas exit {p.returncode}: {(p.stdout + p.stderr)[-800:]}")
        with open(os.path.join(folder, "atlas.json")) as f:
            doc = json.load(f)
        pts = doc["points"]
        check(len(pts) == 3 and all(q["status"] == "done" for q in pts), f"points: {[q['status'] for q in pts]}")
        check([q["index"] % 3 == 0 for q in pts] == [q["certification"]["converged"]["checked"] for q in pts],
              "the rtol sample is not every 3rd point")
        for q in pts:
            check(q["class"] in cm.CLASSES and q["certified_by"], f"{q['id']}: class / certification missing")
            check(q["class"] != "stable" or "< 0.25" in q["reasons"][0], f"{q['id']}: threshold not applied: {q['reasons']}")
            check(len(q["certification"]["settled"]["block_metric"]) == 2, f"{q['id']}: not 2 blocks")
            check(q["certification"]["realisations"]["checked"] == (q["class"] == "unstable"),
                  f"{q['id']}: realisations run for a {q['class']} point or not for an unstable one")
            check(os.path.isfile(os.path.join(folder, q["output"])), f"{q['id']}: output {q['output']} missing")
        speeds = sorted(q["values"]["speed"] for q in pts)
        check(speeds == [2000, 2000, 6000] or speeds == [2000, 6000, 6000], f"corner speeds {speeds}")
        with open(os.path.join(folder, "atlas.csv")) as f:
            rows = list(csv.DictReader(f))
        check(len(rows) == 3 and "speed_rpm" in rows[0] and "load_N" in rows[0] and "certified_by" in rows[0],
              f"atlas.csv columns {list(rows[0]) if rows else []}")
        check(os.path.getsize(os.path.join(folder, "atlas.png")) > 10000, "no map")
        print("; ".join(f"{q['id']} {q['class']} CDI {q['metric']:.3g}" for q in pts))


# The solver of the QJ215 atlases' stored points (their base scene's before it took the trapezoidal rule).
QJ215_SOLVER = {"solver.max_order": 12, "solver.pocket_tolerance_factor": 1, "solver.pocket_tolerance_cage": False}


def case_shipped_files():
    """Every atlas file the project ships passes `raceway atlas FILE --check` (its keys, and its base
    scene at every corner of the ranges, each realisation and the convergence rtol) and creates nothing;
    one over a scene that stores its segment diagnostics at a stride sets them back to every sample, and
    the QJ215 ones pin the solver of their stored points."""
    folder = os.path.join(SOURCE, "jobs", "atlas")
    files = sorted(f for f in os.listdir(folder) if f.endswith(".toml"))
    check("qj215_speed_radial.toml" in files and "6205_speed_unbalance.toml" in files, f"shipped atlases {files}")
    for name in files:
        p = subprocess.run([RACEWAY, "atlas", os.path.join(folder, name), "--check"], capture_output=True, text=True)
        check(p.returncode == 0, f"{name}: --check exit {p.returncode}: {(p.stdout + p.stderr)[-400:]}")
        # A base scene that stores its segment diagnostics at a stride (qj215_validation: every 5th
        # sample) is run with them at every sample: the metric reads every series at the segment rows,
        # and the recorded atlases (docs/atlas/) were taken so.
        with open(os.path.join(folder, name), "rb") as f:
            atlas = tomllib.load(f)["atlas"]
        with open(os.path.normpath(os.path.join(folder, atlas["scene"])), "rb") as f:
            stride = tomllib.load(f).get("output", {}).get("segment_every", 1)
        if stride > 1:
            check(atlas.get("set", {}).get("output.segment_every") == 1,
                  f"{name}: its scene stores the segments every {stride} samples; the atlas must set output.segment_every = 1")
        # The QJ215 atlases keep the solver their stored points were made with: the validation scene
        # ships Adams of order 2 with the pocket factor since (perf/studies/results/pocket_convergence.md).
        if name.startswith("qj215_"):
            sets = atlas.get("set", {})
            check(all(sets.get(k) == v for k, v in QJ215_SOLVER.items()), f"{name}: the solver is not pinned: {sets}")


CASES = {"windows": case_windows,
         "certify": case_certify, "search_accuracy": case_search_accuracy, "search_resume": case_search_resume,
         "search_stop": case_search_stop, "search_ends": case_search_ends,
         "bad_files": case_bad_files, "run_6205": case_run_6205,
         "shipped_files": case_shipped_files}
CASES[CASE]()
sys.exit(1 if failures else 0)
