#!/usr/bin/python3
"""The scene check reads its quantities by meaning, not by one spelling: a run's output with its
series renamed the ways the layout has spelled them (the planar `/cage/angle` as the spatial
`/cage/angles`, a name with a suffix) gives the same quantities as the file as written, and a
series that is gone is reported missing, not passed.

    renamed_datasets_test.py RACEWAY SOURCE_DIR
"""
import json
import os
import shutil
import sys
import tempfile

raceway, source_dir = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(source_dir, "scripts"))
import scene_answers  # noqa: E402 (exits 77 without numpy and h5py)
import h5py  # noqa: E402

failures = 0


def check(condition, message):
    global failures
    if not condition:
        print(f"FAIL: {message}")
        failures += 1


with tempfile.TemporaryDirectory(prefix="renamed_datasets.") as work:
    scene = os.path.join(source_dir, "jobs", "scenes", "default.toml")
    summary, output = scene_answers.run_scene(raceway, scene, ["scene.end_time=2 ms"], work)
    written = scene_answers.quantities(summary, output)
    check("last.cage.rotation" in written, "the planar run's cage rotation not found")
    with h5py.File(output, "r") as f:
        written_name = "cage/angles" if "cage/angles" in f else "cage/angle"  # layout 3 / 2
    for new_name in ("cage/angle", "cage/angles_about_z"):
        renamed = os.path.join(work, "renamed.h5")
        shutil.copy(output, renamed)
        with h5py.File(renamed, "r+") as f:
            f.move(written_name, new_name)
        read = scene_answers.quantities(summary, renamed)
        differing = sorted(n for n in set(read) | set(written) if read.get(n) != written.get(n))
        check(not differing, f"/{written_name} renamed {new_name}: these quantities differ or are missing: {differing}")
    with h5py.File(renamed, "r+") as f:
        del f[new_name]
    answer = {"quantities": {n: {"value": v, "class": c, "rel": 0.0, "abs": 0.0} for n, (v, c) in written.items()}}
    rows, missing = scene_answers.compare(answer, scene_answers.quantities(summary, renamed), verbose=False)
    check(missing == 1 and rows[0][0] == "last.cage.rotation" and rows[0][3] == "missing",
          f"a removed series is not reported missing: {rows}")
    print(json.dumps({n: v for n, (v, _) in written.items() if n == "last.cage.rotation"}))
if failures:
    sys.exit(1)
print("renamed_datasets: passed")
