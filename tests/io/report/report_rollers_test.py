#!/usr/bin/env python3
"""The roller section of `raceway report` (io/report/report_rollers.py) for spatial roller runs.

    report_rollers_test.py CASE RACEWAY_EXECUTABLE SOURCE_DIR

Cases:
- heat_map: a short run of small_spatial_roller.toml (beside this file: 10 rollers, 8 slices, the
  outer ring misaligned 1 mrad about x); summary.json's per-roller-and-slice window means, the load
  by slice, one slice's azimuth bins, the rib means and the tilt/skew window means against values
  this test computes from the file with h5py alone (its own column parsing and trapezoid means); the
  ISO/TS 16281 life with one lamina per slice by hand from the same loads.
- edge_loading: the same scene with the misalignment +1 and -1 mrad. The load acts towards -y; the
  outer ring turned by +theta about x moves its raceway at the bottom (y = -R) to y = -R - z theta:
  away from the rollers at +z, so the -z end (slice 0) carries more; -theta the +z end. Checked on
  both races' load by slice and on the most loaded roller.
- lamina_split: report_life.reference_life on made-up loads: a roller cut into equal laminae, each
  carrying its share of a uniform line load, has the life of the roller as one whole-length contact.
- tilt_skew: tilt_skew() against axes made by hand: e_z turned about e_t by the tilt, then about e_r
  by the skew (Rodrigues' formula), at several azimuths, its Cardan angles about x, y solved here.
Whether ball and planar runs have no roller section is checked in report_runs_test.py and report_test.py.

Exit codes: 0 pass, 1 fail, 77 skipped (numpy or h5py missing).
"""
import json
import math
import os
import re
import subprocess
import sys
import tempfile

try:
    import h5py
    import numpy as np
except ImportError as err:
    print(f"SKIP: {err}", file=sys.stderr)
    sys.exit(77)

failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print(f"FAIL: {what}", file=sys.stderr)


