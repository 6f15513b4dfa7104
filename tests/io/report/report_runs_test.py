#!/usr/bin/env python3
"""`raceway report` on real short runs of every bearing kind, one scene per ctest.

    report_runs_test.py SCENE RACEWAY_EXECUTABLE SOURCE_DIR [--screenshot]

Runs jobs/scenes/SCENE.toml cut short (END_TIMES below), then `raceway report --xdmf --vtk` and checks:
- the page, the figures (PNG, at least 1200 px wide) and summary.json exist; the page embeds every
  figure and names the scene; none of these runs (ball, planar roller) has a roller section;
- summary.json's numbers against values this test computes from the output file itself through the
  reader (the raceway package) and against the run's own summary (summary_json, written by the C++
  run loop): the cage speed window mean, the kinematic speed (spatial: /cage/rolling_speed mean;
  planar: the run's epicyclic speed), one slip in the run's last line, its summary and the report
  (at the loaded contact angle), the largest rolling-element load's window mean, the pocket
  impact count (every run of samples above the contact threshold on one bar of one pocket), the
  cage-land force mean;
- the XDMF file, with h5py (ParaView reads it in paraview_export_test.py): it parses, every HDF
  DataItem names a dataset of OUT_xdmf.h5 with its shape, the time steps are output times, and the
  rolling elements' geometry at the middle step is their position there;
- the VTK export's XML: every .vtp the .pvd names exists, and the middle step's first points are
  the rolling elements' positions at that time; for 6309_R3, a copy of the file without its
  'model' attribute (the ball diameter; the report alone does not need it) is refused with exit
  code 2 before anything is written;
- for 6309_R3 also the animation (the report script directly, 12 frames, MP4 through ffmpeg or GIF).
With --screenshot only the run, the report and a headless chromium screenshot of the page (1600 px
wide); skipped when chromium (a test package) is not installed.

Exit codes: 0 pass, 1 fail, 77 skipped (numpy, h5py or matplotlib missing; chromium with --screenshot).
"""
import json
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

try:
    import h5py
    import numpy as np
    import matplotlib  # noqa: F401
except ImportError as err:
    print(f"SKIP: {err}", file=sys.stderr)
    sys.exit(77)

END_TIMES = {"default": "0.04 s", "seed002_40hz": "0.02 s", "6309_R3": "0.02 s", "qj215_validation": "0.03 s",
             "7206B_angular_contact": "0.02 s"}
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print(f"FAIL: {what}", file=sys.stderr)


def near(value, expected, rel, what, abs_tol=0.0):
    ok = value is not None and math.isfinite(value) and abs(value - expected) <= rel * abs(expected) + abs_tol
    check(ok, f"{what}: {value} not within {rel:g} (rel) of {expected}")


def png_width(path):
    with open(path, "rb") as fh:
        head = fh.read(24)
    return struct.unpack(">I", head[16:20])[0] if head[:8] == b"\x89PNG\r\n\x1a\n" else 0


def runs_above(force, threshold):
    on = np.concatenate([[False], force > threshold, [False]])
    return int(np.count_nonzero(on[1:] & ~on[:-1]))


def expected_from_file(out, window_start):
    """What the report should say, computed here from the file's datasets."""
    t = np.asarray(out["time"])
    w = t >= window_start - 1e-9 * (t[-1] - t[0])
    spatial = out.attrs.get("model_kind") == "spatial"
    cage = np.asarray(out["cage/angular_velocity"])
    cage = cage[:, 2] if spatial else cage
    e = {"cage_mean": float(np.mean(cage[w])), "samples": int(np.count_nonzero(w))}
    if spatial:
        e["rolling_mean"] = float(np.mean(np.asarray(out["cage/rolling_speed"])[w]))
        g = out.segments("ball_inner_groove")
        balls = np.asarray(g["element"], dtype=int)
        n = int(balls.max()) + 1
        load = np.zeros((len(t), n))
        for c, k in enumerate(balls):
            load[:, k] += g["normal_force"][:, c]
        p = out.segments("ball_pocket")
        direction = -1 if e["cage_mean"] < 0 else 1
        front, rear = np.zeros((len(t), n)), np.zeros((len(t), n))
        for c, k in enumerate(np.asarray(p["element"], dtype=int)):
            fn, fc = p["normal_force"][:, c], p["circumferential_force"][:, c]
            front[:, k] += np.where((fn > 0) & (fc * direction < 0), fn, 0.0)
            rear[:, k] += np.where((fn > 0) & (fc * direction >= 0), fn, 0.0)
    else:
        load = np.asarray(out["segments/roller_inner_race/normal_force"])
        front = np.asarray(out["segments/cage_bar_front/normal_force"])
        rear = np.asarray(out["segments/cage_bar_rear/normal_force"])
    e["largest_load_mean"] = float(np.mean(np.max(load[w], axis=1)))
    e["bars"] = (front, rear)
    if "segments/cage_land/normal_force" in out:
        land = np.sum(np.asarray(out["segments/cage_land/normal_force"]), axis=1)
        tw = t[w]
        e["land_mean"] = float(np.trapz(land[w], tw) / (tw[-1] - tw[0]))
    return e


