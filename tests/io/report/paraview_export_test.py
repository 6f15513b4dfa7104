#!/usr/bin/env python3
"""The ParaView exports of a real short run, read back with ParaView's own readers.

    paraview_export_test.py SCENE RACEWAY_EXECUTABLE SOURCE_DIR

Runs jobs/scenes/SCENE.toml cut short (`--set scene.end_time=...`, END_TIMES below), then
`raceway report --xdmf --vtk --no-plots`, and checks:
- OUT.xdmf: ParaView picks an Xdmf3 reader for it (its default), which finds every output time of
  the export, and at every time step reads the four bodies with points (the rolling elements, the
  cage, the inner and the outer ring: Z + (64 + 2 Z) + 66 + 66 points, Z rolling elements); at three
  steps (first, middle, last) the rolling elements are /balls|rollers/position at that time
  (exactly), one vertex each, their element_radius_m is the model's, their inner_race_normal_force_N the file's
  inner-race contact columns summed per element, the cage's circle is centred on /cage/position with
  the pitch radius, each ring's race circle on the ring's position with its race radius (planar: the
  model's; spatial: pitch radius -/+ D/2), the rings' marks at their speed's integral and the cage's
  first bar at its angle + pi / Z, and the cells are Z vertices and Z + 5 polylines (the
  cage's circle and Z bars, each ring's circle and mark);
- OUT_vtk/OUT.pvd with ParaView's PVD reader: every time step has the same points, and every .vtp
  file it names, read with VTK's XML PolyData reader, has them with Z vertices and Z + 5
  polylines; the middle step's bodies as above.

Exit codes: 0 pass, 1 fail, 77 skipped (ParaView's Python, python3-paraview, or h5py missing).
ParaView 5.11's Python can crash while it shuts down, so the test leaves through os._exit.
"""
import math
import os
import re
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

try:
    import h5py
    import numpy as np
    from paraview import servermanager, simple
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    from vtkmodules.util.numpy_support import vtk_to_numpy
except ImportError as err:
    print(f"SKIP: {err}: the ParaView read-back needs ParaView's Python (python3-paraview) and h5py; "
          "scripts/bootstrap.sh --tests installs them", file=sys.stderr)
    sys.stderr.flush()
    os._exit(77)

END_TIMES = {"default": "0.04 s", "seed002_40hz": "0.01 s", "6309_R3": "0.01 s", "qj215_validation": "0.01 s",
             "7206B_angular_contact": "0.01 s"}
CIRCLE = 64          # report_bodies.CIRCLE_SEGMENTS
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print(f"FAIL: {what}", file=sys.stderr)


def leaves(data):
    """The datasets of a (nested) composite data set, in order."""
    if data.IsA("vtkMultiBlockDataSet"):
        return [leaf for i in range(data.GetNumberOfBlocks()) for leaf in leaves(data.GetBlock(i))]
    if data.IsA("vtkMultiPieceDataSet"):
        return [leaf for i in range(data.GetNumberOfPieces()) for leaf in leaves(data.GetPiece(i))]
    return [data] if data is not None else []


def array(data, name):
    values = data.GetPointData().GetArray(name)
    return None if values is None else vtk_to_numpy(values)


def points(data):
    return vtk_to_numpy(data.GetPoints().GetData()) if data.GetPoints() else np.zeros((0, 3))


