#!/usr/bin/env python3
"""docs/output_layout.md against real files: every dataset a run writes is documented with its
shape and units, every documented one is written, /time is the dimension scale of every series,
and the root carries the layout version, the build and the bearing attributes. The files are read
with the raceway package (io/report/raceway, the reader users are pointed to).

    output_layout_test.py CASE RACEWAY SOURCE_DIR [BUILD_DIR]
        CASE: planar, spatial, spatial_rollers, planar_bridges, thermal   one run each against the documented tables
              shared_names                      a planar and a spatial run speak one dialect
              previous                          the committed layout version 2 files
                                                (tests/system/run/layout_v2) read under version 3's names
              package                           `import raceway` from the build tree and from an
                                                installation (cmake --install into a temporary
                                                prefix), its table and pandas view

The run cases run a short scene (serial, --scheduler-log, so /scheduler is written and checked too).
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
source = os.path.abspath(source)
build = os.path.abspath(sys.argv[4]) if len(sys.argv) > 4 else ""
sys.path.insert(0, os.path.join(source, "io", "report"))
from raceway import BEARING_ATTRIBUTES, BUILD_ATTRIBUTES, LAYOUT_VERSION, RacewayOutput  # noqa: E402

#: Bearing attributes of one kind of bearing only.
ROLLER_ONLY, BALL_ONLY = {"roller_length"}, {"inner_groove_radius", "outer_groove_radius"}

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
        # A spatial roller run writes the spatial layout with /rollers in place of /balls.
        skip = "/balls/" if f.attrs.get("rolling_element") == "roller" else None
        for title in sections:
            for paths, tokens, units in documented_tables(doc)[title]:
                for p in paths:
                    for q in expand(p, f):
                        if not (skip and q.startswith(skip)):
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
        only = BALL_ONLY if attrs.get("rolling_element") == "roller" else ROLLER_ONLY
        for name in BEARING_ATTRIBUTES:
            if name not in only:
                check(name in f.file.attrs, f"bearing attribute {name} missing")
        for p in f.series():
            group = p.strip("/").split("/")[0]
            if group in ("inner_ring", "outer_ring", "cage", "rollers", "balls") and "pocket_step" not in p \
                    and not p.endswith("_speed"):
                names = f.components(p)
                shape = f[p].shape[2 if group in ("rollers", "balls") else 1:]
                check("components" in f.file[p.strip("/")].attrs, f"{p}: no components attribute")
                check(len(names) == (shape[0] if shape else 1), f"{p}: components {names} for row shape {shape}")


def short_run(work, scene_file, end, name):
    text = open(os.path.join(source, "jobs", "scenes", scene_file), encoding="utf-8").read()
    scene = os.path.join(work, name + ".toml")
    open(scene, "w", encoding="utf-8").write(re.sub(r"(?m)^end_time = .*$", f'end_time = "{end}"', text))
    out = os.path.join(work, name + ".h5")
    run = subprocess.run([raceway, "run", scene, "-o", out], capture_output=True, text=True, timeout=300)
    check(run.returncode == 0, f"raceway run {scene_file}: exit {run.returncode}: {run.stderr[-500:]}")
    return out if run.returncode == 0 else None


def group_names(f, group):
    prefix = f"/{group}/"
    return {p[len(prefix):] for p in f.datasets() if p.startswith(prefix) and "/" not in p[len(prefix):]}


def shared_names():
    """A planar and a spatial run: the same datasets in every body group and the rolling elements'
    group, the same per-segment datasets, the same bearing attributes, and the rotation about z read
    the same way from both."""
    with tempfile.TemporaryDirectory() as work:
        planar, spatial = short_run(work, "default.toml", "2 ms", "planar"), short_run(work, "6309_R3.toml", "0.2 ms",
                                                                                       "spatial")
        if not (planar and spatial):
            return
        with RacewayOutput(planar) as p, RacewayOutput(spatial) as s:
            for body in ("inner_ring", "outer_ring", "cage"):
                a, b = group_names(p, body), group_names(s, body)
                check(a == b, f"/{body}: planar only {sorted(a - b)}, spatial only {sorted(b - a)}")
            a, b = group_names(p, p.element_group), group_names(s, s.element_group)
            check(a == b, f"rolling elements: planar only {sorted(a - b)}, spatial only {sorted(b - a)}")
            check((p.element_group, s.element_group) == ("rollers", "balls"), "element_group attributes")
            for f in (p, s):
                for kind in f.segment_kinds():
                    check({"names", "element"} <= group_names(f, f"segments/{kind}"),
                          f"{f.path}: /segments/{kind} lacks names or element")
            a = {k for k in p.attrs if k in BEARING_ATTRIBUTES} - ROLLER_ONLY
            b = {k for k in s.attrs if k in BEARING_ATTRIBUTES} - BALL_ONLY
            check(a == b, f"bearing attributes: planar only {sorted(a - b)}, spatial only {sorted(b - a)}")
            for f in (p, s):
                wz = f.component("cage/angular_velocity", "about z")
                check(wz.ndim == 1 and len(wz) == f.rows, f"{f.path}: cage rotation rate about z is [T]")
                check("cage/rolling_speed" in f and "cage/epicyclic_speed" in f, f"{f.path}: kinematic cage speeds")
            check(p.attrs["model_kind"] == "planar" and s.attrs["model_kind"] == "spatial", "model_kind")
            check(abs(p.attrs["inner_race_radius"] - 0.012) < 1e-15 and abs(p.attrs["pitch_radius"] - 0.015) < 1e-15,
                  f"default scene's radii: {p.bearing}")
            near = abs(s.attrs["inner_groove_radius"] - 0.52 * 2 * s.attrs["element_radius"])
            check(near < 1e-15, f"6309 inner groove radius {s.attrs['inner_groove_radius']}")


def previous():
    """The layout version 2 files of tests/system/run/layout_v2 (written by the raceway of that layout: the
    default scene and 6309 R3, 21 samples each) read under version 3's names, with the same values
    as the datasets under their old names."""
    import h5py
    import numpy as np
    folder = os.path.join(source, "tests", "system", "run", "layout_v2")
    for name, kind in (("planar_v2.h5", "planar"), ("spatial_v2.h5", "spatial")):
        path = os.path.join(folder, name)
        with RacewayOutput(path) as f, h5py.File(path, "r") as raw:
            check(f.layout_version == 2, f"{name}: layout version {f.layout_version}")
            check(f.model_kind == kind, f"{name}: model_kind {f.model_kind}")
            renamed = {"cage/angles": "cage/angle", "rollers/angular_velocity": "rollers/spin"} if kind == "planar" \
                else {"segments/ball_inner_groove/element": "segments/ball_inner_groove/ball"}
            for new, old in renamed.items():
                check(new in f and "/" + new in f.datasets() and "/" + old not in f.datasets(),
                      f"{name}: /{new} in the reader's names, /{old} not")
                if new in f:
                    check(np.array_equal(np.asarray(f[new]), raw[old][()]), f"{name}: /{new} holds /{old}")
            old_names = {"angle", "spin", "ball"}
            check(not any(p.rsplit("/", 1)[1] in old_names for p in f.datasets()), f"{name}: old names listed")
            b = f.bearing
            expect = {"planar": {"pitch_radius": 0.015, "element_radius": 0.003, "inner_race_radius": 0.012,
                                 "outer_race_radius": 0.018, "land_clearance": 3e-4, "element_count": 8},
                      "spatial": {"pitch_radius": 0.03625, "element_radius": 0.008731, "element_count": 8,
                                  "inner_groove_radius": 0.52 * 0.017462, "land_clearance": 0.0}}[kind]
            for key, value in expect.items():
                check(key in b and abs(b[key] - value) <= 1e-12, f"{name}: {key} {b.get(key)}, expected {value}")
            wz = f.component("cage/angles", "about z")
            check(wz.shape == (f.rows,), f"{name}: cage rotation about z {wz.shape}")
            epi = np.asarray(f["cage/epicyclic_speed"])
            if kind == "planar":  # computed by the reader: (w_i r_i + w_o r_o) / (r_i + r_o)
                wi, wo = raw["inner_ring/angular_velocity"][()], raw["outer_ring/angular_velocity"][()]
                check(np.allclose(epi, (wi * 0.012 + wo * 0.018) / 0.03, rtol=1e-14, atol=0),
                      f"{name}: derived epicyclic speed")
                check(f.summary["epicyclic_cage_speed_rpm"] == f.summary["epicyclic_cage_speed_rpm"], "summary")
                check(abs(float(np.mean(epi[len(epi) // 2:])) * 30 / np.pi - f.summary["epicyclic_cage_speed_rpm"])
                      < 1e-9, f"{name}: derived epicyclic speed against the run's summary")
            table = f.table(["cage/angular_velocity", "cage/epicyclic_speed"])
            check(len(table) == f.rows and table.columns[-1] == "cage/epicyclic_speed", f"{name}: table {table.columns}")


PROBE = """
import os, sys, raceway
with raceway.open_output(sys.argv[1]) as out:
    t = out.table(["cage/angular_velocity", "rollers/position"])
    assert t.columns[0] == "cage/angular_velocity[about z]", t.columns[:3]
    assert t.units["rollers/position[0, x]"] == "m" and len(t) == out.rows
    try:
        import pandas
    except ImportError:
        pandas = None
    if pandas is None:
        try:
            t.to_pandas()
            raise SystemExit("to_pandas without pandas did not fail")
        except ImportError as err:
            assert "python3-pandas" in str(err), err
    else:
        df = t.to_pandas()
        assert list(df.columns) == t.columns and df.index.name == "time" and df.attrs["units"]["time"] == "s"
        assert (df["cage/angular_velocity[about z]"].to_numpy() == t["cage/angular_velocity[about z]"]).all()
