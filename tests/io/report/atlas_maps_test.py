#!/usr/bin/env python3
"""The atlas's maps for every pair of parameters (io/report/atlas_pairs.py, docs/atlas.md "Outputs").

    atlas_maps_test.py CASE RACEWAY SOURCE_DIR      exit 0 pass, 1 fail, 77 numpy / scikit-learn missing

CASE: pairs_standin3 (a three-parameter stand-in atlas, unstable below the load
0.15 + 0.7 speed^2 + 0.3 (radial - 0.5) in the unit cube: a file per pair listed in atlas.json; on
every slice the classifier's boundary lies where the stand-in's is; the slices where the unstable
class is likeliest are where the stand-in puts them; the points' projections are their parameters
in atlas.csv; the shares of unstable points count every point once), pairs_two_parameters (a
two-parameter atlas keeps its outputs: atlas.png only, no `maps` in atlas.json), realisations_unbalance_phase (the
unbalance's phase, cage.mass_eccentricity_angle, as the atlas's realisation key: checked at every
realisation through the executable, a bare number refused), unbalance_phase_run (3 ms runs of the
6205: the cage centre's offset a 50 um unbalance adds turns by the phase, 90 and 180 deg).
"""
import csv
import json
import os
import subprocess
import sys
import tempfile
import time

try:
    import numpy as np
except ImportError as err:
    print(f"SKIP: {err}", file=sys.stderr)
    sys.exit(77)

CASE, RACEWAY, SOURCE = sys.argv[1], os.path.abspath(sys.argv[2]), os.path.abspath(sys.argv[3])
sys.path.insert(0, os.path.join(SOURCE, "io", "report"))
import atlas_pairs as ap  # noqa: E402
import atlas_search as search  # noqa: E402

if CASE not in ("realisations_unbalance_phase", "unbalance_phase_run") and not search.have_sklearn():
    print("SKIP: scikit-learn (python3-sklearn) is missing", file=sys.stderr)
    sys.exit(77)

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print(f"FAIL: {what}", file=sys.stderr)


ATLAS = """[atlas]
name = "standin3"
scene = "{scene}"
end_time = "20 ms"
settling_time = "10 ms"
classes = ["stable", "unstable"]
budget_points = {budget}
batch_size = 8

[certify]
realisation_key = "cage.initial_offset"
realisations = ["10 um", "20 um"]

[[parameter]]
key = "inner_ring.speed"
name = "speed"
range = [1000, 8000]
unit = "rpm"

[[parameter]]
key = "inner_ring.load.fz"
name = "load"
range = [100, 2000]
unit = "N"
"""
THIRD = """
[[parameter]]
key = "inner_ring.load.fy"
name = "radial"
range = [-40, 0]
unit = "N"
"""
#: The largest distance from the stand-in's boundary, in load (its margin, unit cube), of a slice point
#: the drawn classifier puts on the wrong side (a 0.05 error in load is 0.05 / 0.3 = 0.17 of the radial
#: load's range where the pair has it in place of the load).
TOLERANCE = 0.08


