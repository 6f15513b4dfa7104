"""The tables and formulas of ISO 281:2007 (basic and modified rating life), ISO 76:2006 (basic
static load rating) and ISO/TS 16281:2008 (reference rating life from the rolling-element loads),
as pure functions of numbers in the standards' units: millimetres, newtons, r/min, mm^2/s.

docs/life.md gives every formula with its source and a worked example; report_life.py applies them
to a run. Written by hand: no Debian package implements these standards (a few dozen lines of
tables and closed forms; each table is linearly interpolated between its rows, as the standards allow).
"""
import math

import numpy as np

# ISO 281:2007, the table of f_c for radial ball bearings, first column (single-row radial contact
# groove ball bearings and single- and double-row angular contact groove ball bearings): f_c against
# D_w cos(alpha) / D_pw.
BALL_FC = ((0.01, 29.1), (0.02, 35.8), (0.03, 40.3), (0.04, 43.8), (0.05, 46.7), (0.06, 49.1), (0.07, 51.1),
           (0.08, 52.8), (0.09, 54.3), (0.10, 55.5), (0.12, 57.5), (0.14, 58.8), (0.16, 59.6), (0.18, 59.9),
           (0.20, 59.9), (0.22, 59.6), (0.24, 59.0), (0.26, 58.2), (0.28, 57.1), (0.30, 56.0), (0.32, 54.6),
           (0.34, 53.2), (0.36, 51.7), (0.38, 50.0), (0.40, 48.4))
# ISO 281:2007, the table of f_c for radial roller bearings: f_c against D_we cos(alpha) / D_pw.
ROLLER_FC = ((0.01, 52.1), (0.02, 60.8), (0.03, 66.5), (0.04, 70.7), (0.05, 74.1), (0.06, 76.9), (0.07, 79.2),
             (0.08, 81.2), (0.09, 82.8), (0.10, 84.2), (0.11, 85.4), (0.12, 86.4), (0.13, 87.1), (0.14, 87.7),
             (0.15, 88.2), (0.16, 88.5), (0.17, 88.7), (0.18, 88.8), (0.19, 88.8), (0.20, 88.7), (0.21, 88.5),
             (0.22, 88.2), (0.23, 87.9), (0.24, 87.5), (0.25, 87.0), (0.26, 86.4), (0.27, 85.8), (0.28, 85.2),
             (0.29, 84.5), (0.30, 83.8))
# ISO 76:2006, the table of f_0 (radial contact groove and angular contact groove ball bearings): f_0 against
# D_w cos(alpha) / D_pw.
BALL_F0 = ((0.00, 14.7), (0.01, 14.9), (0.02, 15.1), (0.03, 15.3), (0.04, 15.5), (0.05, 15.7), (0.06, 15.9),
           (0.07, 16.1), (0.08, 16.3), (0.09, 16.5), (0.10, 16.4), (0.11, 16.1), (0.12, 15.9), (0.13, 15.6),
           (0.14, 15.4), (0.15, 15.2), (0.16, 14.9), (0.17, 14.7), (0.18, 14.4), (0.19, 14.2), (0.20, 14.0),
           (0.21, 13.7), (0.22, 13.5), (0.23, 13.2), (0.24, 13.0), (0.25, 12.8), (0.26, 12.5), (0.27, 12.3),
           (0.28, 12.1), (0.29, 11.8), (0.30, 11.6), (0.31, 11.4), (0.32, 11.2), (0.33, 10.9), (0.34, 10.7),
           (0.35, 10.5), (0.36, 10.3), (0.37, 10.0), (0.38, 9.8), (0.39, 9.6), (0.40, 9.4))
# ISO 281:2007, the table of X, Y and e of radial ball bearings, single-row radial contact groove ball
# bearings (normal clearance): f_0 F_a / C_0r, e, and Y for F_a / F_r > e (X = 0.56 there; X = 1,
# Y = 0 for F_a / F_r <= e).
DEEP_GROOVE_XY = ((0.172, 0.19, 2.30), (0.345, 0.22, 1.99), (0.689, 0.26, 1.71), (1.03, 0.28, 1.55),
                  (1.38, 0.30, 1.45), (2.07, 0.34, 1.31), (3.45, 0.38, 1.15), (5.17, 0.42, 1.04), (6.89, 0.44, 1.00))
