#!/usr/bin/env python3
"""Defects and vibration (docs/vibration.md) on short runs of a 6205 in a housing, one case per ctest:

    vibration_test.py CASE RACEWAY MPIEXEC SOURCE_DIR

The scene: a 6205 (9 balls), inner ring at 12000 r/min (a short run, 40 or 80 ms, gives enough
revolutions for the frequency resolution), the outer ring in a housing of 1 kg on 1000 MN/m (5.0 kHz, damping
ratio 0.047) whose acceleration is sampled at 100 kHz; the first 10 ms (the housing settling under
its load) are left out of every signal. Kinematics after slip: the characteristic frequencies from
the run's measured cage speed (raceway.vibration.characteristic_frequencies), the slip reported.

  outer: a spall on the outer race in the load zone (0.5 mm long, sharp edges), 500 N radial: in the
    envelope spectrum (band 0.5 to 1.5 times the housing's frequency) BPFO and its harmonics 2, 3
    and 4 within 1 % of kinematics after slip, each at least 3 times the floor around it.
  inner: the spall on the inner race (80 ms): BPFI and harmonics 2 and 3 within 1 %, and the sidebands of
    the load zone's modulation at BPFI -+ the shaft frequency, each at least 2 times its floor.
  waviness: inner-race waviness of order n = Z - 1 = 8 and of n = Z + 1 = 10 (two runs, 0.5 um,
    500 N axial load: every ball loaded alike): the theory (Wardle 1988) puts the housing's
    vibration at Z (f_i - f_c) -+ f_i for n = Z -+ 1; each order's line within 0.1 % and at least
    10 times its floor, and the other order's line not above 3 times its floor.
  clean: the same bearing without a defect (80 ms): at BPFO, BPFI (harmonics 1 to 3) its envelope
    spectrum carries no line above 3 times its floor, and at BPFO and BPFI themselves less than 10 %
    of the spalled bearings' lines (printed: the spectrum's median, the numerical noise floor).
  report: `raceway report` on the outer-race run: summary.json's vibration part (BPFO x2 among the lines
    that carry energy, BPFI not), the log's sensor line, and sensor.csv holding the window's samples.
  ranks: the outer-race run (with a ball's spall and waviness besides) at np = 2 against np = 1, and a run
    killed (SIGKILL) after a checkpoint and resumed against an uninterrupted one with the same
    checkpoint interval: /housing bitwise.
  ball_spall: a spall on ball[0]: the envelope spectrum's line at 2 BSF and the sidebands 2 BSF -+ FTF.
  ball_waviness: ball[0]'s waviness of order 2: its contact forces at 2 BSF, the housing at 2 BSF -+ FTF;
    of order 3: its contact forces silent at 3 BSF.
  roller_outer: a spatial NU205 (13 rollers, 10 slices) at 6000 r/min under 2 kN in the same housing,
    a spall 1 mm long and 4 mm wide on its outer race in the load zone (the middle slices drop into
    it): BPFO and its harmonics 2 to 4 within 1 % of kinematics after slip, the fundamental at least
    2 times its floor (measured 2.5), the harmonics 3 times (measured 16-29), and no line at BPFI.
  roller_inner: the same bearing with the spall on its inner race instead (80 ms): BPFI and harmonics
    2 and 3, and the sidebands BPFI -+ the shaft frequency, within 1 % and at least 2 times their
    floor (measured within 0.2 %, 3.8 to 5.3 times).
  roller_spall: the same bearing, preloaded by 20 um, with a 0.5 x 4 mm spall on roller[0] instead (80
    ms): the lines at twice and four times the roller's spin relative to the cage (measured from
    /rollers/angular_velocity) within 1 %, at least 5 and 3 times their floors (measured 14 and 9);
    the report's BSF within 1 % of the measured spin, its table marking BSF x2 and no race line.
  tapered_outer: jobs/scenes/30206_tapered.toml (3000 r/min, 4 kN radial, 3 kN axial) for 80 ms in the
    same housing with a 1 x 4 mm spall in its cup's load zone: BPFO and harmonics 2 to 4 within 1 %
    of kinematics after slip, each at least 3 times its floor (measured within 0.013 %, 33 to 111
    times).

Exit codes: 0 pass, 1 fail, 77 skipped (h5py or numpy missing).
"""
import os
import signal
import subprocess
import sys
import tempfile
import time