class Expected:
    """What the file says the bodies are at a sample."""

    def __init__(self, h5):
        self.f = h5py.File(h5, "r")
        self.elements = "balls" if "balls/position" in self.f else "rollers"
        self.count = self.f[f"{self.elements}/position"].shape[1]
        self.times = self.f["time"][()]
        model = self.f.attrs["model"]
        model = model.decode() if isinstance(model, bytes) else model
        a = self.f.attrs
        if "element_radius" in a:  # layout 3: the bearing attributes, exact
            self.radius, self.pitch = float(a["element_radius"]), float(a["pitch_radius"])
            self.races = ((self.pitch - self.radius, self.pitch + self.radius) if "balls" == self.elements
                          else (float(a["inner_race_radius"]), float(a["outer_race_radius"])))
        elif "balls" == self.elements:
            self.radius = 0.5e-3 * float(re.search(r"D = ([0-9.eE+-]+) mm", model).group(1))
            self.pitch = float(self.f.attrs["pitch_radius"])
            self.races = (self.pitch - self.radius, self.pitch + self.radius)
        else:
            self.radius = 1e-3 * float(re.search(r"roller radius ([0-9.eE+-]+) mm", model).group(1))
            r_in, r_out = re.search(r"races ([0-9.eE+-]+) / ([0-9.eE+-]+) mm", model).groups()
            self.pitch = 0.5e-3 * (float(r_in) + float(r_out))
            self.races = (1e-3 * float(r_in), 1e-3 * float(r_out))
        self.counts = {"elements": self.count, "cage": CIRCLE + 2 * self.count, "inner_ring": CIRCLE + 2,
                       "outer_ring": CIRCLE + 2}

    def row(self, t):
        k = int(np.argmin(np.abs(self.times - t)))
        check(self.times[k] == t, f"time step {t!r} is an output time of the run")
        return k

    def xyz(self, path, k):
        v = np.asarray(self.f[path][k], dtype=float)
        out = np.zeros(v.shape[:-1] + (3,))
        out[..., :min(3, v.shape[-1])] = v[..., :3]
        return out

    def turned(self, ring, k):
        """The ring's angle about z at sample k: its speed integrated from the first sample."""
        w = np.asarray(self.f[f"{ring}/angular_velocity"][:k + 1], dtype=float)
        w = w[:, 2] if w.ndim == 2 else w
        return float(np.sum(0.5 * (w[1:] + w[:-1]) * np.diff(self.times[:k + 1])))

    def cage_angle(self, k):
        if "cage/angles" in self.f:  # layout 3: [T x 3] spatial, [T] planar
            a = self.f["cage/angles"]
            return float(a[k, 2] if a.ndim == 2 else a[k])
        return float(self.f["cage/angle"][k])

    def load(self, k):
        kind = "ball_inner_groove" if self.elements == "balls" else "roller_inner_race"
        g = self.f[f"segments/{kind}"]
        key = "element" if "element" in g else "ball"  # layout 3 / 2
        owner = g[key][()] if key in g else [int(re.match(r"roller\[(\d+)\]", n).group(1))
                                                    for n in g["names"].asstr()[()]]
        load = np.zeros(self.count)
        for column, e in enumerate(owner):
            load[int(e)] += g["normal_force"][k, column]
        return load


def check_bodies(datasets, e, k, where):
    """The bodies at sample k against the file; the datasets' points are told apart by `body`
    (one block per body from the XDMF, one PolyData of all from the .pvd)."""
    sizes = [d.GetCell(i).GetNumberOfPoints() for d in datasets for i in range(d.GetNumberOfCells())]
    check(sizes.count(1) == e.count and len(sizes) == 2 * e.count + 5,
          f"{where}: {len(sizes)} cells, {sizes.count(1)} vertices (expected {e.count} vertices and {e.count + 5} "
          "polylines)")
    pts = np.vstack([points(d) for d in datasets])
    columns = {name: np.concatenate([array(d, name) for d in datasets])
               for name in ("body", "element_radius_m", "inner_race_normal_force_N")
               if all(array(d, name) is not None for d in datasets)}
    check(len(columns) == 3, f"{where}: point arrays {sorted(columns)}")
    if len(columns) < 3:
        return
    body = columns["body"]
    el = body < e.count
    check(np.array_equal(body[el], np.arange(e.count)), f"{where}: one point per rolling element, in order")
    check(np.array_equal(pts[el], e.xyz(f"{e.elements}/position", k)),
          f"{where}: element centres are /{e.elements}/position at sample {k}")
    check(np.all(columns["element_radius_m"][el] == e.radius), f"{where}: element radius {e.radius} m")
    check(np.allclose(columns["inner_race_normal_force_N"][el], e.load(k), rtol=1e-12, atol=0),
          f"{where}: inner-race normal force per element")
    bodies = (("cage", e.pitch), ("inner_ring", e.races[0]), ("outer_ring", e.races[1]))
    for offset, (name, radius) in enumerate(bodies):
        mine = body == e.count + offset
        check(np.count_nonzero(mine) == e.counts[name], f"{where}: {np.count_nonzero(mine)} points of the {name}")
        circle = pts[mine][:CIRCLE]
        centre = e.xyz(f"{name}/position", k)
        check(np.allclose(circle.mean(axis=0), centre, rtol=0, atol=1e-12 * e.pitch),
              f"{where}: {name} circle centred on /{name}/position {centre}: {circle.mean(axis=0)}")
        r = np.linalg.norm(circle - centre, axis=1)
        check(np.ptp(r) < 1e-9 * e.pitch and math.isclose(r[0], radius, rel_tol=1e-9),
              f"{where}: {name} circle radius {r.min()}..{r.max()} (expected {radius})")
        # The first mark (the ring's, the cage's first bar) turns with the body (in the x-y plane: the
        # tilts, below 1e-2 rad, move it by their square).
        mark = pts[mine][CIRCLE + 1] - pts[mine][CIRCLE]
        angle = e.cage_angle(k) + math.pi / e.count if name == "cage" else e.turned(name, k)
        off = (math.atan2(mark[1], mark[0]) - angle + math.pi) % (2 * math.pi) - math.pi
        check(abs(off) < 1e-4, f"{where}: the {name}'s mark is {off:.3g} rad off its angle {angle:.6g} rad")