# The same table, angular contact groove ball bearings: alpha (deg), e, then (X, Y) for F_a / F_r > e
# of a single row, and (Y for F_a / F_r <= e; X, Y for F_a / F_r > e) of a double row (X = 1 at <= e).
ANGULAR_XY = ((25, 0.68, 0.41, 0.87, 0.92, 0.67, 1.41), (30, 0.80, 0.39, 0.76, 0.78, 0.63, 1.24),
              (35, 0.95, 0.37, 0.66, 0.66, 0.60, 1.07), (40, 1.14, 0.35, 0.57, 0.55, 0.57, 0.93),
              (45, 1.34, 0.33, 0.50, 0.47, 0.54, 0.81))
# ISO 281:2007, the table of the life modification factor for reliability a_1 against the reliability in percent.
A1 = ((90, 1.0), (95, 0.64), (96, 0.55), (97, 0.47), (98, 0.37), (99, 0.25), (99.2, 0.22), (99.4, 0.19),
      (99.6, 0.16), (99.8, 0.12), (99.9, 0.093), (99.92, 0.087), (99.94, 0.080), (99.95, 0.077))


def interpolate(table, x, column=1):
    """Linear interpolation in a table's first column; None outside it."""
    xs = [row[0] for row in table]
    if not xs[0] - 1e-12 <= x <= xs[-1] + 1e-12:
        return None
    return float(np.interp(x, xs, [row[column] for row in table]))


def dynamic_load_rating(ball, z, dw, dpw, alpha=0.0, lwe=None, rows=1):
    """ISO 281 basic dynamic radial load rating C_r (N) and its f_c, b_m, gamma; C_r None when
    gamma = D_w cos(alpha) / D_pw is outside the standard's table."""
    gamma = dw * math.cos(alpha) / dpw
    if ball:
        fc, bm = interpolate(BALL_FC, gamma), 1.3
        if fc is None:
            return None, fc, bm, gamma
        c = bm * fc * (rows * math.cos(alpha)) ** 0.7 * z ** (2 / 3)
        c *= dw ** 1.8 if dw <= 25.4 else 3.647 * dw ** 1.4
    else:
        fc, bm = interpolate(ROLLER_FC, gamma), 1.1
        if fc is None:
            return None, fc, bm, gamma
        c = bm * fc * (rows * lwe * math.cos(alpha)) ** (7 / 9) * z ** 0.75 * dw ** (29 / 27)
    return c, fc, bm, gamma


def static_load_rating(ball, z, dw, dpw, alpha=0.0, lwe=None, rows=1):
    """ISO 76 basic static radial load rating C_0r (N) and f_0 (None for rollers)."""
    gamma = dw * math.cos(alpha) / dpw
    if ball:
        f0 = interpolate(BALL_F0, gamma)
        return (None if f0 is None else f0 * rows * z * dw ** 2 * math.cos(alpha)), f0
    return 44.0 * (1 - gamma) * rows * z * lwe * dw * math.cos(alpha), None


def fatigue_load_limit(ball, c0, dpw):
    """ISO 281's simple estimate of the fatigue load limit C_u (N) from C_0 (bearings of
    ordinary steel and quality)."""
    if ball:
        return c0 / 22.0 * (1.0 if dpw <= 100 else (100.0 / dpw) ** 0.5)
    return c0 / 8.2 * (1.0 if dpw <= 100 else (100.0 / dpw) ** 0.3)


def equivalent_load(bearing_type, fr, fa, c0=None, f0=None, alpha=0.0):
    """ISO 281 dynamic equivalent radial load P_r = X F_r + Y F_a (N): (P, X, Y, e). Deep groove:
    e and Y from f_0 F_a / C_0r (held at the table's ends); angular contact: single row; four-point
    contact: as a double-row angular contact bearing (makers' practice); cylindrical roller: F_r;
    tapered roller, single row: e = 1.5 tan(alpha), X = 0.4 and Y = 0.4 cot(alpha) above e."""
    if bearing_type == "cylindrical_roller" or fa <= 0:
        return fr, 1.0, 0.0, None
    if bearing_type == "tapered_roller":
        e = 1.5 * math.tan(alpha)
        if fr > 0 and fa / fr <= e:
            return fr, 1.0, 0.0, e
        return 0.4 * fr + 0.4 / math.tan(alpha) * fa, 0.4, 0.4 / math.tan(alpha), e
    y_low = 0.0  # Y for F_a / F_r <= e (X = 1 there)
    if bearing_type == "deep_groove_ball":
        ratio = min(max(f0 * fa / c0, DEEP_GROOVE_XY[0][0]), DEEP_GROOVE_XY[-1][0])
        e, x, y = interpolate(DEEP_GROOVE_XY, ratio, 1), 0.56, interpolate(DEEP_GROOVE_XY, ratio, 2)
    else:
        deg = min(max(math.degrees(alpha), ANGULAR_XY[0][0]), ANGULAR_XY[-1][0])
        e = interpolate(ANGULAR_XY, deg, 1)
        if bearing_type == "angular_contact_ball":
            x, y = interpolate(ANGULAR_XY, deg, 2), interpolate(ANGULAR_XY, deg, 3)
        else:
            y_low, x, y = (interpolate(ANGULAR_XY, deg, c) for c in (4, 5, 6))
    if fr > 0 and fa / fr <= e:
        return fr + y_low * fa, 1.0, y_low, e
    return x * fr + y * fa, x, y, e