try:
    import h5py
    import numpy as np
except ImportError as err:
    print(f"SKIP: {err}", file=sys.stderr)
    sys.exit(77)

SCENE = """[scene]
end_time = "{end}"
output_interval = "{interval}"
[bearing]
designation = "6205"
[inner_ring]
speed = "12000 rpm"
load = {{ {load} }}
{inner}
[outer_ring]
motion = "fixed"
{outer}
[housing]
mass = "1 kg"
stiffness = "1000 MN/m"
damping = "3000 N s/m"
sensor_interval = "10 us"
[output]
segments = {segments}
{extra}
"""
SPALL = 'spall = { angle = "%s", length = "0.5 mm", width = "2 mm", depth = "0.1 mm" }'
failures = []


def check(cond, what):
    print(f"{'ok' if cond else 'FAIL'}: {what}", file=sys.stderr)
    if not cond:
        failures.append(what)


def write_scene(work, name, end="40 ms", load='fy = "-500 N"', inner="", outer="", extra="", segments=False,
                interval="1 ms"):
    path = os.path.join(work, name + ".toml")
    with open(path, "w", encoding="utf-8") as f:
        f.write(SCENE.format(end=end, interval=interval, load=load, inner=inner, outer=outer, extra=extra,
                             segments="true" if segments else "false"))
    return path


def run(raceway, scene, out, np_ranks=1, mpiexec=None, extra=()):
    cmd = [raceway, "run", scene, "-o", out, *extra]
    if np_ranks > 1:
        cmd = [mpiexec, "--oversubscribe", "-np", str(np_ranks)] + cmd
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=300, env=env)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)}: exit {r.returncode}: {r.stderr[-800:]}")
    return out


def analyse(path, envelope=True, axis=1):
    import raceway.vibration as vib
    with h5py.File(path, "r") as f:
        freqs = vib.characteristic_frequencies(f)
        s = vib.sensor_signal(f, start=0.01)
        x = s.acceleration[:, axis]
        if envelope:
            freq, amp = vib.envelope_spectrum(x, s.rate, vib.resonance_band(f), pad=8)
        else:
            freq, amp = vib.spectrum(x, s.rate, pad=8)
    print(f"{os.path.basename(path)}: cage {freqs['FTF']:.3f} Hz, slip {100 * freqs['slip']:.3f} %, "
          f"BPFO {freqs['BPFO']:.2f} Hz (kinematic {freqs['kinematic']['BPFO']:.2f}), BPFI {freqs['BPFI']:.2f} Hz "
          f"(kinematic {freqs['kinematic']['BPFI']:.2f}), statistics {vib.statistics(x)}", file=sys.stderr)
    return vib, freqs, freq, amp


def line(vib, freq, amp, f0, name, within, above):
    at, a = vib.peak_near(freq, amp, f0, 0.03)
    floor = vib.noise_floor(freq, amp, f0)
    check(abs(at / f0 - 1) <= within, f"{name}: line at {at:.2f} Hz, expected {f0:.2f} Hz "
          f"({100 * (at / f0 - 1):+.3f} %, within {100 * within:g} %)")
    check(a >= above * floor, f"{name}: amplitude {a:.4g} >= {above} x floor {floor:.4g}")
    return a, floor


def case_outer(raceway, work):
    vib, f, freq, amp = analyse(run(raceway, write_scene(work, "outer", outer=SPALL % "-90 deg"),
                                    os.path.join(work, "outer.h5")))
    for k in range(1, 5):
        line(vib, freq, amp, k * f["BPFO"], f"BPFO x{k}", 0.01, 3.0)


