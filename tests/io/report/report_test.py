#!/usr/bin/env python3
"""Behaviour tests of `raceway report` on synthetic spatial output files, one case per ctest.

    report_test.py CASE RACEWAY_EXECUTABLE SOURCE_DIR

The files are written with h5py following docs/output_layout.md ("Spatial (ball-bearing) runs"):
8 balls on a 50 mm pitch radius turning with the cage at 200 rad/s (epicyclic 210 rad/s), a cage
centre whirling on a 20 um circle three times per window, square pulses on two pockets (pocket 0:
front bar, 40 N x 5 samples every 50; pocket 3: rear bar, 25 N x 8 samples every 100), a
four-point inner-groove load Qmax cos^1.5(psi - 270 deg) split over two arcs, and a constant
power loss. The expected numbers below follow from these by hand (see each check).

Exit codes: 0 pass, 1 fail, 77 skipped (h5py or numpy missing for the test itself).
"""
import json
import math
import os
import subprocess
import sys
import tempfile

try:
    import h5py
    import numpy as np
except ImportError as err:
    print(f"SKIP: {err}", file=sys.stderr)
    sys.exit(77)

T, DT, N = 600, 1e-4, 8  # samples, output interval (s), balls; default window = samples 300 .. 599
W_CAGE, W_EPI, W_ROLL = 200.0, 210.0, 201.0  # rad/s: cage, epicyclic (nominal angle), at the rolling angle
R_WHIRL, CX, CY = 20e-6, 5e-6, -10e-6  # m
W_WHIRL = 2 * math.pi * 3 / (300 * DT)  # 3 whirl periods per 300-sample window
PITCH = 0.05
QMAX = 1500.0
LAND = 1e-4
#: Bearing attributes of layout version 3 for the contact-angle resolution: 10 mm balls, grooves
#: 0.52 D and 0.53 D, positions to 1e-8 m: resolution 1e-8 / (0.02 x 10 mm) = 5e-5 rad = 0.00286 deg.
GEOMETRY = {"element_radius": 0.005, "inner_groove_radius": 0.0052, "outer_groove_radius": 0.0053,
            "element_position_tolerance": 1e-8, "pitch_radius": PITCH}
RESOLUTION = 1e-8 / 2e-4
FRONT_F, REAR_F = 40.0, 25.0

failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print(f"FAIL: {what}", file=sys.stderr)


def near(value, expected, tol, what):
    ok = value is not None and abs(value - expected) <= tol
    check(ok, f"{what}: {value} not within {tol} of {expected}")


def pulses(first, on, period, height):
    v = np.zeros(T)
    for s in range(first, T, period):
        v[s:s + on] = height
    return v


