"""ParaView export of a run: an XDMF 3 file beside the .h5 (`raceway report --xdmf`).

The XDMF file holds no numbers of its own: it describes, for each output time, where in the .h5
the bodies' positions are (hyperslabs of /balls/position or /rollers/position, /cage/position and the
rings' /position), so ParaView (File > Open, the "Xdmf3 Reader") plays the run as an animation:
one point per rolling element with its inner-race normal force where there is one contact column
per element, and one point each for the cage and ring centres. Planar runs have x, y only
(GeometryType XY, z = 0). The .h5 is referenced by its file name: keep the two side by side.
"""
import os
import xml.etree.ElementTree as ET

import h5py


def _hdf(parent, path, dims, h5name):
    item = ET.SubElement(parent, "DataItem", Dimensions=" ".join(map(str, dims)), NumberType="Float", Precision="8",
                         Format="HDF")
    item.text = f"{h5name}:{path}"
    return item


def _slab(parent, path, full, sample, h5name):
    """Row `sample` of the series `path` of shape `full` ([T x ...]) as a hyperslab."""
    rest = list(full[1:])
    count = [1] + rest
    slab = ET.SubElement(parent, "DataItem", ItemType="HyperSlab", Type="HyperSlab",
                         Dimensions=" ".join(map(str, count)))
    sel = ET.SubElement(slab, "DataItem", Dimensions=f"3 {len(full)}", Format="XML")
    sel.text = " ".join(map(str, [sample] + [0] * len(rest))) + "  " + " ".join(["1"] * len(full)) + "  " + \
        " ".join(map(str, count))
    _hdf(slab, path, full, h5name)
    return slab


def _points(step, name, count, path, shape, sample, h5name):
    grid = ET.SubElement(step, "Grid", Name=name, GridType="Uniform")
    ET.SubElement(grid, "Topology", TopologyType="Polyvertex", NumberOfElements=str(count))
    geometry = ET.SubElement(grid, "Geometry", GeometryType="XYZ" if shape[-1] == 3 else "XY")
    _slab(geometry, path, shape, sample, h5name)
    return grid


def write_xdmf(h5_path, xdmf_path=None, stride=None, max_steps=2000):
    """Writes the XDMF file (default: the .h5's path with .xdmf) and returns its path. Every
    `stride`-th sample is a time step (default: the smallest stride giving at most max_steps, so the
    XML stays a few MB; the .h5 keeps every sample)."""
    if xdmf_path is None:
        base = h5_path[:-len(".partial")] if h5_path.endswith(".partial") else h5_path
        xdmf_path = os.path.splitext(base)[0] + ".xdmf"
    h5name = os.path.relpath(os.path.abspath(h5_path), os.path.dirname(os.path.abspath(xdmf_path)))
    with h5py.File(h5_path, "r") as f:
        elements = "balls" if "balls/position" in f else "rollers"
        shapes = {p: f[p].shape for p in ("balls/position", "rollers/position", "cage/position",
                                          "inner_ring/position", "outer_ring/position") if p in f}
        rows = min(s[0] for s in shapes.values())
        times = f["time"][:rows]
        load_kind = "ball_inner_groove" if elements == "balls" else "roller_inner_race"
        load_path = f"segments/{load_kind}/normal_force"
        n = shapes[f"{elements}/position"][1]
        load_shape = f[load_path].shape if load_path in f and f[load_path].shape[1] == n else None
    if stride is None:
        stride = max(1, -(-rows // max_steps))
    root = ET.Element("Xdmf", Version="3.0")
    domain = ET.SubElement(root, "Domain")
    series = ET.SubElement(domain, "Grid", Name="bearing", GridType="Collection", CollectionType="Temporal")
    for i in range(0, rows, stride):
        step = ET.SubElement(series, "Grid", Name=f"sample_{i}", GridType="Collection", CollectionType="Spatial")
        ET.SubElement(step, "Time", Value=repr(float(times[i])))
        grid = _points(step, elements, n, f"/{elements}/position", shapes[f"{elements}/position"], i, h5name)
        if load_shape:
            att = ET.SubElement(grid, "Attribute", Name="inner_race_normal_force_N", AttributeType="Scalar",
                                Center="Node")
            _slab(att, "/" + load_path, load_shape, i, h5name)
        for body in ("cage", "inner_ring", "outer_ring"):
            if f"{body}/position" in shapes:
                _points(step, body, 1, f"/{body}/position", shapes[f"{body}/position"], i, h5name)
    ET.indent(root)
    tmp = xdmf_path + ".tmp"
    with open(tmp, "w") as fh:
        fh.write('<?xml version="1.0" ?>\n<!DOCTYPE Xdmf SYSTEM "Xdmf.dtd" []>\n')
        fh.write(ET.tostring(root, encoding="unicode"))
        fh.write("\n")
    os.replace(tmp, xdmf_path)
    return xdmf_path
