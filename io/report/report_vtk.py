"""ParaView/VTK export of a run: a .pvd time series of VTK PolyData files (`raceway report --vtk`).

Beside the XDMF description (report_xdmf.py, which points into the .h5 and needs ParaView's Xdmf3
reader), this writes the bodies' positions as VTK's own XML files, which every VTK build and
ParaView read without further readers: OUT_vtk/OUT.pvd (the collection: one entry per time step)
and OUT_vtk/step_NNNNNN.vtp (one vertex per rolling element, then the cage, the inner ring and the
outer ring centres, in that order). Point data: `body` (0..Z-1 the rolling elements, Z the cage,
Z+1 the inner ring, Z+2 the outer ring) and, where the file has one inner-race contact column per
element, `inner_race_normal_force_N`. Planar runs have z = 0. Positions in m, time in s.

Written by hand (plain ASCII XML, a few dozen lines) rather than through VTK's Python module so
that the report does not need VTK installed; the test reads the files back with VTK.
"""
import os

import h5py
import numpy as np

BODIES = ("cage", "inner_ring", "outer_ring")


def _array(name, values, kind, components=1):
    text = " ".join(repr(float(v)) if kind == "Float64" else str(int(v)) for v in np.ravel(values))
    return (f'<DataArray type="{kind}" Name="{name}" NumberOfComponents="{components}" format="ascii">'
            f"{text}</DataArray>")


def _polydata(points, body, force):
    n = len(points)
    point_data = [_array("body", body, "Int32")]
    if force is not None:
        point_data.append(_array("inner_race_normal_force_N", force, "Float64"))
    return ('<?xml version="1.0"?>\n<VTKFile type="PolyData" version="0.1" byte_order="LittleEndian">\n'
            f'<PolyData><Piece NumberOfPoints="{n}" NumberOfVerts="{n}">\n'
            f'<PointData Scalars="body">{"".join(point_data)}</PointData>\n'
            f'<Points>{_array("position", points, "Float64", 3)}</Points>\n'
            f'<Verts>{_array("connectivity", range(n), "Int64")}{_array("offsets", range(1, n + 1), "Int64")}'
            "</Verts>\n</Piece></PolyData>\n</VTKFile>\n")


def _xyz(rows):
    """[k x 2] or [k x 3] positions as [k x 3] (planar runs: z = 0)."""
    rows = np.atleast_2d(np.asarray(rows, dtype=float))
    return rows if rows.shape[1] == 3 else np.hstack([rows[:, :2], np.zeros((rows.shape[0], 1))])


def write_vtk(h5_path, folder=None, max_steps=200):
    """Writes the .pvd collection and its .vtp files into `folder` (default: OUT_vtk beside the
    .h5) at every stride-th sample (at most max_steps steps); returns the .pvd's path."""
    base = h5_path[:-len(".partial")] if h5_path.endswith(".partial") else h5_path
    stem = os.path.splitext(os.path.basename(base))[0]
    folder = folder or os.path.splitext(base)[0] + "_vtk"
    os.makedirs(folder, exist_ok=True)
    entries = []
    with h5py.File(h5_path, "r") as f:
        elements = "balls" if "balls/position" in f else "rollers"
        series = [f[f"{elements}/position"]] + [f[f"{b}/position"] for b in BODIES if f"{b}/position" in f]
        rows = min(s.shape[0] for s in series)
        count = f[f"{elements}/position"].shape[1]
        load = f.get(f"segments/{'ball_inner_groove' if elements == 'balls' else 'roller_inner_race'}/normal_force")
        load = load if load is not None and load.shape[1] == count else None
        body = np.arange(count + len(series) - 1)
        stride = max(1, -(-rows // max_steps))
        for i in range(0, rows, stride):
            points = np.vstack([_xyz(series[0][i])] + [_xyz(s[i]) for s in series[1:]])
            force = None if load is None else np.concatenate([load[i], np.zeros(len(series) - 1)])
            name = f"step_{i:06d}.vtp"
            with open(os.path.join(folder, name), "w") as fh:
                fh.write(_polydata(points, body, force))
            entries.append(f'<DataSet timestep="{float(f["time"][i])!r}" part="0" file="{name}"/>')
    pvd = os.path.join(folder, stem + ".pvd")
    with open(pvd + ".tmp", "w") as fh:
        fh.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n<Collection>\n'
                 + "\n".join(entries) + "\n</Collection>\n</VTKFile>\n")
    os.replace(pvd + ".tmp", pvd)
    return pvd
