#!/usr/bin/env python3
"""Measured rolling friction torque of lubricated ball-race contacts (Balan, Houpert, Tufescu and
Olaru 2015, docs/references.md "Balan 2015": three balls between the races of a 51205, no cage,
spun down in 0.05 Pa s oil) against raceway's EHL rolling resistance and the paper's own
Biboulet-Houpert forces, over the six contacts: Tz = 6 r F_R.

    /usr/bin/python3 perf/studies/rolling_torque_measurement.py

Measured: Tz = K* omega^n (Tables 1 and 2) at each run's initial speed. raceway: the formula of
ehl_rolling_resistance (contact/laws/point_contact.cpp), re-coded here for the table; the test
tests/contact/test_rolling_torque_measurement.cpp calls the C++ function itself. Assumptions not
in the paper: the orbit radius r = 18 mm (the 51205's pitch radius) and alpha = 2e-8 1/Pa.
"""
import math

E_PRIME = 208e9 / (1 - 0.3 ** 2)  # E' = 2 E* of steel on steel (the paper: 2.3e11 Pa)
R = 18e-3                         # orbit radius [m] (assumed)
GROOVE = 4.16e-3                  # races' groove radius [m]
ALPHA = 2e-8                      # pressure-viscosity coefficient [1/Pa] (assumed)
ETA = 0.05                        # oil viscosity [Pa s]
# (ball diameter [m], load per ball [N]) -> runs (initial r/min, K* [N m (s/rad)^n], n)
SERIES = {(3e-3, 0.633): [(60, 4.001e-5, 0.116), (90, 3.287e-5, 0.277), (120, 2.864e-5, 0.318),
                          (150, 2.796e-5, 0.366), (180, 3.21e-5, 0.344), (210, 3.213e-5, 0.339)],
          (6.35e-3, 0.125): [(60, 4.208e-5, 0.652), (90, 3.839e-5, 0.647), (120, 3.943e-5, 0.620),
                             (150, 3.779e-5, 0.654), (180, 3.457e-5, 0.622), (210, 3.354e-5, 0.649)]}


def raceway_force(u, q, rx, ry):
    """ehl_rolling_resistance: 2.86 E' Rx^2 k^0.348 G^0.022 U^0.66 W^0.47, k Hamrock-Brewe."""
    k = 1.0339 * (ry / rx) ** 0.636
    return (2.86 * E_PRIME * rx * rx * k ** 0.348 * (ALPHA * E_PRIME) ** 0.022
            * (ETA * u / (E_PRIME * rx)) ** 0.66 * (q / (E_PRIME * rx * rx)) ** 0.47)


def biboulet_forces(u, q, rx, ry):
    """The paper's eq. 1-4 (k = Ry / Rx): IVR, EHL, transition force and the EHL partition."""
    k = ry / rx
    U, W = ETA * u / (E_PRIME * rx), q / (E_PRIME * rx * rx)
    ivr = 2.9766 * E_PRIME * rx * rx * k ** 0.3316 * W ** (1 / 3) * U ** (2 / 3)
    ehl = 7.5826 * E_PRIME * rx * rx * k ** 0.4055 * W ** (1 / 3) * U ** 0.75
    m = 0.5549 * k ** -0.6029 * W * U ** -0.75
    return ivr, ehl, (ivr - ehl) / (1 + m / 6.6) + ehl, (m / 6.6) / (1 + m / 6.6)


def main():
    print("| d mm | Q N | n r/min | measured N mm | raceway N mm | ratio | Biboulet transition N mm | ratio "
          "| Biboulet IVR N mm | ratio | EHL partition |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for (d, q), runs in SERIES.items():
        rx, ry = d / 2, 1 / (2 / d - 1 / GROOVE)
        for rpm, k_star, n in runs:
            omega = rpm * 2 * math.pi / 60
            u = omega * R / 2
            meas = k_star * omega ** n
            rw = 6 * R * raceway_force(u, q, rx, ry)
            ivr_f, _e, tr_f, part = biboulet_forces(u, q, rx, ry)
            ivr, tr = 6 * R * ivr_f, 6 * R * tr_f
            print(f"| {d * 1e3:.2f} | {q} | {rpm} | {meas * 1e3:.4f} | {rw * 1e3:.4f} | {rw / meas:.2f} "
                  f"| {tr * 1e3:.4f} | {tr / meas:.2f} | {ivr * 1e3:.4f} | {ivr / meas:.2f} | {part:.2f} |")


if __name__ == "__main__":
    main()