def check_summary(s, h5, element):
    sys.path.insert(0, os.path.join(SOURCE, "io", "report"))
    from raceway import RacewayOutput
    with RacewayOutput(h5) as out:
        run_summary = out.summary
        e = expected_from_file(out, s["window"]["start_s"])
        spatial = out.attrs.get("model_kind") == "spatial"
    near(s["window"]["samples"], e["samples"], 0, "window samples")
    cs = s["cage_speed"]
    near(cs["mean_rad_s"], e["cage_mean"], 1e-12, "cage speed window mean")
    near(cs["mean_rpm"], run_summary["cage_speed_rpm"], 1e-9, "cage speed against the run's own summary")
    # One slip definition: the run's summary (and its last line) and the report, at the loaded angle.
    slip = cs["slip"]
    near(run_summary["cage_slip"], slip, 1e-9, "the run summary's cage_slip against the report's", 1e-12)
    near(run_summary["rolling_cage_speed_rpm"], cs.get("rolling_rpm", cs["epicyclic_rpm"]), 1e-9,
         "the run summary's kinematic speed at the loaded angle against the report's")
    if spatial:
        near(cs["rolling_rad_s"], e["rolling_mean"], 1e-12, "kinematic speed at the loaded contact angle")
        near(cs["slip"], 1 - e["cage_mean"] / e["rolling_mean"], 1e-9, "slip at the loaded angle", 1e-12)
    else:
        near(cs["epicyclic_rpm"], run_summary["epicyclic_cage_speed_rpm"], 1e-6, "planar epicyclic speed against the "
             "run's own summary")
    near(s[f"{element}_load"]["largest_mean_n"], e["largest_load_mean"], 1e-12, "largest element load window mean")
    check(s[f"{element}_load"]["max_n"] >= s[f"{element}_load"]["largest_mean_n"], "peak load >= its mean")
    p = s["pocket_forces"]
    front, rear = e["bars"]
    if cs["direction"] < 0 and not spatial:
        front, rear = rear, front
    count = sum(runs_above(f[:, k], p["threshold_n"]) for f in (front, rear) for k in range(f.shape[1]))
    check(p["impacts"]["count"] == count, f"impact count {p['impacts']['count']}, the file has {count}")
    check(len(p["impacts"]["time_s"]) == count, "one impact time per impact")
    if "land_mean" in e:
        near(s["cage_land"]["force_mean_n"], e["land_mean"], 1e-9, "cage-land force window mean", 1e-12)
    return count