def check_xdmf(xdmf, e):
    reader = simple.OpenDataFile(xdmf)
    name = reader.GetXMLName()
    check(name.startswith("Xdmf3"), f"ParaView's default reader for {xdmf} is {name}, not an Xdmf3 reader")
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues)
    with h5py.File(xdmf[:-len(".xdmf")] + "_xdmf.h5", "r") as heavy:
        check(times == list(heavy["time"][()]), f"{name}: {len(times)} time steps, the export's /time")
    check(len(times) > 1, f"{name}: {len(times)} time steps")
    total = sum(e.counts.values())
    empty = []
    for t in times:
        reader.UpdatePipeline(t)
        if reader.GetDataInformation().GetNumberOfPoints() != total:
            empty.append(t)
    check(not empty, f"{name}: {len(empty)} of {len(times)} steps without the {total} points, first {empty[:3]}")
    for t in (times[0], times[len(times) // 2], times[-1]):
        reader.UpdatePipeline(t)
        check_bodies(leaves(servermanager.Fetch(reader)), e, e.row(t), f"{name} at t = {t:.6g} s")
    print(f"{name}: {len(times)} time steps of {total} points read", file=sys.stderr)
    simple.Delete(reader)


def check_pvd(pvd, e):
    reader = simple.OpenDataFile(pvd)
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues)
    total = sum(e.counts.values())
    empty = []
    for t in times:
        reader.UpdatePipeline(t)
        if reader.GetDataInformation().GetNumberOfPoints() != total:
            empty.append(t)
    check(len(times) > 1 and not empty,
          f"{reader.GetXMLName()}: {len(times)} steps, {len(empty)} without {total} points")
    t = times[len(times) // 2]
    reader.UpdatePipeline(t)
    check_bodies(leaves(servermanager.Fetch(reader)), e, e.row(t), f"{reader.GetXMLName()} at t = {t:.6g} s")
    entries = ET.parse(pvd).getroot().findall("./Collection/DataSet")
    check(len(entries) == len(times), f"{pvd}: {len(entries)} files for {len(times)} steps")
    vtp = vtkXMLPolyDataReader()
    bad = []
    for entry in entries:
        vtp.SetFileName(os.path.join(os.path.dirname(pvd), entry.get("file")))
        vtp.Update()
        data = vtp.GetOutput()
        shape = (data.GetNumberOfPoints(), data.GetNumberOfVerts(), data.GetNumberOfLines())
        if shape != (total, e.count, e.count + 5):
            bad.append(entry.get("file"))
    check(not bad, f"{len(bad)} .vtp files without {total} points, {e.count} vertices, {e.count + 5} lines: "
          f"{bad[:3]}")
    print(f"{reader.GetXMLName()}: {len(times)} time steps, {len(entries)} .vtp files of {total} points",
          file=sys.stderr)


def main():
    scene, raceway, source = sys.argv[1:4]
    with tempfile.TemporaryDirectory(prefix=f"raceway_paraview_{scene}.") as work:
        h5 = os.path.join(work, scene + ".h5")
        # The segment diagnostics at every sample (6309 R3 ships them at every 5th): the frames' ball
        # loads are read at the frames' samples.
        r = subprocess.run([raceway, "run", os.path.join(source, "jobs", "scenes", scene + ".toml"), "-o", h5,
                            "--set", f"scene.end_time={END_TIMES[scene]}", "--set", "output.segment_every=1"],
                           capture_output=True, text=True, timeout=600)
        check(r.returncode == 0, f"run: exit code {r.returncode}: {r.stderr[-2000:]}")
        if r.returncode:
            return 1
        r = subprocess.run([raceway, "report", h5, "--xdmf", "--vtk", "--no-plots"], capture_output=True, text=True,
                           timeout=600)
        check(r.returncode == 0, f"report: exit code {r.returncode}: {r.stderr[-3000:]}")
        if r.returncode:
            return 1
        e = Expected(h5)
        check_xdmf(os.path.join(work, scene + ".xdmf"), e)
        check_pvd(os.path.join(work, scene + "_vtk", scene + ".pvd"), e)
        e.f.close()
    return 1 if failures else 0


if __name__ == "__main__":
    code = main()
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)