def write_spatial(path, direction=1, drop=None, model_kind="spatial", contact_angle=None, transient=1.0,
                  pinned=False):
    """A synthetic spatial run; direction -1 turns everything the other way (cage speed, whirl, balls,
    circumferential forces), so front and rear must come out the same. contact_angle: the inner
    groove's contact angle [rad] (with the bearing attributes of layout version 3 that set its
    resolution); transient: the pocket forces and the power loss of the first tenth of the run
    times this (a start-up); pinned: the cage centre still on its land (a cage_land contact at every
    sample) instead of whirling."""
    t = np.arange(T) * DT
    wc, we, ww = direction * W_CAGE, direction * W_EPI, direction * W_WHIRL
    with h5py.File(path, "w") as f:
        def ds(name, data, units=""):
            if name == drop:
                return
            d = f.create_dataset(name, data=np.asarray(data, dtype=float))
            d.attrs["units"] = units
            d.attrs["description"] = "synthetic"

        ds("time", t, "s")
        ds("energy", np.zeros(T), "J")
        th = ww * t
        if pinned:  # on the land at -y, trembling by 1 nm: no turn about its centre
            jitter = 1e-9 * np.sin(2 * math.pi * np.arange(T) / 7)
            ds("cage/position", np.stack([jitter, np.full(T, -LAND) + jitter, np.zeros(T)], 1), "m")
            ds("cage/velocity", np.stack([jitter / DT, jitter / DT, np.zeros(T)], 1), "m/s")
        else:
            ds("cage/position", np.stack([CX + R_WHIRL * np.cos(th), CY + R_WHIRL * np.sin(th), np.zeros(T)], 1), "m")
            ds("cage/velocity", np.stack([-R_WHIRL * ww * np.sin(th), R_WHIRL * ww * np.cos(th), np.zeros(T)], 1),
               "m/s")
        ds("cage/angular_velocity", np.stack([np.zeros(T), np.zeros(T), np.full(T, wc)], 1), "rad/s")
        ds("cage/angles", np.stack([np.zeros(T), np.zeros(T), wc * t], 1), "rad")
        ds("cage/epicyclic_speed", np.full(T, we), "rad/s")
        ds("cage/rolling_speed", np.full(T, direction * W_ROLL), "rad/s")
        for ring in ("inner_ring", "outer_ring"):
            ds(f"{ring}/position", np.zeros((T, 3)), "m")
        psi = wc * t[:, None] + 2 * math.pi * np.arange(N)[None, :] / N  # [T x N]
        ds("balls/position", np.stack([PITCH * np.cos(psi), PITCH * np.sin(psi), np.zeros((T, N))], 2), "m")
        ds("balls/velocity", np.zeros((T, N, 3)), "m/s")

        # Pockets: one column per ball; the cage pushes the ball back (front bar) in pocket 0 and
        # forward (rear bar) in pocket 3, in the sense of rotation.
        fn = np.zeros((T, N))
        fc = np.zeros((T, N))
        fn[:, 0] = pulses(10, 5, 50, FRONT_F)
        fc[:, 0] = -direction * fn[:, 0]
        fn[:, 3] = pulses(20, 8, 100, REAR_F)
        fc[:, 3] = direction * fn[:, 3]
        fn[:T // 10] *= transient
        fc[:T // 10] *= transient
        g = "segments/ball_pocket/"
        f.create_dataset(g + "names", data=[f"pocket_{k}" for k in range(N)], dtype=h5py.string_dtype())
        ds(g + "ball", np.arange(N), "-")
        ds(g + "normal_force", fn, "N")
        ds(g + "circumferential_force", fc, "N")

        # Inner groove, four-point: arcs a and b of each ball carry 60 % and 40 % of its load.
        c = np.cos(np.mod(psi, 2 * math.pi) - 1.5 * math.pi)
        q = np.where(c > 0, QMAX * np.clip(c, 0, None) ** 1.5, 0.0)
        arcs = np.empty((T, 2 * N))
        arcs[:, 0::2] = 0.6 * q
        arcs[:, 1::2] = 0.4 * q
        g = "segments/ball_inner_groove/"
        f.create_dataset(g + "names", data=[f"ball_{k}_{a}" for k in range(N) for a in "ab"],
                         dtype=h5py.string_dtype())
        ds(g + "ball", np.repeat(np.arange(N), 2), "-")
        ds(g + "normal_force", arcs, "N")
        power = np.full((T, 2 * N), 0.5)
        power[:T // 10] *= transient
        ds(g + "power_loss", power, "W")
        if contact_angle is not None:
            ds(g + "contact_angle", np.full((T, 2 * N), contact_angle), "rad")
            f.attrs["layout_version"] = np.int64(3)
            for key, value in GEOMETRY.items():
                f.attrs[key] = value
        if pinned:
            g = "segments/cage_land/"
            f.create_dataset(g + "names", data=["cage_land"], dtype=h5py.string_dtype())
            ds(g + "element", [-1], "-")
            ds(g + "normal_force", np.full((T, 1), 15.0), "N")

        if model_kind is not None:
            f.attrs["model_kind"] = model_kind
        f.attrs["ball_count"] = np.int64(N)
        f.attrs["pitch_radius"] = PITCH
        f.attrs["pocket_clearance"] = 2e-4
        f.attrs["land_clearance"] = LAND
        f.attrs["scene_text"] = '[cage]\nguidance = "inner_land"\n'


def run(raceway, *args, env=None):
    e = dict(os.environ)
    e.update(env or {})
    p = subprocess.run([raceway, "report", *args], capture_output=True, text=True, env=e, timeout=300)
    return p.returncode, p.stdout, p.stderr


def check_summary(s, window_samples=300, direction=1, rolling=True):
    """The numbers of write_spatial(), by hand (rolling=False: a file without /cage/rolling_speed,
    as written before it existed: no rolling keys)."""
    near(s["window"]["samples"], window_samples, 0, "window samples")
    check("rollers" not in s, "a ball run has no roller section")
    cs = s["cage_speed"]
    near(cs["mean_rad_s"], direction * W_CAGE, 1e-9, "cage speed")
    near(cs["mean_rpm"], direction * W_CAGE * 60 / (2 * math.pi), 1e-7, "cage rpm")
    near(cs["epicyclic_rad_s"], direction * W_EPI, 1e-9, "epicyclic speed")
    near(cs["slip_nominal"], 1 - W_CAGE / W_EPI, 1e-12, "slip at the nominal contact angle")
    near(cs["slip"], 1 - W_CAGE / (W_ROLL if rolling else W_EPI), 1e-12, "slip (loaded angle where the file has it)")
    if rolling:
        near(cs.get("rolling_rad_s", math.nan), direction * W_ROLL, 1e-9, "kinematic speed at the rolling angle")
        check("slip_rolling" not in cs, "one slip: no second slip key")
    else:
        check("rolling_rad_s" not in cs, "no rolling keys without /cage/rolling_speed")
    near(cs["direction"], direction, 0, "direction")
    c = s["cage_centroid"]
    near(c["centre_x_m"], CX, 1e-12, "centre x")
    near(c["centre_y_m"], CY, 1e-12, "centre y")
    near(c["vortex_radius_mean_m"], R_WHIRL, 1e-12, "vortex radius")
    near(c["vortex_radius_ratio"], 0.0, 1e-6, "vortex radius ratio (circle)")
    near(c["sigma_v"], 0.0, 1e-9, "sigma_v (constant speed)")
    near(c["speed_mean_m_s"], R_WHIRL * W_WHIRL, 1e-9, "centroid speed")
    near(c["whirl_frequency_rad_s"], direction * W_WHIRL, 1e-6 * W_WHIRL, "whirl frequency")
    near(c["whirl_to_cage_speed_ratio"], W_WHIRL / W_CAGE, 1e-6, "whirl / cage speed")
    near(c["land_clearance_m"], 1e-4, 0, "land clearance")
    p = s["pocket_forces"]
    near(p["threshold_n"], 0.01 * FRONT_F, 1e-12, "contact threshold")
    win_len = (window_samples - 1) * DT
    first = T - window_samples
    # Front: pulses at 10 + 50 j, 5 samples; rear: 20 + 100 j, 8 samples (all inside the window).
    n_front = len([s0 for s0 in range(10, T, 50) if s0 >= first])
    n_rear = len([s0 for s0 in range(20, T, 100) if s0 >= first])
    near(p["front"]["events"], n_front, 0, "front events")
    near(p["rear"]["events"], n_rear, 0, "rear events")
    near(p["front"]["impulse_n_s"], n_front * 5 * DT * FRONT_F, 1e-12, "front impulse")
    near(p["rear"]["impulse_n_s"], n_rear * 8 * DT * REAR_F, 1e-12, "rear impulse")
    fi, ri = n_front * 5 * FRONT_F, n_rear * 8 * REAR_F
    near(p["rear_impulse_fraction"], ri / (fi + ri), 1e-12, "rear impulse fraction")
    pf, pr = p["front_per_pocket"], p["rear_per_pocket"]
    near(pf["events"][0], n_front, 0, "pocket 0 front events")
    near(pr["events"][0], 0, 0, "pocket 0 rear events")
    near(pr["events"][3], n_rear, 0, "pocket 3 rear events")
    near(pf["events"][3], 0, 0, "pocket 3 front events")
    near(pf["mean_duration_s"][0], 5 * DT, 1e-15, "pocket 0 front duration")
    near(pf["duty_cycle"][0], n_front * 5 * DT / win_len, 1e-12, "pocket 0 front duty cycle")
    near(pf["rms_n"][0], FRONT_F * math.sqrt(n_front * 5 * DT / win_len), 1e-9, "pocket 0 front RMS")
    near(pf["peak_n"][0], FRONT_F, 0, "pocket 0 front peak")
    near(pr["peak_n"][3], REAR_F, 0, "pocket 3 rear peak")
    near(p["rms_circumferential_force_n"],
         math.sqrt((FRONT_F ** 2 * n_front * 5 + REAR_F ** 2 * n_rear * 8) * DT / (N * win_len)), 1e-9,
         "circumferential RMS")
    az = s["azimuth"]
    near(az["bin_width_deg"], 5.0, 0, "bin width")
    check(len(az["bin_centre_deg"]) == 72, "72 azimuth bins")
    for key in ("front_force_mean_n", "front_force_max_n", "rear_force_mean_n", "ball_load_mean_n"):
        check(len(az[key]) == 72, f"azimuth/{key} has 72 bins")
    check(max(v for v in az["front_force_max_n"] if v is not None) == FRONT_F, "front max per bin")
    bl = s["ball_load"]
    near(bl["max_n"], QMAX, 1e-3 * QMAX, "max ball load (sum of both arcs)")
    near(bl["max_azimuth_deg"], 270, 1.2, "azimuth of the max ball load")
    near(bl["load_zone_start_deg"], 180, 5.0 + 1e-9, "load zone start")
    end = bl["load_zone_end_deg"]
    near(min(end, 360 - end), 0, 5.0 + 1e-9, "load zone end")
    near(bl["load_zone_width_deg"], 180, 10.0, "load zone width")
    near(s["power_loss"]["total_mean_w"], 2 * N * 0.5, 1e-9, "total power loss")


def report_modules(source_dir):
    """The report's own modules, imported here to look inside its figures and page."""
    sys.path.insert(0, os.path.join(source_dir, "io", "report"))
    import matplotlib
    matplotlib.use("Agg")
    import report_data
    import report_page
    import report_plots
    import report_summary
    return report_data, report_summary, report_plots, report_page


def drawn_limits(report_plots, plot, run, summary, folder):
    """The y-limits of every axes of one figure, taken as it is saved."""
    limits = {}
    original = report_plots.save

    def keep(fig, folder_, name):
        limits[name] = [ax.get_ylim() for ax in fig.axes if ax.name != "polar"]
        limits[name + ":texts"] = [t.get_text() for ax in fig.axes for t in ax.texts]
        return original(fig, folder_, name)
    report_plots.save = keep
    try:
        plot(run, summary, folder)
    finally:
        report_plots.save = original
    return limits


def case_contact_angle(raceway, work):
    """A deep groove bearing under radial load: contact angles of 1e-10 rad (the rounding of a
    ball centred in its groove) are below the model's resolution, so 0 and no figure; 0.2 rad is
    reported as it is."""
    for angle, shown in ((2e-10, 0.0), (0.2, 0.2)):
        h5 = os.path.join(work, f"angle_{angle}.h5")
        write_spatial(h5, contact_angle=angle)
        folder = os.path.join(work, f"angle_{angle}")
        rc, out, err = run(raceway, h5, "-o", folder)
        check(rc == 0, f"contact angle {angle}: exit code {rc}; stderr:\n{err}")
        with open(os.path.join(folder, "summary.json")) as fh:
            ca = json.load(fh)["contact_angle"]
        near(ca["resolution_deg"], math.degrees(RESOLUTION), 1e-12, "contact-angle resolution")
        near(ca["ball_inner_groove_loaded_mean_deg"], math.degrees(shown), 1e-9, f"contact angle {angle} rad")
        near(ca["ball_inner_groove_max_deg"], math.degrees(shown), 1e-9, f"largest contact angle {angle} rad")
        drawn = os.path.isfile(os.path.join(folder, "contact_angle.png"))
        check(drawn == (shown > 0), f"contact angle {angle} rad: figure {'drawn' if drawn else 'left out'}")
        with open(os.path.join(folder, "report.html"), encoding="utf-8") as fh:
            page = fh.read()
        if shown == 0:
            check("below the model&#x27;s resolution" in page or "below the model's resolution" in page,
                  "the page says the angle is below the resolution")
            check("e-08 deg" not in page and "e-09 deg" not in page, "no angle of rounding noise on the page")


def case_window_scale(source_dir, work):
    """A start-up 50 times the steady pocket forces and power loss in the first tenth of the run: the
    time plots' vertical axes still fit the window's values (40 N front, 25 N rear, 8 W)."""
    h5 = os.path.join(work, "transient.h5")
    write_spatial(h5, transient=50.0)
    report_data, report_summary, report_plots, _ = report_modules(source_dir)
    bearing = report_data.read_run(h5)
    summary, _ = report_summary.summarize(bearing)
    limits = drawn_limits(report_plots, report_plots.pocket_force_time, bearing, summary, work)
    lo, hi = limits["pocket_force_time.png"][0]
    check(FRONT_F <= hi <= 1.25 * FRONT_F and -1.25 * REAR_F <= lo <= -REAR_F,
          f"pocket force axis {lo:.4g} .. {hi:.4g} N, expected about -{REAR_F} .. {FRONT_F} (the window)")
    check(any("off scale" in t for t in limits["pocket_force_time.png:texts"]), "the clipped start-up is named")
    limits = drawn_limits(report_plots, report_plots.friction, bearing, summary, work)
    lo, hi = limits["friction.png"][-1]
    check(hi <= 1.2 * 2 * N * 0.5, f"power loss axis up to {hi:.4g} W, the window has {2 * N * 0.5} W")


def case_whirl(raceway, source_dir, work):
    """A cage pinned on its land (land contact at every sample, the centre still): no whirl, the
    vortex metrics null and said to be undefined, in the summary, the log and the page."""
    h5 = os.path.join(work, "pinned.h5")
    write_spatial(h5, pinned=True)
    folder = os.path.join(work, "pinned")
    rc, out, err = run(raceway, h5, "-o", folder)
    check(rc == 0, f"pinned cage: exit code {rc}; stderr:\n{err}")
    with open(os.path.join(folder, "summary.json")) as fh:
        c = json.load(fh)["cage_centroid"]
    check(c.get("whirl") == "pinned_on_land", f"whirl state {c.get('whirl')}, expected pinned_on_land")
    for key in ("sigma_v", "vortex_radius_ratio", "whirl_frequency_rad_s", "whirl_to_cage_speed_ratio"):
        check(c.get(key, 0.0) is None, f"{key} = {c.get(key)} for a pinned cage, expected null")
    near(c["axis_radius_mean_m"], LAND, 1e-8, "the pinned centre's distance from the axis")
    check("undefined" in err and "pinned on its land" in err, f"the log says the metrics are undefined:\n{err}")
    with open(os.path.join(folder, "report.html"), encoding="utf-8") as fh:
        page = fh.read()
    check("sigma_v" not in page and "pinned on its land" in page, "the page names no whirl metric for a pinned cage")
    # A whirling cage keeps them, with its state.
    h5 = os.path.join(work, "whirl.h5")
    write_spatial(h5)
    _, report_summary, _, _ = report_modules(source_dir)
    import report_data
    summary, lines = report_summary.summarize(report_data.read_run(h5))
    check(summary["cage_centroid"]["whirl"] == "whirling", "a whirling cage is whirling")
    check(any("sigma_v" in line for line in lines), "a whirling cage's log line gives sigma_v")


def case_page(source_dir, work):
    """The page's table: line contacts get one kinematic cage speed row (the nominal and loaded angle
    are one), ball bearings two; the contacts and the impacts rows say what each counts."""
    h5 = os.path.join(work, "run.h5")
    write_spatial(h5)
    report_data, report_summary, _, report_page = report_modules(source_dir)
    summary, _ = report_summary.summarize(report_data.read_run(h5))
    labels = [k for k, _ in report_page.rows(summary, "ball")]
    check(sum("kinematic cage speed" in k for k in labels) == 2, f"ball bearing: two kinematic rows: {labels}")
    # A deep groove bearing under radial load: the loaded angle's speed is the nominal one's.
    cs = summary["cage_speed"]
    loaded = dict(summary, cage_speed=dict(cs, rolling_rpm=cs["epicyclic_rpm"] * (1 + 1e-9)))
    labels = [k for k, _ in report_page.rows(loaded, "ball")]
    check(sum("kinematic cage speed" in k for k in labels) == 1, f"equal kinematic speeds: one row: {labels}")
    summary["model_kind"] = "planar"
    summary["cage_speed"]["rolling_rpm"] = summary["cage_speed"]["epicyclic_rpm"]
    rows = report_page.rows(summary, "ball")
    kinematic = [(k, v) for k, v in rows if "kinematic cage speed" in k]
    check(len(kinematic) == 1, f"line contacts: one kinematic row, got {kinematic}")
    values = [v for _, v in rows]
    check(len(values) == len(set(values)) or all(values.count(v) == 1 for v in values if "rpm" in v),
          f"no repeated speed rows: {rows}")
    contacts = [k for k, _ in rows if k.startswith("pocket contacts")]
    impacts = [k for k, _ in rows if k.startswith("pocket impacts")]
    check(len(contacts) == 1 and "window" in contacts[0] and "at every integrator step" not in contacts[0],
          f"contacts row: {contacts}")
    check(len(impacts) == 1 and "whole run" in impacts[0] and "above" in impacts[0], f"impacts row: {impacts}")


def case_campaign_plot(source_dir, work):
    """A speed sweep given in rpm is drawn in rpm (not its SI rad/s), with readable labels, 1200 px wide."""
    sys.path.insert(0, os.path.join(source_dir, "io", "report"))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import campaign_table
    manifest = {"campaign": "sweep", "axes": {"speed": "inner_ring.speed"}, "axis_units": {"speed": "rad/s"}}
    rows = [{"speed": f"{v} rpm", "speed_si": v * math.pi / 30, "cage_speed_rpm": 0.4 * v, "status": "done"}
            for v in (1000, 2000, 3000)]
    os.makedirs(os.path.join(work, "plots"), exist_ok=True)
    figures = []

    class Recorder:
        def subplots(self, *a, **k):
            fig, ax = plt.subplots(*a, **k)
            figures.append((fig, ax))
            return fig, ax

        def close(self, fig):
            pass
    path = campaign_table._draw_trend(work, manifest, rows, "speed", "cage_speed_rpm", Recorder())
    fig, ax = figures[0]
    x = list(ax.lines[0].get_xdata())
    check(x == [1000.0, 2000.0, 3000.0], f"x values {x}, expected the sweep's rpm")
    check("[rpm]" in ax.get_xlabel() and "rad/s" not in ax.get_xlabel(), f"x label '{ax.get_xlabel()}'")
    check("_" not in ax.get_ylabel() and "_" not in ax.get_xlabel(), f"raw column names: '{ax.get_xlabel()}', "
          f"'{ax.get_ylabel()}'")
    width = fig.get_size_inches()[0] * fig.dpi
    with open(path, "rb") as fh:
        head = fh.read(24)
    png_width = int.from_bytes(head[16:20], "big")
    check(png_width >= 1200, f"plot {png_width} px wide (figure {width:.0f} px), expected >= 1200")
    plt.close(fig)


PLOTS = ["cage_speed.png", "cage_centroid.png", "pocket_force_time.png", "pocket_force_azimuth.png",
         "ball_load_azimuth.png", "friction.png"]


def main():
    case, raceway, source_dir = sys.argv[1:4]
    with tempfile.TemporaryDirectory(prefix=f"raceway_report_{case}.") as work:
        h5 = os.path.join(work, "run.h5")
        if case == "spatial":
            write_spatial(h5)
            rc, out, err = run(raceway, h5)
            check(rc == 0, f"exit code {rc}, expected 0; stderr:\n{err}")
            folder = os.path.join(work, "run_report")
            summary = os.path.join(folder, "summary.json")
            check(os.path.isfile(summary), "summary.json beside the input in run_report/")
            if os.path.isfile(summary):
                with open(summary) as fh:
                    check_summary(json.load(fh))
            for png in PLOTS:
                p = os.path.join(folder, png)
                size = os.path.getsize(p) if os.path.isfile(p) else 0
                check(size > 1000, f"{png} missing or empty ({size} bytes); stderr:\n{err}")
                check(size < 400_000, f"{png} is {size} bytes, expected a PNG of a few hundred kB at most")
                if size:
                    with open(p, "rb") as fh:
                        check(fh.read(8) == b"\x89PNG\r\n\x1a\n", f"{png} is not a PNG")
            page = os.path.join(folder, "report.html")
            check(os.path.isfile(page) and os.path.getsize(page) > 10000, "report.html with its figures")
        elif case == "reverse":
            # Cage turning in -z with the circumferential signs flipped: the same bars.
            # Also a file without /cage/rolling_speed (older runs): read all the same.
            write_spatial(h5, direction=-1, drop="cage/rolling_speed")
            out_dir = os.path.join(work, "custom")
            rc, out, err = run(raceway, h5, "-o", out_dir, "--no-plots")
            check(rc == 0, f"exit code {rc}, expected 0; stderr:\n{err}")
            with open(os.path.join(out_dir, "summary.json")) as fh:
                s = json.load(fh)
            # The ball load zone turns with the balls' azimuths, which are the same set of angles.
            check_summary(s, direction=-1, rolling=False)
            check(not any(n.endswith(".png") for n in os.listdir(out_dir)), "--no-plots wrote PNGs")
        elif case == "options":
            write_spatial(h5)
            out_dir = os.path.join(work, "all")
            rc, out, err = run(raceway, h5, "-o", out_dir, "--no-plots", "--window-start", "0", "--bin-width", "10")
            check(rc == 0, f"exit code {rc}, expected 0; stderr:\n{err}")
            with open(os.path.join(out_dir, "summary.json")) as fh:
                s = json.load(fh)
            near(s["window"]["samples"], T, 0, "--window-start 0: all samples")
            near(s["pocket_forces"]["front"]["events"], 12, 0, "--window-start 0: front pulses 10, 60, ..., 560")
            near(s["pocket_forces"]["rear"]["events"], 6, 0, "--window-start 0: rear pulses 20, ..., 520")
            check(len(s["azimuth"]["bin_centre_deg"]) == 36, "--bin-width 10: 36 bins")
            rc, out, err = run(raceway, h5, "-o", out_dir, "--bin-width", "0", "--no-plots")
            check(rc == 2, f"--bin-width 0: exit code {rc}, expected 2 (a bad option)")
            check("bin" in err, f"--bin-width 0: stderr does not mention the bin width:\n{err}")
        elif case == "bad_inputs":
            rc, out, err = run(raceway, os.path.join(work, "missing.h5"))
            check(rc == 2, f"missing file: exit code {rc}, expected 2")
            check("missing.h5" in err and "no such file" in err, f"missing file: stderr:\n{err}")
            text = os.path.join(work, "text.h5")
            with open(text, "w") as fh:
                fh.write("not hdf5\n")
            rc, out, err = run(raceway, text)
            check(rc == 2, f"text file: exit code {rc}, expected 2")
            check("text.h5" in err and "not an HDF5 file" in err, f"text file: stderr:\n{err}")
            # Without model_kind the file is read as planar: it lacks what a planar report needs.
            planar = os.path.join(work, "planar.h5")
            write_spatial(planar, model_kind=None)
            rc, out, err = run(raceway, planar)
            check(rc == 2, f"planar run: exit code {rc}, expected 2")
            check("planar.h5" in err and "/rollers/position" in err, f"planar run: stderr:\n{err}")
            nods = os.path.join(work, "nods.h5")
            write_spatial(nods, drop="cage/epicyclic_speed")
            rc, out, err = run(raceway, nods)
            check(rc == 2, f"missing dataset: exit code {rc}, expected 2")
            check("nods.h5" in err and "/cage/epicyclic_speed" in err, f"missing dataset: stderr:\n{err}")
            check(not os.path.exists(os.path.join(work, "nods_report", "summary.json")),
                  "a bad input wrote a summary")
        elif case == "no_python":
            # No interpreter, then a report script that finds no numpy or h5py (exit 3): the
            # report fails (exit 1 and 3), says why and writes nothing.
            write_spatial(h5)
            rc, out, err = run(raceway, h5, env={"RACEWAY_PYTHON": os.path.join(work, "no_python3")})
            check(rc == 1, f"no python: exit code {rc}, expected 1")
            check("no python interpreter" in err, f"no python: stderr:\n{err}")
            check(not os.path.exists(os.path.join(work, "run_report")), "no python: wrote a report folder")
            fake = os.path.join(work, "fake_report.py")
            with open(fake, "w") as fh:
                fh.write("import sys\nsys.exit(3)\n")
            rc, out, err = run(raceway, h5, env={"RACEWAY_REPORT_SCRIPT": fake})
            check(rc == 3, f"no numpy: exit code {rc}, expected 3")
            check("lacks numpy or h5py" in err, f"no numpy: stderr:\n{err}")
        elif case == "contact_angle":
            case_contact_angle(raceway, work)
        elif case == "window_scale":
            case_window_scale(source_dir, work)
        elif case == "whirl":
            case_whirl(raceway, source_dir, work)
        elif case == "page":
            case_page(source_dir, work)
        elif case == "campaign_plot":
            case_campaign_plot(source_dir, work)
        else:
            print(f"unknown case {case}", file=sys.stderr)
            return 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