def check_xdmf(xdmf, h5):
    """The XDMF file's structure with h5py alone (ParaView reads it in paraview_export_test.py):
    every HDF DataItem names a dataset of OUT_xdmf.h5 with its shape, the time steps are output
    times, and the rolling elements' geometry at the middle step is their position there."""
    root = ET.parse(xdmf).getroot()
    steps = root.findall("./Domain/Grid/Grid")
    check(len(steps) > 1, f"{xdmf}: {len(steps)} time steps")
    heavy_name = os.path.basename(xdmf)[:-len(".xdmf")] + "_xdmf.h5"
    with h5py.File(h5, "r") as f, h5py.File(os.path.join(os.path.dirname(xdmf), heavy_name), "r") as heavy:
        times = [float(s.find("Time").get("Value")) for s in steps]
        check(set(times) <= set(f["time"][()].tolist()), "XDMF times are output times of the run")
        check(times == sorted(times) and times == heavy["time"][()].tolist(), "XDMF times are the export's /time")
        for item in root.iter("DataItem"):
            name, path = item.text.strip().split(":")
            dims = tuple(int(v) for v in item.get("Dimensions").split())
            check(name == heavy_name and path in heavy and heavy[path].shape == dims,
                  f"XDMF: {name}:{path} {dims} is not in {heavy_name}")
        elements = "balls" if "balls/position" in f else "rollers"
        k = len(steps) // 2
        grid = [g for g in steps[k].findall("Grid") if g.get("Name") == elements][0]
        xyz = heavy[grid.find("Geometry/DataItem").text.split(":")[1]][()]
        sample = int(np.searchsorted(f["time"][()], times[k]))
        position = f[f"{elements}/position"][sample]
        check(np.array_equal(xyz[:, :position.shape[1]], position), "element centres through the XDMF")