def case_inner(raceway, work):
    vib, f, freq, amp = analyse(run(raceway, write_scene(work, "inner", end="80 ms", inner=SPALL % "0 deg"),
                                    os.path.join(work, "inner.h5")))
    for k in range(1, 4):
        line(vib, freq, amp, k * f["BPFI"], f"BPFI x{k}", 0.01, 2.0)
    for sign, name in ((-1, "BPFI - shaft"), (1, "BPFI + shaft")):
        line(vib, freq, amp, f["BPFI"] + sign * f["shaft"], name, 0.01, 2.0)


def case_waviness(raceway, work):
    for order, sign in ((8, -1), (10, 1)):
        scene = write_scene(work, f"waviness{order}", load='fz = "500 N"',
                            inner=f'waviness = {{ orders = [{order}], amplitudes = ["0.5 um"] }}')
        vib, f, freq, amp = analyse(run(raceway, scene, os.path.join(work, f"waviness{order}.h5")), envelope=False,
                                    axis=0)
        expected = f["BPFI"] + sign * f["shaft"]  # Z (f_i - f_c) -+ f_i
        line(vib, freq, amp, expected, f"waviness order {order}: Z (f_i - f_c) {'+' if sign > 0 else '-'} f_i", 0.001,
             10.0)
        other = f["BPFI"] - sign * f["shaft"]
        at, a = vib.peak_near(freq, amp, other, 0.01)
        floor = vib.noise_floor(freq, amp, other)
        check(a < 3.0 * floor, f"waviness order {order}: nothing at the other order's line {other:.1f} Hz "
              f"({a:.3g} < 3 x floor {floor:.3g})")


def case_ball_spall(raceway, work):
    """A spall on ball[0] meets the inner and the outer race once each per turn of the ball relative to
    the cage: impacts at 2 BSF, and with the load zone turning at the cage's speed, sidebands at FTF."""
    ball = 'spall = { element = 0, angle = "180 deg", length = "0.5 mm", width = "2 mm", depth = "0.1 mm" }'
    vib, f, freq, amp = analyse(run(raceway, write_scene(work, "ball", end="80 ms", extra="[rolling_element]\n" + ball),
                                    os.path.join(work, "ball.h5")))
    print(f"BSF {f['BSF']:.2f} Hz (kinematic {f['kinematic']['BSF']:.2f}), FTF {f['FTF']:.2f} Hz", file=sys.stderr)
    a, _ = line(vib, freq, amp, 2 * f["BSF"], "2 BSF", 0.01, 3.0)
    for sign, name in ((-1, "2 BSF - FTF"), (1, "2 BSF + FTF")):
        line(vib, freq, amp, 2 * f["BSF"] + sign * f["FTF"], name, 0.01, 2.0)


def loaded_bsf(path, f):
    """BSF at the contact angle the measured cage speed implies: under an axial load every ball rolls
    at one contact angle a, and f_c = f_i (1 - gamma) / 2 with gamma = D cos a / d_m gives gamma; then
    BSF = (d_m / D) (1 - gamma) (f_i - f_c) (the report's BSF takes the nominal angle, 0 here)."""
    with h5py.File(path, "r") as h:
        d_over_dm = float(np.squeeze(h.attrs["element_radius"])) / float(np.squeeze(h.attrs["pitch_radius"]))
    gamma = 1 - 2 * f["FTF"] / f["shaft"]
    print(f"contact angle from the cage's speed: {np.degrees(np.arccos(gamma / d_over_dm)):.1f} deg", file=sys.stderr)
    return (1 - gamma) * (f["shaft"] - f["FTF"]) / d_over_dm


def contact_force_line(vib, path, f0):
    """Ball[0]'s inner- and outer-race normal forces: their spectra's largest peaks within 2 % of f0."""
    with h5py.File(path, "r") as h:
        t = h["time"][()].reshape(-1)
        keep = t >= 0.01
        out = []
        for kind in ("ball_inner_groove", "ball_outer_groove"):
            freq, amp = vib.spectrum(h["segments"][kind]["normal_force"][()][keep, 0], 1 / (t[1] - t[0]), pad=8)
            out.append((vib.peak_near(freq, amp, f0, 0.02), vib.noise_floor(freq, amp, f0)))
    return out


