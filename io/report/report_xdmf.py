"""ParaView export of a run: OUT.xdmf and its data OUT_xdmf.h5 beside the .h5 (`raceway report --xdmf`).

ParaView opens OUT.xdmf with its default XDMF reader (Xdmf3) and plays the run: at each time step
a block per body (report_bodies.py): the rolling elements as points with `element_radius_m` (draw
them with the Glyph filter, sphere, scale array element_radius_m, scale factor 2) and
`inner_race_normal_force_N`; the cage (pitch circle and bars) and the inner and outer ring (race
circle and a mark) as polylines that move, tilt and turn with their bodies. Every point has `body`.
The legacy "XDMF Reader" reads it too. Keep the two files side by side (the .xdmf names the data
file by its name alone).

Layout of OUT_xdmf.h5: /time [S] (s); per body (rollers or balls, cage, inner_ring, outer_ring)
/BODY/cells (the Mixed topology, the same at every step: 1 1 k for a vertex, 2 N i0 .. iN-1 for a
polyline) and, for `points` ([m x 3], m) and each point array ([m]), either /BODY/NAME/SAMPLE (one
dataset per time step, SAMPLE the 7-digit row of the run's series) where it changes, or /BODY/NAME
where it is the same at every step.

Why the XML is written here and not by a library: the maintained writers at hand each fail this
file. VTK's vtkXdmf3Writer (in ParaView's Python) rewrites the whole XML after every block of every
step, so its cost grows with the square of the steps (400 steps of one small block: 46 s; 2,000:
about 20 min); VTK's older vtkXdmfWriter writes polylines without NodesPerElement, which the Xdmf3
reader rejects, and time steps as "Tree" collections, which it reads with 0 points; Debian 12's
python3-xdmf does not import (undefined symbol XdmfUnstructuredGridCast); meshio's XDMF time series
keeps one mesh for all steps, and these bodies move. The XML below follows what vtkXdmf3Writer
writes (Mixed topology, XYZ geometry, a Time on every grid, one heavy dataset per step and array:
the Xdmf3 reader of ParaView 5.11 reads hyperslabs of one big dataset as 0 points), and
tests/io/report/paraview_export_test.py reads every step back with ParaView's default reader.
"""
import os
import xml.etree.ElementTree as ET

import h5py

from report_bodies import read_bodies

# Xdmf's Mixed topology codes (XdmfTopologyType: Polyvertex 0x1, Polyline 0x2).
XDMF_POLYVERTEX, XDMF_POLYLINE = 1, 2


def mixed_cells(cells):
    """The Mixed topology list of polyline cells (a one-point cell is a vertex)."""
    out = []
    for cell in cells:
        out += [XDMF_POLYVERTEX, 1, cell[0]] if len(cell) == 1 else [XDMF_POLYLINE, len(cell)] + list(cell)
    return out


def _data_item(parent, dims, text, number_type="Float", precision=8, fmt="HDF"):
    item = ET.SubElement(parent, "DataItem", Dimensions=" ".join(map(str, dims)), NumberType=number_type,
                         Precision=str(precision), Format=fmt)
    item.text = text
    return item


def _per_step(values):
    """Whether the [S x ...] array changes between steps (else one dataset serves every step)."""
    return values.shape[0] > 1 and not (values == values[:1]).all()


def _sample_name(row):
    return f"{row:07d}"


def _write_heavy(path, bodies):
    with h5py.File(path, "w") as f:
        f.create_dataset("time", data=bodies.times)
        f["time"].attrs["units"] = "s"
        for body in bodies.bodies:
            g = f.create_group(body.name)
            g.create_dataset("cells", data=mixed_cells(body.cells), dtype="i8")
            for name, values in [("points", body.points)] + list(body.point_data.items()):
                if _per_step(values):
                    group = g.create_group(name)
                    for row, v in zip(bodies.samples, values):
                        group.create_dataset(_sample_name(row), data=v)
                else:
                    g.create_dataset(name, data=values[0])


def _where(heavy, body, name, varying, row):
    """The HDF reference of `name` of `body` at sample `row` (see _write_heavy)."""
    return f"{heavy}:/{body}/{name}/{_sample_name(row)}" if varying else f"{heavy}:/{body}/{name}"


def _xml(bodies, heavy):
    root = ET.Element("Xdmf", Version="3.0")
    domain = ET.SubElement(root, "Domain")
    series = ET.SubElement(domain, "Grid", Name="bearing", GridType="Collection", CollectionType="Temporal")
    varying = {(body.name, name): _per_step(values) for body in bodies.bodies
               for name, values in [("points", body.points)] + list(body.point_data.items())}
    topology_size = {body.name: len(mixed_cells(body.cells)) for body in bodies.bodies}
    for row, t in zip(bodies.samples, bodies.times):
        step = ET.SubElement(series, "Grid", Name=f"sample_{row}", GridType="Collection", CollectionType="Spatial")
        ET.SubElement(step, "Time", Value=repr(float(t)))
        for body in bodies.bodies:
            grid = ET.SubElement(step, "Grid", Name=body.name, GridType="Uniform")
            ET.SubElement(grid, "Time", Value=repr(float(t)))
            topology = ET.SubElement(grid, "Topology", TopologyType="Mixed", NumberOfElements=str(len(body.cells)))
            _data_item(topology, (topology_size[body.name],), f"{heavy}:/{body.name}/cells", "Int", 8)
            geometry = ET.SubElement(grid, "Geometry", GeometryType="XYZ")
            where = _where(heavy, body.name, "points", varying[body.name, "points"], row)
            _data_item(geometry, body.points.shape[1:], where)
            for name, values in body.point_data.items():
                attribute = ET.SubElement(grid, "Attribute", Name=name, AttributeType="Scalar", Center="Node")
                _data_item(attribute, values.shape[1:], _where(heavy, body.name, name, varying[body.name, name], row))
    ET.indent(root)
    return root


def data_path(xdmf_path):
    """The data file beside OUT.xdmf: OUT_xdmf.h5."""
    return os.path.splitext(xdmf_path)[0] + "_xdmf.h5"


def write_xdmf(h5_path, xdmf_path=None, max_steps=2000):
    """Writes OUT.xdmf (default: the .h5's path with .xdmf) and OUT_xdmf.h5 at every stride-th sample
    (the smallest stride giving at most max_steps steps; the run's .h5 keeps every sample) and returns
    the .xdmf's path."""
    if xdmf_path is None:
        base = h5_path[:-len(".partial")] if h5_path.endswith(".partial") else h5_path
        xdmf_path = os.path.splitext(base)[0] + ".xdmf"
    heavy_path = data_path(xdmf_path)
    if os.path.abspath(heavy_path) == os.path.abspath(h5_path):
        raise ValueError(f"{xdmf_path}: its data file would be the run's own file {h5_path}; choose another name")
    bodies = read_bodies(h5_path, max_steps)
    _write_heavy(heavy_path + ".tmp", bodies)
    os.replace(heavy_path + ".tmp", heavy_path)
    root = _xml(bodies, os.path.basename(heavy_path))
    with open(xdmf_path + ".tmp", "w") as fh:
        fh.write('<?xml version="1.0" ?>\n')
        fh.write(ET.tostring(root, encoding="unicode"))
        fh.write("\n")
    os.replace(xdmf_path + ".tmp", xdmf_path)
    return xdmf_path
