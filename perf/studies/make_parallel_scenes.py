#!/usr/bin/python3
"""Scenes for the parallel benchmarks (perf/studies/run_parallel_benchmarks.sh), derived from the job files
so they follow the physics of the full runs:

  heavy_6309_R3.toml   6309 R3 with a 40 x 40 ball-race traction grid, 100 ms (5 revolutions; the heavy scene)
  moving_6309_R3.toml  the same with a 30 x 30 grid and the 1019.6 N radial load on the outer ring
                       turning at -50 Hz (against the cage): the loaded zone, and with it the
                       expensive contacts, moves round the bearing (work that moves), 60 ms
  short_*.toml         6309 R3, QJ215, seed 002 as they are, shortened (replay-model inputs)
  heavy_qj215_validation.toml  QJ215 with a 40 x 40 ball-race grid, 20 ms (replay-model input)

    make_parallel_scenes.py SOURCE_DIR OUT_DIR
"""
import math
import re
import sys

src, out = sys.argv[1], sys.argv[2]


def derive(name, new_name, end_time, grid=None, load=None):
    text = open(f"{src}/jobs/scenes/{name}").read()
    text = re.sub(r'(?m)^end_time = .*$', f'end_time = "{end_time}"', text)
    if grid:
        text, n = re.subn(r'(?m)^grid = \[5, 5\]', f"grid = [{grid}, {grid}]", text, count=1)
        assert n == 1, "no ball-race grid line to replace"
    if load:
        text, n = re.subn(r'(?m)^load = \{ fy = "1019.6 N" \}.*$', load, text, count=1)
        assert n == 1, "no outer-ring load line to replace"
    open(f"{out}/{new_name}", "w").write(text)


derive("6309_R3.toml", "heavy_6309_R3.toml", "100 ms", grid=40)
# Rotating load: F (sin, cos) of the angle, tabulated every 5 degrees (piecewise linear between).
force, hz, end = 1019.6, -50.0, 0.06
times = [i * end / 240 for i in range(241)]
fx = [force * math.sin(2 * math.pi * hz * t) for t in times]
fy = [force * math.cos(2 * math.pi * hz * t) for t in times]
fmt = lambda v, unit: "[" + ", ".join(f'"{x:.6g} {unit}"' for x in v) + "]"
load = (f"load.fx = {{ time = {fmt(times, 's')}, value = {fmt(fx, 'N')} }}\n"
        f"load.fy = {{ time = {fmt(times, 's')}, value = {fmt(fy, 'N')} }}")
derive("6309_R3.toml", "moving_6309_R3.toml", f"{end * 1e3:g} ms", grid=30, load=load)
derive("6309_R3.toml", "short_6309_R3.toml", "40 ms")
derive("qj215_validation.toml", "short_qj215_validation.toml", "40 ms")
derive("seed002_40hz.toml", "short_seed002_40hz.toml", "50 ms")
derive("qj215_validation.toml", "heavy_qj215_validation.toml", "20 ms", grid=40)