def reference_viscosity(n_rpm, dpw):
    """ISO 281 rated viscosity nu_1 (mm^2/s) at speed n (r/min) and pitch diameter D_pw (mm)."""
    if n_rpm < 1000:
        return 45000.0 * n_rpm ** -0.83 * dpw ** -0.5
    return 4500.0 * n_rpm ** -0.5 * dpw ** -0.5


def a_iso(ball, kappa, load_ratio):
    """ISO 281 life modification factor a_ISO for radial bearings from the viscosity ratio kappa
    (used up to 4; None below 0.1, outside the standard) and e_C C_u / P; at most 50."""
    if kappa < 0.1:
        return None
    k = min(kappa, 4.0)
    if ball:
        a, b, c = (2.5671, 2.2649, 0.054381) if k < 0.4 else (2.5671, 1.9987, 0.19087) if k < 1 else \
            (2.5671, 1.9987, 0.071739)
        bracket = 1 - max(a - b / k ** c, 0.0) ** 0.83 * load_ratio ** (1 / 3)
        power = -9.3
    else:
        a, b, c = (1.5859, 1.3993, 0.054381) if k < 0.4 else (1.5859, 1.2348, 0.19087) if k < 1 else \
            (1.5859, 1.2348, 0.071739)
        bracket = 1 - max(a - b / k ** c, 0.0) * load_ratio ** 0.4
        power = -9.185
    return 50.0 if bracket <= 0 else min(0.1 * bracket ** power, 50.0)


def a1(reliability_percent):
    """ISO 281's table of a_1, interpolated between its rows (90 % .. 99.95 %)."""
    return interpolate(A1, reliability_percent)


def contact_ratings(ball, c, z, gamma, alpha=0.0, fi=None, fe=None, rows=1):
    """ISO/TS 16281 dynamic load ratings of one rolling-element contact on the inner and outer ring
    (Q_ci, Q_ce, N) from the bearing's C; balls with the grooves' osculations f_i, f_e; rollers of the
    whole effective length (one lamina: q_c,k = Q_c n_s^(-7/9) for n_s laminae), lambda nu = 0.83."""
    ratio = (1 - gamma) / (1 + gamma)
    if ball:
        osc = (fi * (2 * fe - 1) / (fe * (2 * fi - 1))) ** 0.41
        term = 1.044 * ratio ** 1.72 * osc
        base = c / (z * rows ** 0.7 * math.cos(alpha) ** 0.7)
        return (base / 0.407 * (1 + term ** (10 / 3)) ** 0.3, base / 0.389 * (1 + term ** (-10 / 3)) ** 0.3)
    term = 1.038 * ratio ** (143 / 108)
    base = c / (0.83 * z * rows ** (7 / 9) * math.cos(alpha) ** (7 / 9))
    return (base / 0.378 * (1 + term ** 4.5) ** (2 / 9), base / 0.364 * (1 + term ** -4.5) ** (2 / 9))


def equivalent_contact_load(loads, ball, rotating):
    """ISO/TS 16281 dynamic equivalent load of a raceway track from its contacts' loads (any array:
    elements, and here also the samples of a window, i.e. azimuths): the power mean with exponent 3
    (balls) or 4 (rollers) on the ring that rotates relative to the load, 10/3 or 9/2 on the other."""
    w = (3.0 if rotating else 10 / 3) if ball else (4.0 if rotating else 4.5)
    q = np.asarray(loads, dtype=float)
    return float(np.mean(q ** w) ** (1 / w)) if q.size else 0.0


def reference_life(ball, tracks):
    """ISO/TS 16281 basic reference rating life L10r (10^6 revolutions) from (Q_c, Q_e) of every
    raceway track (inner and outer ring, each arc of a four-point ring): balls
    [sum (Q_c / Q_e)^(-10/3)]^(-9/10), rollers [sum (q_c / q_e)^(-9/2)]^(-8/9); inf when unloaded."""
    e = 10 / 3 if ball else 4.5
    total = sum((qe / qc) ** e for qc, qe in tracks if qe > 0)
    return math.inf if total == 0 else total ** (-(0.9 if ball else 8 / 9))