def case_ball_waviness(raceway, work):
    """Waviness of order n round one ball's equator (2 um) under an axial load. The two race contacts face
    each other across the ball: an even order changes the ball's diameter between them n times a turn
    relative to the cage: ball[0]'s contact forces vary at n BSF (within 1 %), a radial force turning
    with the cage, so the housing vibrates at n BSF -+ FTF (within 1 %, at least 5 times the floor); an
    odd order moves the surface in on one side and out on the other and leaves the diameter: its
    contact forces at n BSF stay below 1 % of the even order's."""
    even = None
    for order in (2, 3):
        extra = f'[rolling_element]\nwaviness = {{ element = 0, orders = [{order}], amplitudes = ["2 um"] }}'
        path = run(raceway, write_scene(work, f"ballwav{order}", load='fz = "500 N"', extra=extra, segments=True,
                                        interval="0.1 ms"), os.path.join(work, f"ballwav{order}.h5"))
        vib, f, freq, amp = analyse(path, envelope=False, axis=0)
        bsf = loaded_bsf(path, f)
        forces = contact_force_line(vib, path, order * bsf)
        for (at, a), floor in forces:
            print(f"order {order}: ball[0]'s contact force {a:.4g} N at {at:.1f} Hz ({order} BSF {order * bsf:.1f} Hz), "
                  f"floor {floor:.3g} N", file=sys.stderr)
        if order % 2 == 0:
            even = min(a for (_, a), _ in forces)
            for ((at, a), floor), race in zip(forces, ("inner", "outer")):
                check(abs(at / (order * bsf) - 1) <= 0.01 and a >= 10 * floor,
                      f"order {order}: the {race}-race force's line at {at:.1f} Hz is {order} BSF, {a:.3g} N")
            for sign in (-1, 1):
                line(vib, freq, amp, order * bsf + sign * f["FTF"],
                     f"ball waviness order {order}: {order} BSF {'+' if sign > 0 else '-'} FTF", 0.01, 5.0)
        else:
            for ((_, a), _), race in zip(forces, ("inner", "outer")):
                check(a < 0.01 * even, f"order {order}: the {race}-race force at {order} BSF, {a:.3g} N, is below 1 % "
                      f"of the even order's {even:.3g} N")


def case_clean(raceway, work):
    vib, f, freq, amp = analyse(run(raceway, write_scene(work, "clean", end="80 ms"), os.path.join(work, "clean.h5")))
    _, fo, freq_o, amp_o = analyse(run(raceway, write_scene(work, "outer", end="80 ms", outer=SPALL % "-90 deg"),
                                       os.path.join(work, "outer.h5")))
    _, fi, freq_i, amp_i = analyse(run(raceway, write_scene(work, "inner", end="80 ms", inner=SPALL % "0 deg"),
                                       os.path.join(work, "inner.h5")))
    print(f"clean: envelope spectrum's median {np.median(amp):.4g} m/s^2 (the floor)", file=sys.stderr)
    for name, fd, freq_d, amp_d in (("BPFO", fo, freq_o, amp_o), ("BPFI", fi, freq_i, amp_i)):
        for k in range(1, 4):
            f0 = k * f[name]
            _, a = vib.peak_near(freq, amp, f0, 0.02)
            floor = vib.noise_floor(freq, amp, f0)
            _, defect = vib.peak_near(freq_d, amp_d, k * fd[name], 0.02)
            check(a < 3.0 * floor, f"clean {name} x{k}: {a:.4g} < 3 x floor {floor:.4g}")
            if k == 1:  # the harmonics of a spall are weaker: there the floor alone decides
                check(a < 0.1 * defect, f"clean {name}: {a:.4g} < 10 % of the spalled bearing's {defect:.4g}")