def check_vtk(pvd, h5):
    """The VTK export's structure (ParaView reads it in paraview_export_test.py): one .vtp per
    step, the rolling elements first, at the middle step their positions there."""
    entries = ET.parse(pvd).getroot().findall("./Collection/DataSet")
    check(len(entries) > 1, f"{pvd}: {len(entries)} time steps")
    check(all(os.path.isfile(os.path.join(os.path.dirname(pvd), e.get("file"))) for e in entries),
          "every .vtp the .pvd names exists")
    entry = entries[len(entries) // 2]
    piece = ET.parse(os.path.join(os.path.dirname(pvd), entry.get("file"))).getroot().find("./PolyData/Piece")
    xyz = np.array(piece.find("Points/DataArray").text.split(), dtype=float).reshape(-1, 3)
    with h5py.File(h5, "r") as f:
        elements = "balls" if "balls/position" in f else "rollers"
        position = f[f"{elements}/position"][int(np.searchsorted(f["time"][()], float(entry.get("timestep"))))]
    check(np.array_equal(xyz[:len(position), :position.shape[1]], position), "element centres through the .vtp")


def check_export_refusal(h5, raceway, work):
    """A file the exports cannot draw (neither the bearing attributes nor the 'model' description to
    take the radii from): exit 2 naming the file and the attribute, before anything is written."""
    bad = os.path.join(work, "no_model.h5")
    shutil.copy(h5, bad)
    with h5py.File(bad, "a") as f:
        for name in ("model", "element_radius"):
            if name in f.attrs:
                del f.attrs[name]
    r = subprocess.run([raceway, "report", bad, "--xdmf", "--vtk", "--no-plots"], capture_output=True, text=True,
                       timeout=600)
    written = [n for n in os.listdir(work) if n.startswith("no_model") and n != "no_model.h5"]
    check(r.returncode == 2 and bad in r.stderr and "'model'" in r.stderr and not written,
          f"export of a file without 'model': exit {r.returncode}, wrote {written}: {r.stderr[-500:]}")


def browser():
    return shutil.which("chromium") or shutil.which("chromium-browser")


def screenshot(page, work):
    png = os.path.join(work, "page.png")
    # Flags for a closed network: no background connections, a fresh profile.
    subprocess.run([browser(), "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                    "--disable-background-networking", "--disable-component-update", "--disable-sync",
                    f"--user-data-dir={os.path.join(work, 'chromium-profile')}", f"--screenshot={png}",
                    "--window-size=1600,3000", "file://" + os.path.abspath(page)], capture_output=True, timeout=120)
    check(os.path.isfile(png) and png_width(png) == 1600, "headless chromium screenshot of the page")
    if os.path.isfile(png):
        print(f"page screenshot: {png_width(png)} px wide, {os.path.getsize(png)} bytes", file=sys.stderr)


def main():
    global SOURCE
    scene, raceway, SOURCE = sys.argv[1:4]
    page_only = sys.argv[4:] == ["--screenshot"]
    if page_only and not browser():
        print("SKIP: chromium is not installed (a test package: scripts/bootstrap.sh --tests installs it); "
              "the page screenshot needs it", file=sys.stderr)
        return 77
    with open(os.path.join(SOURCE, "jobs", "scenes", scene + ".toml")) as fh:
        text = re.sub(r'^end_time = .*$', f'end_time = "{END_TIMES[scene]}"', fh.read(), count=1, flags=re.M)
    with tempfile.TemporaryDirectory(prefix=f"raceway_report_{scene}.") as work:
        toml, h5 = os.path.join(work, scene + ".toml"), os.path.join(work, scene + ".h5")
        with open(toml, "w") as fh:
            fh.write(text)
        # The segment diagnostics at every sample (6309 R3 ships them at every 5th): the expected
        # values below put the ball loads and pocket forces beside /time.
        r = subprocess.run([raceway, "run", toml, "-o", h5, "--set", "output.segment_every=1"], capture_output=True,
                           text=True, timeout=600)
        check(r.returncode == 0, f"run: exit code {r.returncode}: {r.stderr[-2000:]}")
        if r.returncode:
            return 1
        run_line = re.search(r"slip (-?[0-9.]+) %", r.stderr)
        exports = [] if page_only else ["--xdmf", "--vtk"]
        r = subprocess.run([raceway, "report", h5] + exports, capture_output=True, text=True, timeout=600)
        check(r.returncode == 0, f"report: exit code {r.returncode}: {r.stderr[-3000:]}")
        folder = os.path.join(work, scene + "_report")
        if page_only:
            screenshot(os.path.join(folder, "report.html"), work)
            return 1 if failures else 0
        with open(os.path.join(folder, "summary.json")) as fh:
            s = json.load(fh)
        element = s["rolling_element"]
        pngs = sorted(n for n in os.listdir(folder) if n.endswith(".png"))
        for png in ["cage_speed.png", "cage_centroid.png", f"{element}_load_azimuth.png", "pocket_force_time.png"]:
            check(png in pngs, f"{png} written")
        for png in pngs:
            check(png_width(os.path.join(folder, png)) >= 1200, f"{png} is {png_width(os.path.join(folder, png))} px wide")
        with open(os.path.join(folder, "report.html"), encoding="utf-8") as fh:
            page = fh.read()
        check(page.count("data:image/png;base64,") == len(pngs), "the page embeds every figure")
        check(s["scene_name"] in page and "<pre>" in page, "the page names the scene and holds its text")
        # Ball and planar runs have no roller section (only spatial roller runs do: report_rollers_test.py).
        check("rollers" not in s and "Rollers: slices" not in page and "slice_load_heatmap.png" not in pngs,
              "no roller section, figure or page rows for a ball or planar run")
        impacts = check_summary(s, h5, element)
        slip = s["cage_speed"]["slip"]
        check(run_line is not None and abs(float(run_line.group(1)) - 100 * slip) <= 0.0005 + 1e-9,
              f"the run's last line says slip {run_line.group(1) if run_line else '?'} %, the report "
              f"{100 * slip:.4f} %")
        check_xdmf(os.path.join(work, scene + ".xdmf"), h5)
        check_vtk(os.path.join(work, scene + "_vtk", scene + ".pvd"), h5)
        if scene == "6309_R3":
            check_export_refusal(h5, raceway, work)
        print(f"{scene}: {len(pngs)} figures, cage {s['cage_speed']['mean_rpm']:.3f} rpm, {impacts} impacts",
              file=sys.stderr)
        if scene == "6309_R3":
            script = os.path.join(SOURCE, "io", "report", "raceway_report.py")
            r = subprocess.run([sys.executable, script, h5, "--animate", "--animation-frames", "12", "-o", folder],
                               capture_output=True, text=True, timeout=600)
            videos = [n for n in os.listdir(folder) if n.startswith("cage.")]
            check(r.returncode == 0 and len(videos) == 1, f"animation: {r.returncode} {videos} {r.stderr[-2000:]}")
            if videos and videos[0].endswith(".mp4"):
                probe = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0",
                                        "-show_entries", "stream=nb_read_frames", "-of", "csv=p=0",
                                        os.path.join(folder, videos[0])], capture_output=True, text=True)
                check(probe.stdout.strip() == "12", f"animation has {probe.stdout.strip()} frames, expected 12")
            if videos and videos[0].endswith(".gif"):
                from PIL import Image
                with Image.open(os.path.join(folder, videos[0])) as im:
                    check(im.n_frames == 12, f"animation has {im.n_frames} frames, expected 12")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
