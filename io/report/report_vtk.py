"""ParaView/VTK export of a run: a .pvd time series of VTK PolyData files (`raceway report --vtk`).

The same bodies as the XDMF export (report_bodies.py), as VTK's own XML files, which ParaView and
every VTK build read without further readers: OUT_vtk/OUT.pvd (the collection: one entry per time
step) and OUT_vtk/step_NNNNNN.vtp, one PolyData per step: a vertex per rolling element (its centre),
then the polylines of the cage (pitch circle and bars), the inner ring and the outer ring (race
circle and a mark). Point data: `body` (0..Z-1 the rolling elements, Z the cage, Z+1 the inner
ring, Z+2 the outer ring), `element_radius_m` (the rolling element's radius, 0 on the polylines: the
Glyph filter scaled by it draws the elements at size) and `inner_race_normal_force_N`. Planar runs
have z = 0. Positions in m, time in s.

Written by hand (plain ASCII XML, a few dozen lines) rather than through VTK's Python module so
that `raceway report --vtk` needs no VTK installed (VTK's Python is hundreds of MB); the tests read
the files back with ParaView's readers.
"""
import os

import numpy as np

from report_bodies import read_bodies


def _array(name, values, kind, components=1):
    text = " ".join(repr(float(v)) if kind == "Float64" else str(int(v)) for v in np.ravel(values))
    return (f'<DataArray type="{kind}" Name="{name}" NumberOfComponents="{components}" format="ascii">'
            f"{text}</DataArray>")


def _cells(cells):
    """connectivity and offsets of VTK cells from lists of point indices."""
    connectivity = [i for cell in cells for i in cell]
    offsets = np.cumsum([len(cell) for cell in cells])
    return _array("connectivity", connectivity, "Int64") + _array("offsets", offsets, "Int64")


def _polydata(points, point_data, verts, lines):
    arrays = "".join(_array(name, values, "Float64") for name, values in point_data.items())
    return ('<?xml version="1.0"?>\n<VTKFile type="PolyData" version="0.1" byte_order="LittleEndian">\n'
            f'<PolyData><Piece NumberOfPoints="{len(points)}" NumberOfVerts="{len(verts)}" '
            f'NumberOfLines="{len(lines)}">\n'
            f'<PointData Scalars="body">{arrays}</PointData>\n'
            f'<Points>{_array("position", points, "Float64", 3)}</Points>\n'
            f"<Verts>{_cells(verts)}</Verts>\n<Lines>{_cells(lines)}</Lines>\n"
            "</Piece></PolyData>\n</VTKFile>\n")


def write_vtk(h5_path, folder=None, max_steps=200):
    """Writes the .pvd collection and its .vtp files into `folder` (default: OUT_vtk beside the
    .h5) at every stride-th sample (at most max_steps steps); returns the .pvd's path."""
    base = h5_path[:-len(".partial")] if h5_path.endswith(".partial") else h5_path
    stem = os.path.splitext(os.path.basename(base))[0]
    folder = folder or os.path.splitext(base)[0] + "_vtk"
    bodies = read_bodies(h5_path, max_steps)
    os.makedirs(folder, exist_ok=True)
    # One point list for all bodies: each body's cell indices shifted by the points before it.
    verts, lines, first = [], [], 0
    for body in bodies.bodies:
        for cell in body.cells:
            (verts if len(cell) == 1 else lines).append([first + i for i in cell])
        first += body.points.shape[1]
    names = list(bodies.bodies[0].point_data)
    entries = []
    for s, (row, t) in enumerate(zip(bodies.samples, bodies.times)):
        points = np.vstack([body.points[s] for body in bodies.bodies])
        data = {name: np.concatenate([body.point_data[name][s] for body in bodies.bodies]) for name in names}
        name = f"step_{row:06d}.vtp"
        with open(os.path.join(folder, name), "w") as fh:
            fh.write(_polydata(points, data, verts, lines))
        entries.append(f'<DataSet timestep="{float(t)!r}" part="0" file="{name}"/>')
    pvd = os.path.join(folder, stem + ".pvd")
    with open(pvd + ".tmp", "w") as fh:
        fh.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n<Collection>\n'
                 + "\n".join(entries) + "\n</Collection>\n</VTKFile>\n")
    os.replace(pvd + ".tmp", pvd)
    return pvd