ROLLER_SCENE = """[scene]
end_time = "40 ms"
output_interval = "0.1 ms"
model = "spatial"
[bearing]
designation = "NU205"
[inner_ring]
speed = "6000 rpm"
load = { fy = "-2000 N" }
[outer_ring]
motion = "fixed"
spall = { angle = "-90 deg", length = "1 mm", width = "4 mm", depth = "0.1 mm" }
[housing]
mass = "1 kg"
stiffness = "1000 MN/m"
damping = "3000 N s/m"
sensor_interval = "10 us"
[contact.roller_race]
slices = 10
[output]
segments = false
"""


def case_roller_outer(raceway, work):
    path = os.path.join(work, "roller_outer.toml")
    open(path, "w", encoding="utf-8").write(ROLLER_SCENE)
    vib, f, freq, amp = analyse(run(raceway, path, os.path.join(work, "roller_outer.h5")))
    line(vib, freq, amp, f["BPFO"], "roller BPFO x1", 0.01, 2.0)
    for k in range(2, 5):
        line(vib, freq, amp, k * f["BPFO"], f"roller BPFO x{k}", 0.01, 3.0)
    _, a = vib.peak_near(freq, amp, f["BPFI"], 0.02)
    floor = vib.noise_floor(freq, amp, f["BPFI"])
    check(a < 3.0 * floor, f"roller BPFI (no inner-race fault): {a:.4g} < 3 x floor {floor:.4g}")


def case_roller_inner(raceway, work):
    text = ROLLER_SCENE.replace('end_time = "40 ms"', 'end_time = "80 ms"').replace(
        'spall = { angle = "-90 deg"', '# no outer spall').replace(
        '[inner_ring]\n', '[inner_ring]\nspall = { angle = "0 deg", length = "1 mm", width = "4 mm", depth = "0.1 mm" }\n')
    path = os.path.join(work, "roller_inner.toml")
    open(path, "w", encoding="utf-8").write(text)
    vib, f, freq, amp = analyse(run(raceway, path, os.path.join(work, "roller_inner.h5")))
    for k in range(1, 4):
        line(vib, freq, amp, k * f["BPFI"], f"roller BPFI x{k}", 0.01, 2.0)
    for sign, name in ((-1, "roller BPFI - shaft"), (1, "roller BPFI + shaft")):
        line(vib, freq, amp, f["BPFI"] + sign * f["shaft"], name, 0.01, 2.0)


def roller_bsf(path, element=0, start=0.01):
    """Roller[element]'s spin relative to the cage [Hz], measured: the mean of its angular velocity about
    the bearing's axis less the cage's, from `start` on."""
    with h5py.File(path, "r") as h:
        t = h["time"][()].reshape(-1)
        keep = t >= start
        spin = np.asarray(h["rollers/angular_velocity"])[keep, element, 2]
        cage = np.asarray(h["cage/angular_velocity"]).reshape(t.size, -1)[keep, -1]
    return abs(float(np.mean(spin - cage))) / (2 * np.pi)