print(os.path.realpath(raceway.__file__), "pandas" if pandas else "no pandas")
"""


def package():
    """`import raceway` from outside the sources: the build tree's python/ and an installed prefix;
    the installed report imports it too."""
    fixture = os.path.join(source, "tests", "system", "run", "layout_v2", "planar_v2.h5")
    with tempfile.TemporaryDirectory() as work:
        def probe(path, where):
            env = dict(os.environ, PYTHONPATH=path)
            r = subprocess.run(["/usr/bin/python3", "-c", PROBE, fixture], capture_output=True, text=True, cwd=work,
                               env=env, timeout=120)
            check(r.returncode == 0, f"import raceway from {where}: {r.stderr[-1500:]}")
            print(f"{where}: {r.stdout.strip()}", file=sys.stderr)
            return r.stdout
        probe(os.path.join(build, "python"), "the build tree")
        prefix = os.path.join(work, "prefix")
        r = subprocess.run(["cmake", "--install", build, "--prefix", prefix], capture_output=True, text=True,
                           timeout=300)
        check(r.returncode == 0, f"cmake --install: {r.stderr[-1500:]}")
        found = [os.path.join(d, "..") for d, _, files in os.walk(prefix) if "__init__.py" in files
                 and os.path.basename(d) == "raceway" and "dist-packages" in d]
        check(len(found) == 1, f"the installed package: {found}")
        if found:
            where = probe(os.path.realpath(found[0]), "the installation")
            check(where.startswith(os.path.realpath(prefix)), f"imported from {where}, not the installation")
        report = subprocess.run([os.path.join(prefix, "bin", "raceway"), "report", fixture, "-o",
                                 os.path.join(work, "report"), "--no-plots"], capture_output=True, text=True, timeout=300)
        check(report.returncode == 0, f"the installed raceway report on a layout 2 file: {report.stderr[-1500:]}")


def main():
    if case == "package":
        package()
        print(f"{case}: {'passed' if not failures else f'{len(failures)} failure(s)'}")
        return 1 if failures else 0
    if case == "shared_names":
        shared_names()
        print(f"{case}: {'passed' if not failures else f'{len(failures)} failure(s)'}")
        return 1 if failures else 0
    if case == "previous":
        previous()
        print(f"{case}: {'passed' if not failures else f'{len(failures)} failure(s)'}")
        return 1 if failures else 0
    doc = open(os.path.join(source, "docs", "output_layout.md"), encoding="utf-8").read()
    scene_file, end, sections = {
        "planar": ("seed002_40hz.toml", "2 ms", ["Planar (roller-bearing) runs"]),
        "spatial": ("6309_R3.toml", "1 ms", ["Spatial (ball-bearing) runs"]),
        "housing": ("cwru_6205_outer_race_007.toml", "2 ms",
                    ["Spatial (ball-bearing) runs", "Housing (spatial runs with a `[housing]`)"]),
        "spatial_rollers": ("nj_heavy_spatial_roller.toml", "1 ms",
                            ["Spatial (ball-bearing) runs", "Spatial roller-bearing runs"]),
        "planar_bridges": ("seed003_flexible_bridges.toml", "0.3 ms",
                           ["Planar (roller-bearing) runs",
                            'Flexible cage bridges (planar runs with `[cage] bridges = "flexible"`)']),
        "thermal": ("6205_first_scene.toml", "1 ms",
                    ["Spatial (ball-bearing) runs", "Thermal network (runs with a `[thermal]` section)"]),
    }[case]
    extra = "\n[thermal]\n" if case == "thermal" else ""
    sections.append("Power balance (every run)")
    sections.append("Scheduler (`/scheduler`, runs on several ranks or with `--scheduler-log`)")
    tables = documented_tables(doc)
    for title in sections:
        check(title in tables and tables[title], f"docs/output_layout.md has no table under '{title}'")
    if failures:
        return 1
    with tempfile.TemporaryDirectory() as work:
        text = open(os.path.join(source, "jobs", "scenes", scene_file), encoding="utf-8").read()
        scene = os.path.join(work, "scene.toml")
        open(scene, "w", encoding="utf-8").write(re.sub(r"(?m)^end_time = .*$", f'end_time = "{end}"', text) + extra)
        out = os.path.join(work, "out.h5")
        # The segment diagnostics at every sample, the tables' [T x S] (6309 R3 ships them at every
        # 5th; that layout: run.segment_every_rows).
        run = subprocess.run([raceway, "run", scene, "-o", out, "--scheduler-log", "--set", "output.segment_every=1"],
                             capture_output=True, text=True, timeout=300)
        check(run.returncode == 0, f"raceway run exit {run.returncode}: {run.stderr[-500:]}")
        if run.returncode == 0:
            check_file(out, sections, doc)
    print(f"{case}: {'passed' if not failures else f'{len(failures)} failure(s)'}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