def run_atlas(tmp, text, budget):
    path = os.path.join(tmp, "atlas.toml")
    with open(path, "w") as f:
        f.write(text.format(scene=os.path.join(SOURCE, "jobs", "scenes", "6205_first_scene.toml"), budget=budget))
    out = os.path.join(tmp, "out")
    start = time.monotonic()
    done = subprocess.run(["/usr/bin/python3", os.path.join(SOURCE, "io", "report", "raceway_atlas.py"), path,
                           "-o", out, "--standin", "0"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, check=False)
    print(f"atlas of {budget} points: {time.monotonic() - start:.1f} s, exit {done.returncode}")
    check(done.returncode == 0, f"the stand-in atlas exits {done.returncode}: {done.stdout[-400:]}")
    with open(os.path.join(out, "atlas.json")) as f:
        doc = json.load(f)
    with open(os.path.join(out, "atlas.csv")) as f:
        rows = list(csv.DictReader(f))
    return out, doc, rows


def true_margin(unit):
    """The stand-in's margin (load above its boundary) at unit-cube points (speed, load, radial)."""
    return unit[:, 1] - search.standin_boundary(unit[:, 0], unit[:, 2])


def boundary_error(model, i, j, others):
    """The largest |margin| (the stand-in's load above its boundary, unit cube) of a slice point the
    drawn classifier puts on the wrong side, and how many there are (of the 81 x 81 drawn)."""
    g, z, _, _ = ap.predict_slice(model, 3, i, j, others)
    predicted = np.asarray(model.classes_)[z.astype(int)]  # rows: the pair's second parameter
    unit = np.empty((len(g), len(g), 3))  # built here, not by atlas_pairs: the drawn grid's own axes
    unit[:, :, i], unit[:, :, j] = g[None, :], g[:, None]
    unit[:, :, 3 - i - j] = others[0]
    margin = true_margin(unit.reshape(-1, 3)).reshape(len(g), len(g))
    wrong = predicted != np.where(margin < 0, "unstable", "stable")
    return (float(np.max(np.abs(margin[wrong]))) if wrong.any() else 0.0), int(wrong.sum())


def case_pairs_standin3():
    with tempfile.TemporaryDirectory() as tmp:
        out, doc, rows = run_atlas(tmp, ATLAS + THIRD, 41)
        atlas = {"name": doc["name"], "parameters": doc["parameters"], "classes": doc["classes"],
                 "metric": doc["metric"]}
        names = [p["name"] for p in doc["parameters"]]
        expected = [f"atlas_{names[i]}_{names[j]}.png" for i, j in ((0, 1), (0, 2), (1, 2))]
        check([m["file"] for m in doc.get("maps", [])] == expected, f"maps listed: {doc.get('maps')}")
        for name in ["atlas.png"] + expected:
            size = os.path.getsize(os.path.join(out, name)) if os.path.exists(os.path.join(out, name)) else 0
            check(size > 20000, f"{name}: {size} bytes")
        points = ap.done_points({"points": doc["points"]})
        labels = [p["label"] for p in points]
        model = search.search_classifier(np.array([p["unit"] for p in points]), labels)[0]
        # Where the unstable class is likeliest: the stand-in's boundary rises with the radial load and
        # the speed and falls with the load (unit cube), so at the radial's high, the load's low, the
        # speed's high.
        likeliest = {(0, 1): "high", (0, 2): "low", (1, 2): "high"}
        for record, (i, j) in zip(doc.get("maps", []), ((0, 1), (0, 2), (1, 2))):
            k = 3 - i - j
            low, high = doc["parameters"][k]["range"]
            cuts = record["slices"]
            got = [s["values"][names[k]] for s in cuts]
            check(np.allclose(got[:3], [low, 0.5 * (low + high), high]), f"{record['file']}: slices at {got}")
            marked = [s["what"] for s in cuts if "likeliest" in s["what"]]
            check(len(cuts) == 3 and len(marked) == 1 and marked[0].startswith(f"range's {likeliest[(i, j)]}"),
                  f"{record['file']}: the unstable class likeliest at {marked} "
                  f"(expected the range's {likeliest[(i, j)]})")
            for s in cuts:
                others = [(s["values"][names[k]] - low) / (high - low)]
                error, wrong = boundary_error(model, i, j, others)
                print(f"{record['file']} at {names[k]} = {s['values'][names[k]]:g}: {wrong} of 81 x 81 slice points "
                      f"on the wrong side, at most {error:.3f} in load from the stand-in's boundary")
                check(error <= TOLERANCE, f"{record['file']} at {s['values']}: boundary off by {error:.3f}")
            # The projections: each point at its own parameters (atlas.csv), near a slice as defined.
            x, y, near = ap.projections(atlas, points, i, j, [0.5])
            by_id = {r["id"]: r for r in rows}
            cols = [f"{p['name']}_{p['unit']}" for p in doc["parameters"]]
            want_x = [float(by_id[p["id"]][cols[i]]) for p in points]
            want_y = [float(by_id[p["id"]][cols[j]]) for p in points]
            check(np.allclose(x, want_x, rtol=1e-5) and np.allclose(y, want_y, rtol=1e-5),
                  f"{record['file']}: projections differ from atlas.csv")
            third = np.array([float(by_id[p["id"]][cols[k]]) for p in points])
            want_near = np.abs(third - 0.5 * (low + high)) <= ap.NEAR_SLICE * (high - low) * (1 + 1e-9)
            check(np.array_equal(near, want_near), f"{record['file']}: points near the middle slice")
            share = record["unstable_share"]
            total, hit = np.array(share["points"]), np.array(share["unstable"])
            check(total.sum() == len(points) and hit.sum() == labels.count("unstable") and np.all(hit <= total),
                  f"{record['file']}: shares count {total.sum()} points, {hit.sum()} unstable")
            # one cell by hand: the pair's lowest quarter in both
            corner = [p for p in points if p["unit"][i] < 0.25 and p["unit"][j] < 0.25]
            check(total[0, 0] == len(corner) and hit[0, 0] == sum(p["label"] == "unstable" for p in corner),
                  f"{record['file']}: the lowest cell holds {total[0, 0]}, {len(corner)} by hand")


def case_pairs_two_parameters():
    with tempfile.TemporaryDirectory() as tmp:
        out, doc, _ = run_atlas(tmp, ATLAS, 9)
        files = sorted(f for f in os.listdir(out) if f.endswith(".png"))
        check(files == ["atlas.png"], f"two parameters draw {files}")
        check("maps" not in doc, "two parameters: atlas.json lists maps")


PHASE_ATLAS = """[atlas]
scene = "{scene}"
end_time = "20 ms"
settling_time = "10 ms"
budget_points = 9

[certify]
realisation_key = "cage.mass_eccentricity_angle"
realisations = {realisations}

[[parameter]]
key = "inner_ring.speed"
name = "speed"
range = [3000, 8000]
unit = "rpm"

[[parameter]]
key = "cage.mass_eccentricity"
name = "unbalance"
range = [10, 100]
unit = "um"
"""


def case_realisations_unbalance_phase():
    """The unbalance's phase as the atlas's realisation key: `raceway atlas --check` runs `raceway check`
    at every realisation: 90, 180 and 270 deg pass; a bare number is refused naming the atlas file's
    line of the realisations and the scene's reason (the key's other refusals: the bad scenes)."""
    scene = os.path.join(SOURCE, "jobs", "scenes", "6205_first_scene.toml")
    cases = [('["90 deg", "180 deg", "270 deg"]', 0, None),
             ('["90 deg", "180"]', 2, "180 has no unit: an angle needs one")]
    with tempfile.TemporaryDirectory() as tmp:
        for realisations, code, words in cases:
            path = os.path.join(tmp, "phase.toml")
            with open(path, "w") as f:
                f.write(PHASE_ATLAS.format(scene=scene, realisations=realisations))
            p = subprocess.run([RACEWAY, "atlas", path, "--check"], capture_output=True, text=True, check=False)
            text = p.stdout + p.stderr
            print(f"realisations {realisations}: exit {p.returncode}: {text.strip().splitlines()[-1]}")
            check(p.returncode == code,
                  f"realisations {realisations}: exit {p.returncode}, expected {code}: {text[-300:]}")
            if words:
                check(f"{path}:9: key 'certify.realisations'" in text and words in text
                      and "cage.mass_eccentricity_angle" in text, f"realisations {realisations}: {text[-300:]}")


def cage_offsets(tmp, sets):
    """The cage centre's (x, y) [m] at each output of a 3 ms run of the 6205 with `sets`."""
    import h5py

    out = os.path.join(tmp, f"run{len(os.listdir(tmp))}.h5")
    args = [RACEWAY, "run", os.path.join(SOURCE, "jobs", "scenes", "6205_first_scene.toml"), "-o", out,
            "--set", "scene.end_time=3 ms"]
    for key, value in sets.items():
        args += ["--set", f"{key}={value}"]
    done = subprocess.run(args, capture_output=True, text=True, check=False)
    check(done.returncode == 0, f"run {sets}: exit {done.returncode}: {(done.stdout + done.stderr)[-300:]}")
    with h5py.File(out, "r") as f:
        return np.asarray(f["cage/position"], dtype=float)[:, :2]


def case_unbalance_phase_run():
    """A short run of the 6205 (3 ms): what a 50 um unbalance adds to the cage centre's path (against
    the run without it) turns by the phase cage.mass_eccentricity_angle (90 and 180 deg, through
    --set), its length the same; phase 0 is the key left out, bitwise."""
    with tempfile.TemporaryDirectory() as tmp:
        base = cage_offsets(tmp, {})
        at = {name: cage_offsets(tmp, {"cage.mass_eccentricity": "50 um", **sets}) - base
              for name, sets in (("none", {}), ("0", {"cage.mass_eccentricity_angle": "0 deg"}),
                                 ("90", {"cage.mass_eccentricity_angle": "90 deg"}),
                                 ("180", {"cage.mass_eccentricity_angle": "3.14159265358979 rad"}))}
        check(np.array_equal(at["0"], at["none"]), "the phase 0 deg changes the run")
        ref = at["none"][-1]
        check(np.hypot(*ref) > 1e-6, f"the unbalance moves the cage by {np.hypot(*ref) * 1e6:.3g} um only")
        for name, phase in (("90", 90.0), ("180", 180.0)):
            d = at[name][-1]
            turn = (np.degrees(np.arctan2(d[1], d[0]) - np.arctan2(ref[1], ref[0])) + 360.0) % 360.0
            ratio = np.hypot(*d) / np.hypot(*ref)
            print(f"phase {phase:g} deg: the added offset {np.hypot(*d) * 1e6:.4f} um (x {ratio:.6f}), turned "
                  f"{turn:.4f} deg")
            check(abs(turn - phase) < 0.01 and abs(ratio - 1.0) < 1e-3,
                  f"phase {phase:g} deg: turned {turn:.4f} deg, length x {ratio:.6f}")


CASES = {"unbalance_phase_run": case_unbalance_phase_run, "pairs_standin3": case_pairs_standin3,
         "pairs_two_parameters": case_pairs_two_parameters,
         "realisations_unbalance_phase": case_realisations_unbalance_phase}
start = time.monotonic()
CASES[CASE]()
print(f"{CASE}: {time.monotonic() - start:.1f} s")
if failures:
    sys.exit(1)
print("PASS")
