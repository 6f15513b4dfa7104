#!/usr/bin/env python3
"""docs/output_layout.md against real files: every dataset a run writes is documented with its
shape and units, every documented one is written, /time is the dimension scale of every series,
and the root carries the layout version and the build. The files are read with
io/report/raceway_output.py (the reader users are pointed to).

    output_layout_test.py CASE RACEWAY SOURCE_DIR      CASE: planar, spatial, planar_bridges

Each case runs a short scene (serial, --scheduler-log, so /scheduler is written and checked too).
Exit codes: 0 pass, 1 fail, 77 skipped (h5py or numpy missing).
"""
import os
import re
import subprocess
import sys
import tempfile

try:
    import h5py  # noqa: F401  (the reader needs it)
    import numpy as np  # noqa: F401
except ImportError as err:
    print(f"SKIP: {err}", file=sys.stderr)
    sys.exit(77)

case, raceway, source = sys.argv[1:4]
sys.path.insert(0, os.path.join(source, "io", "report"))
from raceway_output import LAYOUT_VERSION, BUILD_ATTRIBUTES, RacewayOutput  # noqa: E402

failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print(f"FAIL: {what}", file=sys.stderr)


def documented_tables(doc):
    """{section title: [(paths, shape tokens, units)]} of every '| path | shape | units | ...' table."""
    tables, title, rows = {}, None, None
    for line in doc.splitlines():
        if line.startswith("#"):
            title, rows = line.lstrip("#").strip(), None
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")] if line.startswith("|") else None
        if cells and cells[:3] == ["path", "shape", "units"]:
            rows = tables.setdefault(title, [])
        elif cells and rows is not None and not set(cells[0]) <= set("-"):
            paths = re.findall(r"`([^`]+)`", cells[0])
            shape = re.fullmatch(r"`\[(.*)\]`", cells[1])
            check(shape is not None, f"{title}: shape cell '{cells[1]}' is not `[...]`")
            tokens = [t.strip() for t in shape.group(1).split(" x ")] if shape and shape.group(1) else []
            rows.append((paths, tokens, cells[2]))
        elif not cells:
            rows = None
    return tables


def expand(path, f):
    """The file paths a documented path stands for (<body>, <kind>)."""
    out = [path]
    if "<body>" in out[0]:
        out = [p.replace("<body>", b) for p in out for b in ("inner_ring", "outer_ring", "cage")]
    if "<kind>" in path:
        out = [p.replace("<kind>", k) for p in out for k in f.segment_kinds()]
    return out


def shape_matches(tokens, shape, bound, scope):
    """Numbers must match; a symbol binds to one size per file (S: per segment kind)."""
    if len(tokens) != len(shape):
        return False
    for tok, size in zip(tokens, shape):
        if tok.isdigit():
            if int(tok) != size:
                return False
            continue
        key = (tok, scope) if tok == "S" else tok
        if bound.setdefault(key, size) != size:
            return False
    return True


def check_file(path, sections, doc):
    with RacewayOutput(path) as f:
        documented = {}
        for title in sections:
            for paths, tokens, units in documented_tables(doc)[title]:
                for p in paths:
                    for q in expand(p, f):
                        documented[q] = (tokens, units, title)
        in_file = set(f.datasets())
        bound = {"T": len(f["time"])}
        for p in sorted(in_file):
            check(p in documented, f"{path}: {p} is written but not documented")
            if p not in documented:
                continue
            tokens, units, title = documented[p]
            data = f[p]
            shape = (len(data),) if isinstance(data, list) else data.shape
            scope = p.rsplit("/", 1)[0]
            check(shape_matches(tokens, shape, bound, scope),
                  f"{p}: shape {shape} is not the documented [{' x '.join(tokens)}] ({title})")
            check("units" in f.file[p.strip("/")].attrs, f"{p}: no units attribute")
            if not isinstance(data, list):
                check(data.units == units, f"{p}: units '{data.units}', documented '{units}'")
        for p, (tokens, units, title) in documented.items():
            if p.startswith("/scheduler/") and p.rsplit("/", 1)[1] in ("plans", "imbalance"):
                continue  # written only when the scheduler planned or sampled anything
            check(p in in_file, f"{path}: documented {p} ({title}) is not written")
        for p in f.series():
            if p == "/time":
                continue
            scales = f.file[p.strip("/")].dims[0]
            check(len(scales) == 1 and scales[0].name == "/time", f"{p}: /time is not its dimension scale")
        attrs = f.attrs
        check(attrs.get("layout_version") == LAYOUT_VERSION, f"layout_version {attrs.get('layout_version')}")
        for name in BUILD_ATTRIBUTES:
            check(bool(str(attrs.get(name, "")).strip()), f"root attribute {name} missing or empty")
        for name in attrs:
            check(f"`{name}`" in doc, f"root attribute {name} is not documented")
        check(f.summary.get("output_samples") == len(f["time"]), "summary output_samples != rows of /time")


def main():
    doc = open(os.path.join(source, "docs", "output_layout.md"), encoding="utf-8").read()
    scene_file, end, sections = {
        "planar": ("seed002_40hz.toml", "2 ms", ["Planar (roller-bearing) runs"]),
        "spatial": ("6309_R3.toml", "1 ms", ["Spatial (ball-bearing) runs"]),
        "planar_bridges": ("seed003_flexible_bridges.toml", "0.3 ms",
                           ["Planar (roller-bearing) runs",
                            'Flexible cage bridges (planar runs with `[cage] bridges = "flexible"`)']),
    }[case]
    sections.append("Scheduler (`/scheduler`, runs on several ranks or with `--scheduler-log`)")
    tables = documented_tables(doc)
    for title in sections:
        check(title in tables and tables[title], f"docs/output_layout.md has no table under '{title}'")
    if failures:
        return 1
    with tempfile.TemporaryDirectory() as work:
        text = open(os.path.join(source, "jobs", "scenes", scene_file), encoding="utf-8").read()
        scene = os.path.join(work, "scene.toml")
        open(scene, "w", encoding="utf-8").write(re.sub(r"(?m)^end_time = .*$", f'end_time = "{end}"', text))
        out = os.path.join(work, "out.h5")
        run = subprocess.run([raceway, "run", scene, "-o", out, "--scheduler-log"], capture_output=True, text=True,
                             timeout=300)
        check(run.returncode == 0, f"raceway run exit {run.returncode}: {run.stderr[-500:]}")
        if run.returncode == 0:
            check_file(out, sections, doc)
    print(f"{case}: {'passed' if not failures else f'{len(failures)} failure(s)'}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