def close(value, expected, rel, what, abs_tol=1e-9):
    v, e = np.asarray(value, dtype=float), np.asarray(expected, dtype=float)
    ok = v.shape == e.shape and bool(np.all(np.abs(v - e) <= rel * np.abs(e) + abs_tol))
    check(ok, f"{what}: {value} against {expected}")


ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def run_and_report(raceway, source, folder, misalignment="1 mrad"):
    """The small scene with the outer ring's misalignment about x; returns (h5 path, summary)."""
    with open(os.path.join(source, "tests/io/report/small_spatial_roller.toml")) as fh:
        text = fh.read()
    text, count = re.subn(r'misalignment = \{ x = "[^"]*" \}', f'misalignment = {{ x = "{misalignment}" }}', text)
    assert count == 1, "small_spatial_roller.toml: no misalignment line"
    stem = os.path.join(folder, "m" + misalignment.replace(" ", "").replace("-", "neg"))
    with open(stem + ".toml", "w") as fh:
        fh.write(text)
    subprocess.run([raceway, "run", stem + ".toml", "-o", stem + ".h5"], check=True, env=ENV,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    subprocess.run([raceway, "report", stem + ".h5", "--no-plots", "-o", stem + "_report"], check=True, env=ENV,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(os.path.join(stem + "_report", "summary.json")) as fh:
        return stem + ".h5", json.load(fh)


def text(x):
    return x.decode() if isinstance(x, bytes) else str(x)


def trapezoid_mean(t, v, start):
    """Trapezoid time mean over t >= start along axis 0 (computed here, not with the report's code)."""
    keep = t >= start - 1e-12
    t, v = t[keep], v[keep]
    return np.trapz(v, t, axis=0) / (t[-1] - t[0])


def per_roller_slice(f, kind, n):
    names = [text(x) for x in f[f"segments/{kind}/names"][:]]
    q = f[f"segments/{kind}/normal_force"][:]
    slices = 1 + max(int(re.search(r"slice\[(\d+)\]", s).group(1)) for s in names)
    table = np.zeros((q.shape[0], n, slices))
    for c, name in enumerate(names):
        k, j = re.match(r"roller\[(\d+)\]/\w+/slice\[(\d+)\]$", name).groups()
        table[:, int(k), int(j)] += q[:, c]
    return table


def case_heat_map(raceway, source, folder):
    h5, s = run_and_report(raceway, source, folder)
    r = s.get("rollers")
    check(r is not None, "a spatial roller run's summary has a rollers section")
    if r is None:
        return
    start = r["window"]["start_s"]
    with h5py.File(h5, "r") as f:
        t = f["time"][:]
        xy = f["rollers/position"][:][..., :2]
        n = xy.shape[1]
        check(abs(start - (t[0] + 0.5 * (t[-1] - t[0]))) < 1e-12, "the window is the run's second half")
        for race in ("inner", "outer"):
            q = per_roller_slice(f, f"roller_{race}_slice", n)
            mean = trapezoid_mean(t, q, start)
            e = r["slices"][race]
            close(e["load_mean_per_roller_slice_n"], mean, 1e-9, f"{race}: window mean per roller and slice")
            by_slice = mean.sum(axis=0)
            close(e["load_by_slice_mean_n"], by_slice, 1e-9, f"{race}: window mean by slice")
            x = np.linspace(-1, 1, 2 * len(by_slice) + 1)[1::2]
            close(e["load_centre_offset"], np.sum(by_slice * x) / by_slice.sum(), 1e-9, f"{race}: load centre")
            close(e["minus_z_half_share"], by_slice[:4].sum() / by_slice.sum(), 1e-9, f"{race}: -z half's share")
            # The azimuth bins of slice 0: the plain mean of the window's samples whose roller is in the bin.
            keep = t >= start - 1e-12
            az = np.degrees(np.mod(np.arctan2(xy[keep, :, 1], xy[keep, :, 0]), 2 * math.pi))
            width = r["bin_centre_deg"][1] - r["bin_centre_deg"][0]
            b = np.floor(az / width).astype(int)
            got = np.array([np.nan if v is None else v for v in e["load_bin_mean_n"][0]])
            for k in np.unique(b):
                close(got[k], np.mean(q[keep, :, 0][b == k]), 1e-9, f"{race}: slice 0, bin {k}")
            check(int(np.count_nonzero(np.isfinite(got))) == len(np.unique(b)), f"{race}: empty bins are NaN")
            check(e["slice_load_peak_n"] == float(np.max(q[keep])), f"{race}: peak slice load")
        g = f["segments/roller_flange"]
        names = [text(x).split("/", 1)[1] for x in g["names"][:]]
        for rib in set(names):
            cols = [c for c, name in enumerate(names) if name == rib]
            close(r["ribs"][rib]["force_mean_n"], trapezoid_mean(t, g["normal_force"][:, cols].sum(axis=1), start),
                  1e-9, f"rib {rib}: force mean")
            close(r["ribs"][rib]["power_loss_mean_w"], trapezoid_mean(t, g["power_loss"][:, cols].sum(axis=1), start),
                  1e-9, f"rib {rib}: power mean")
        check(sum(e["force_mean_n"] for e in r["ribs"].values()) > 0, "the ribs carry some load")
        # The tilt's window means per roller: asin of the axis's radial component (the conversion
        # itself against hand-made rotations in tilt_skew).
        a = f["rollers/angles"][:]
        ax, ay = a[..., 0], a[..., 1]
        axis = np.stack([np.sin(ay), -np.sin(ax) * np.cos(ay), np.cos(ax) * np.cos(ay)], -1)
        psi = np.arctan2(xy[..., 1], xy[..., 0])
        tilt = np.arcsin(axis[..., 0] * np.cos(psi) + axis[..., 1] * np.sin(psi))
        close(r["tilt"]["mean_per_roller_mrad"], 1e3 * trapezoid_mean(t, tilt, start), 1e-9, "tilt: window means",
              abs_tol=1e-9)
        check(0 < r["skew"]["max_abs_mrad"] < 50 and 0 < r["tilt"]["max_abs_mrad"] < 50, "tilt and skew in mrad, small")
        check_lamina_life(f, s, n, start)


def check_lamina_life(f, s, n, start):
    """ISO/TS 16281 with one lamina per slice, by hand from the file's slice loads: per slice the power
    mean over the rollers and the window's samples (exponent 4 on the rotating inner ring, 9/2 on the
    outer), lamina ratings q_c = Q_c (w / L_we)^(7/9) with w = (L_we + 2 r_c) / slices."""
    life = s["life"]
    c, z, gamma = life["dynamic_load_rating_n"], 10, 10.0 / 60.0
    term = 1.038 * ((1 - gamma) / (1 + gamma)) ** (143 / 108)
    share = (12.0 + 2 * 0.5) / (8 * 12.0)
    q_ci = c / (0.83 * 0.378 * z) * (1 + term ** 4.5) ** (2 / 9) * share ** (7 / 9)
    q_ce = c / (0.83 * 0.364 * z) * (1 + term ** -4.5) ** (2 / 9) * share ** (7 / 9)
    t = f["time"][:]
    keep = t >= start - 1e-12
    total = 0.0
    for race, q_c, p in (("inner", q_ci, 4.0), ("outer", q_ce, 4.5)):
        q = per_roller_slice(f, f"roller_{race}_slice", n)[keep]
        for j in range(q.shape[2]):
            q_e = np.mean(q[:, :, j] ** p) ** (1 / p)
            total += (q_c / q_e) ** -4.5
    tracks = life["reference"]["tracks"]
    check(len(tracks) == 16, f"one track per slice and race: {len(tracks)}")
    close([tracks[0]["rating_n"], tracks[8]["rating_n"]], [q_ci, q_ce], 1e-9, "lamina ratings")
    close(life["reference"]["l10r_mrev"], total ** (-8 / 9), 1e-9, "L10r from the laminae")


def case_edge_loading(raceway, source, folder):
    for misalignment, loaded_end in (("1 mrad", 0), ("-1 mrad", -1)):
        _, s = run_and_report(raceway, source, folder, misalignment)
        for race in ("inner", "outer"):
            e = s["rollers"]["slices"][race]
            by_slice = e["load_by_slice_mean_n"]
            other = -1 - loaded_end
            check(by_slice[loaded_end] > 2.0 * by_slice[other],
                  f"{misalignment}, {race}: the {'-z' if loaded_end == 0 else '+z'} end carries more: {by_slice}")
            check(e["slice_load_peak_slice"] == (loaded_end % e["slices"]),
                  f"{misalignment}, {race}: the peak slice {e['slice_load_peak_slice']} is at the loaded end")
            sign = -1 if loaded_end == 0 else 1
            check(sign * e["load_centre_offset"] > 0.1, f"{misalignment}, {race}: load centre {e['load_centre_offset']}")
            check(sign * (0.5 - e["minus_z_half_share"]) > 0.1, f"{misalignment}, {race}: -z half {e['minus_z_half_share']}")
            per = np.asarray(e["load_mean_per_roller_slice_n"])
            top = int(np.argmax(per.sum(axis=1)))
            check(per[top, loaded_end] > per[top, other], f"{misalignment}, {race}: the most loaded roller's end")


def rotation(axis, angle):
    """Rodrigues' formula."""
    k = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(angle) * kx + (1 - math.cos(angle)) * kx @ kx


def case_tilt_skew(source):
    sys.path.insert(0, os.path.join(source, "io/report"))
    from report_rollers import tilt_skew
    for psi_deg in (0.0, 37.0, 90.0, 200.0, 315.0):
        psi = math.radians(psi_deg)
        e_r, e_t = np.array([math.cos(psi), math.sin(psi), 0.0]), np.array([-math.sin(psi), math.cos(psi), 0.0])
        for tilt, skew in ((2e-3, 0.0), (0.0, -3e-3), (1.5e-3, 2.5e-3), (0.2, -0.3)):
            axis = rotation(e_r, skew) @ rotation(e_t, tilt) @ np.array([0.0, 0.0, 1.0])
            beta = math.asin(axis[0])                      # axis = Rx(alpha) Ry(beta) e_z
            alpha = math.atan2(-axis[1], axis[2])
            xy = 0.03 * np.array([[math.cos(psi), math.sin(psi)]])
            t, s = tilt_skew(np.array([[alpha, beta]]), xy)
            close([t[0], s[0]], [tilt, skew], 1e-9, f"psi {psi_deg} deg: tilt {tilt}, skew {skew}", abs_tol=1e-12)
    # A pure tilt turns the axis's end outwards (towards e_r): at psi = 90 deg the axis leans to +y.
    t, s = tilt_skew(np.array([[-1e-3, 0.0]]), np.array([[0.0, 0.03]]))
    close([t[0], s[0]], [1e-3, 0.0], 1e-6, "psi 90 deg: Rx(-1 mrad) is a tilt of +1 mrad", abs_tol=1e-12)


def case_lamina_split(source):
    sys.path.insert(0, os.path.join(source, "io/report"))
    import report_life
    rng = np.random.default_rng(7)
    inner, outer = 100 + 900 * rng.random((40, 12)), 100 + 900 * rng.random((40, 12))
    g = {"ball": False, "z": 12, "alpha": 0.0, "fi": None, "fe": None, "rows": 1, "lwe": 12.0}
    args = (slice(0, 40), g, 40e3, 0.18, True, 10 / 3, 3000.0, 1.0, 0.5, 4e3, None)
    zero = np.zeros_like(inner)
    whole = report_life.reference_life({"tracks": {"inner": [(inner, zero)], "outer": [(outer, zero)]}}, *args)
    check(math.isfinite(whole["l10r_mrev"]) and whole["l10r_mrev"] > 0, "the whole roller's life")
    # Each lamina of width w carries w / L_we of the roller's load. Without corners (S w = L_we) the
    # laminae give the whole roller's life; slices over the corners too (S w = L_we + 2 r_c) carry
    # (S w / L_we) times the load in all, and each lamina's term (q_c / q_e)^(-9/2) scales by w / L_we:
    # L10r = whole (S w / L_we)^(-8/9).
    for slices, corner in ((1, 0.0), (5, 0.0), (8, 0.5e-3), (20, 1.5e-3)):
        share = (12.0 + 2e3 * corner) / slices / 12.0
        li = {"tracks": {"inner": [(inner * share, zero)] * slices, "outer": [(outer * share, zero)] * slices},
              "laminae": {"inner": slices, "outer": slices}, "parameters": {"bearing.corner_radius": {"value": corner}}}
        laminae = report_life.reference_life(li, *args)
        close(laminae["l10r_mrev"], whole["l10r_mrev"] * (slices * share) ** (-8 / 9), 1e-9,
              f"{slices} laminae, corners {corner} m")


def main():
    case, raceway, source = sys.argv[1:4]
    with tempfile.TemporaryDirectory() as folder:
        if case == "heat_map":
            case_heat_map(raceway, source, folder)
        elif case == "edge_loading":
            case_edge_loading(raceway, source, folder)
        elif case == "lamina_split":
            case_lamina_split(source)
        elif case == "tilt_skew":
            case_tilt_skew(source)
        else:
            print(f"unknown case {case}", file=sys.stderr)
            return 2
    print(f"{case}: {'FAIL' if failures else 'pass'}" + (f" ({len(failures)} checks)" if failures else ""))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
