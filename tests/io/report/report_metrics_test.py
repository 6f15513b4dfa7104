#!/usr/bin/env python3
"""The cage-centre vortex metrics of io/report/report_metrics.py on synthetic orbits with known
answers (seed 001 eq. 9: vortex radius ratio (max - min) / mean radius, sigma_v std / mean speed).

    report_metrics_test.py SOURCE_DIR        exit 0 pass, 1 fail, 77 numpy missing
"""
import math
import sys

try:
    import numpy as np
except ImportError as err:
    print(f"SKIP: {err}", file=sys.stderr)
    sys.exit(77)
sys.path.insert(0, f"{sys.argv[1]}/io/report")
import report_metrics as rm  # noqa: E402

failures = []


def near(value, expected, tol, what):
    if not abs(value - expected) <= tol:
        failures.append(what)
        print(f"FAIL: {what}: {value} not within {tol} of {expected}", file=sys.stderr)


def orbit(a, b, turns, samples, centre=(7e-6, -4e-6), tilt=0.5):
    """An ellipse (semi-axes a, b, turned by tilt) swept `turns` times at a steady parametric rate
    over `samples` samples 0.1 ms apart: time, x, y, vx, vy and the whole window."""
    t = np.arange(samples) * 1e-4
    w = 2 * math.pi * turns / (samples * 1e-4)
    u, v = a * np.cos(w * t), b * np.sin(w * t)
    du, dv = -a * w * np.sin(w * t), b * w * np.cos(w * t)
    c, s = math.cos(tilt), math.sin(tilt)
    x, y = centre[0] + c * u - s * v, centre[1] + s * u + c * v
    return t, x, y, c * du - s * dv, s * du + c * dv, rm.select_window(t, start=0.0)


# A perfect circle swept 4.5 times: about the mean of all its samples (1 / (4.5 pi) of the radius
# off the centre) the ratio would be 2 / (4.5 pi) = 0.14; over its last 4 whole turns it is 0.
t, x, y, vx, vy, w = orbit(100e-6, 100e-6, 4.5, 2700)
r_mean_centre = np.hypot(x - x.mean(), y - y.mean())
near((r_mean_centre.max() - r_mean_centre.min()) / r_mean_centre.mean(), 2 / (4.5 * math.pi), 0.01,
     "the bias of the window's mean centre (the trap the metric avoids)")
m = rm.centroid_metrics(t, x, y, vx, vy, w, 1.0)
near(m["vortex_radius_ratio"], 0.0, 1e-9, "circle swept 4.5 times: vortex radius ratio")
near(m["vortex_turns"], 4, 0, "circle swept 4.5 times: whole turns")
near(m["vortex_window_s"], 2400 * 1e-4 - 1e-4, 1e-12, "the last 4 turns: 2400 samples")
near(m["centre_x_m"], 7e-6, 1e-15, "circle centre x")
near(m["sigma_v"], 0.0, 1e-9, "circle at a steady speed: sigma_v")
near(m["whirl_revolutions"], 4.5 * 2699 / 2700, 1e-9, "whirl turns in the window")

# An ellipse a = 100 um, b = 80 um swept 4.5 times: the radius about its centre runs from b to a,
# its mean over whole turns is the perimeter / 2 pi (Ramanujan's perimeter, exact to 1e-9 here);
# the speed w sqrt(a^2 sin^2 + b^2 cos^2) has std / mean from a fine quadrature.
a, b = 100e-6, 80e-6
mean_r = math.pi * (3 * (a + b) - math.sqrt((3 * a + b) * (a + 3 * b))) / (2 * math.pi)
m = rm.centroid_metrics(*orbit(a, b, 4.5, 2700), 1.0)
near(m["vortex_radius_ratio"], (a - b) / mean_r, 1e-6, "ellipse: (a - b) / mean radius")
phase = np.linspace(0, 2 * math.pi, 200001)[:-1]
speed = np.hypot(a * np.sin(phase), b * np.cos(phase))
near(m["sigma_v"], speed.std() / speed.mean(), 1e-4, "ellipse: sigma_v")

# A window that ends before the run: its whole turns end with it (the first 2.5 of the 4.5 turns).
t, x, y, vx, vy, _ = orbit(100e-6, 100e-6, 4.5, 2700)
m = rm.centroid_metrics(t, x, y, vx, vy, rm.Window(0, 1500, 0.0, t[1499], False), 1.0)
near(m["vortex_turns"], 2, 0, "the first 2.5 turns: 2 whole turns")
near(m["vortex_window_start_s"], 300 * 1e-4, 1e-12, "... from sample 300")
near(m["vortex_window_s"], 1199 * 1e-4, 1e-12, "... to sample 1499")
near(m["vortex_radius_ratio"], 0.0, 1e-9, "... a circle: ratio 0")

# Less than one turn: no whole turn to take, the whole window about its mean centre.
t, x, y, vx, vy, w = orbit(100e-6, 100e-6, 0.6, 600)
m = rm.centroid_metrics(t, x, y, vx, vy, w, 1.0)
near(m["vortex_turns"], 0, 0, "0.6 turns: no whole turn")
near(m["vortex_window_s"], w.length, 0, "0.6 turns: the whole window")
sys.exit(1 if failures else 0)