def case_roller_spall(raceway, work):
    """A spall on roller[0] meets the inner and the outer race once each per turn of the roller relative
    to the cage: a line at 2 BSF (BSF measured from the roller's spin) and its harmonic 4 BSF; the
    report's BSF (rolling without slip on the inner race at the measured cage speed) within 1 % of the
    measured spin, its table marking BSF x2 and no race line. A 20 um preload loads every roller all
    round, so that the spall strikes at every half turn (under a clearance only in the load zone,
    which spreads the line into a comb 2 BSF -+ k FTF of nearly equal lines)."""
    text = ROLLER_SCENE.replace('end_time = "40 ms"', 'end_time = "80 ms"').replace(
        'spall = { angle = "-90 deg"', '# no outer spall').replace(
        '[bearing]\n', '[bearing]\nradial_clearance = "-20 um"\n') + (
        '[rolling_element]\nspall = { element = 0, angle = "0 deg", length = "0.5 mm", width = "4 mm", '
        'depth = "0.1 mm" }\n')
    path = os.path.join(work, "roller_spall.toml")
    open(path, "w", encoding="utf-8").write(text)
    out = run(raceway, path, os.path.join(work, "roller_spall.h5"))
    vib, f, freq, amp = analyse(out)
    bsf = roller_bsf(out)
    print(f"roller BSF measured {bsf:.2f} Hz, the report's {f['BSF']:.2f} Hz "
          f"({100 * (f['BSF'] / bsf - 1):+.3f} %), FTF {f['FTF']:.2f} Hz", file=sys.stderr)
    check(abs(f["BSF"] / bsf - 1) <= 0.01, "the report's BSF within 1 % of the roller's measured spin")
    line(vib, freq, amp, 2 * bsf, "roller 2 BSF", 0.01, 5.0)
    line(vib, freq, amp, 4 * bsf, "roller 4 BSF", 0.01, 3.0)
    rows = {(r["name"], r["harmonic"]): r for r in vib.energy_table(freq, amp, f)}
    check(rows[("BSF", 2)]["carries_energy"], "the report's table: BSF x2 carries energy")
    check(not rows[("BPFO", 1)]["carries_energy"] and not rows[("BPFI", 1)]["carries_energy"],
          "the report's table: no race line (BPFO, BPFI) carries energy")


def case_tapered_outer(raceway, source, work):
    text = open(os.path.join(source, "jobs", "scenes", "30206_tapered.toml"), encoding="utf-8").read()
    text = text.replace('end_time = "10 ms"', 'end_time = "80 ms"').replace('output_interval = "0.25 ms"',
                                                                           'output_interval = "0.1 ms"')
    text = text.replace('[outer_ring]\nmotion = "fixed"\n', '[outer_ring]\nmotion = "fixed"\n'
                        'spall = { angle = "-90 deg", length = "1 mm", width = "4 mm", depth = "0.1 mm" }\n')
    text += '\n[housing]\nmass = "1 kg"\nstiffness = "1000 MN/m"\ndamping = "3000 N s/m"\nsensor_interval = "10 us"\n'
    check("spall = " in text and "80 ms" in text, "the tapered scene took the spall and the longer run")
    path = os.path.join(work, "tapered_outer.toml")
    open(path, "w", encoding="utf-8").write(text)
    vib, f, freq, amp = analyse(run(raceway, path, os.path.join(work, "tapered_outer.h5")))
    for k in range(1, 5):
        line(vib, freq, amp, k * f["BPFO"], f"tapered BPFO x{k}", 0.01, 3.0)


def case_report(raceway, work):
    """`raceway report` on a spalled run: the vibration summary, its lines and the sensor's CSV."""
    import csv
    import json
    out = run(raceway, write_scene(work, "report", end="30 ms", outer=SPALL % "-90 deg", segments=True),
              os.path.join(work, "report.h5"))
    r = subprocess.run([raceway, "report", out, "--no-plots"], capture_output=True, text=True, timeout=300)
    check(r.returncode == 0, f"raceway report: exit {r.returncode}: {r.stderr[-600:]}")
    folder = os.path.join(work, "report_report")
    summary = json.load(open(os.path.join(folder, "summary.json"), encoding="utf-8"))
    v = summary.get("vibration", {})
    check({"statistics", "frequencies_hz", "lines", "slip"} <= v.keys(), f"summary.json's vibration: {sorted(v)}")
    carrying = [(line["name"], line["harmonic"]) for line in v.get("lines", []) if line["carries_energy"]]
    check(("BPFO", 2) in carrying, f"the table says BPFO x2 carries energy: {carrying}")
    check(all(name != "BPFI" or k != 1 for name, k in carrying), f"and BPFI does not: {carrying}")
    check("housing sensor (y): RMS" in r.stderr, "the report's log names the sensor's RMS")
    with open(os.path.join(folder, "sensor.csv"), encoding="utf-8") as f:
        rows = list(csv.reader(f))
    with h5py.File(out, "r") as f:
        t = f["housing/sensor_time"][1:].reshape(-1)
        ay = f["housing/acceleration"][1:].reshape(-1, 2)[:, 1]
    start = summary["window"]["start_s"]
    keep = t >= start
    check(rows[0][0] == "time_s" and len(rows) - 1 == int(keep.sum()), f"sensor.csv: {len(rows) - 1} rows")
    check(float(rows[1][6]) == ay[keep][0] and float(rows[-1][0]) == t[keep][-1], "sensor.csv holds the samples")


def housing_series(path):
    with h5py.File(path, "r") as f:
        return {k: f["housing"][k][()] for k in f["housing"]}


def same(a, b, what):
    equal = a.keys() == b.keys() and all(np.array_equal(a[k], b[k], equal_nan=True) and a[k].shape == b[k].shape
                                         for k in a)
    check(equal, what)


BALL_DEFECTS = ('[rolling_element]\nspall = { element = 0, angle = "180 deg", length = "0.5 mm", width = "2 mm", '
                'depth = "0.1 mm" }\nwaviness = { element = 3, orders = [2], amplitudes = ["1 um"] }')


def case_ranks(raceway, mpiexec, work):
    # The outer race's spall, and a ball's spall and waviness (the balls' orientations are states).
    scene = write_scene(work, "outer", end="30 ms", outer=SPALL % "-90 deg", extra=BALL_DEFECTS)
    one = housing_series(run(raceway, scene, os.path.join(work, "np1.h5")))
    two = housing_series(run(raceway, scene, os.path.join(work, "np2.h5"), 2, mpiexec))
    same(one, two, "np = 2 writes the np = 1 run's /housing bitwise")
    check(np.isfinite(one["acceleration"][1:]).all(), "every sensor sample after t = 0 is written")
    # Killed after a checkpoint and resumed: the same bits as the uninterrupted run (which restarts
    # its integrator at the same checkpoints).
    ckpt = write_scene(work, "ckpt", end="60 ms", outer=SPALL % "-90 deg",
                       extra='checkpoint_interval = "5 ms"\n' + BALL_DEFECTS)
    whole = housing_series(run(raceway, ckpt, os.path.join(work, "whole.h5")))
    out = os.path.join(work, "killed.h5")
    proc = subprocess.Popen([raceway, "run", ckpt, "-o", out], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.time() + 60
    while not os.path.exists(out + ".checkpoint") and proc.poll() is None and time.time() < deadline:
        time.sleep(0.01)
    time.sleep(0.1)
    proc.send_signal(signal.SIGKILL)
    code = proc.wait(timeout=120)
    check(code != 0 and os.path.exists(out + ".checkpoint"), "the run was killed after a checkpoint")
    run(raceway, ckpt, out, extra=("--resume",))
    same(whole, housing_series(out), "a run killed after a checkpoint and resumed writes the uninterrupted /housing "
         "bitwise")


def main():
    if len(sys.argv) != 5:
        print(__doc__, file=sys.stderr)
        return 2
    case, raceway, mpiexec, source = sys.argv[1:]
    sys.path.insert(0, os.path.join(source, "io", "report"))
    with tempfile.TemporaryDirectory() as work:
        if case == "ranks":
            case_ranks(raceway, mpiexec, work)
        else:
            {"outer": case_outer, "inner": case_inner, "waviness": case_waviness, "clean": case_clean,
             "report": case_report, "ball_spall": case_ball_spall,
             "ball_waviness": case_ball_waviness, "roller_outer": case_roller_outer,
             "roller_inner": case_roller_inner, "roller_spall": case_roller_spall,
             "tapered_outer": lambda r, w: case_tapered_outer(r, source, w)}[case](raceway, work)
    if failures:
        print(f"{case}: FAILED ({len(failures)})", file=sys.stderr)
        return 1
    print(f"{case}: passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
