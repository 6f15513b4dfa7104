"""Vibration of a bearing as a sensor on its housing sees it (docs/vibration.md).

    import raceway, raceway.vibration as vib
    with raceway.open_output("run.h5") as out:
        s = vib.sensor_signal(out)                     # t, displacement, velocity, acceleration [N x 2]
        f = vib.characteristic_frequencies(out)        # FTF, BSF, BPFO, BPFI [Hz] from the run's cage speed
        freq, amp = vib.envelope_spectrum(s.acceleration[:, 1], s.rate, vib.resonance_band(out))
        rows = vib.energy_table(freq, amp, f)           # which characteristic frequencies carry energy
        vib.export_csv(out, "sensor.csv")

The spectra, the band-pass and the Hilbert envelope are written with numpy's FFT alone (a few
lines each): scipy would bring some 250 MB of Debian packages to every installation for them.
"""
import csv
import math
from dataclasses import dataclass

import numpy as np


@dataclass
class SensorSignal:
    time: np.ndarray          # [N] s
    displacement: np.ndarray  # [N x 2] m
    velocity: np.ndarray      # [N x 2] m/s
    acceleration: np.ndarray  # [N x 2] m/s^2
    rate: float               # samples per second


def sensor_signal(out, start=0.0):
    """The housing sensor's samples from `start` [s] on (the rows of /housing flattened in time)."""
    f = out.file if hasattr(out, "file") else out
    if "housing" not in f:
        raise KeyError("the output has no /housing: the scene has no [housing]")
    t = np.asarray(f["housing/sensor_time"][1:]).reshape(-1)
    keep = np.isfinite(t) & (t >= start)

    def series(name):
        return np.asarray(f[f"housing/{name}"][1:]).reshape(-1, 2)[keep]

    t = t[keep]
    rate = 1.0 / float(np.median(np.diff(t)))
    return SensorSignal(t, series("displacement"), series("velocity"), series("acceleration"), rate)


def _root_attr(f, name):
    v = f.attrs[name]
    return float(np.asarray(v).reshape(-1)[0])


def characteristic_frequencies(out, cage_hz=None):
    """FTF, BSF, BPFO, BPFI and the shaft frequency [Hz] of the run: from the rings' speeds and the
    cage speed the run measured (summary: cage_speed_rpm), so that they include the cage's slip; the
    kinematic (no-slip) values under the key 'kinematic'. Fixed outer ring, inner ring driven."""
    import json
    f = out.file if hasattr(out, "file") else out
    summary = json.loads(f.attrs["summary_json"])
    z = int(_root_attr(f, "element_count"))
    f_i = abs(float(np.median(np.asarray(f["inner_ring/angular_velocity"])[:, 2]))) / (2 * math.pi)
    d = 2 * _root_attr(f, "element_radius")
    dm = 2 * _root_attr(f, "pitch_radius")
    ratio = d * math.cos(_root_attr(f, "nominal_contact_angle")) / dm
    if _bearing_type(f) == "tapered_roller" and "epicyclic_cage_speed_rpm" in summary:
        # Rollers on two cones about a common apex: the run's own rolling-without-slip cage speed
        # (the summary's, from the cup and cone angles); D cos a / d_m is what gives it here.
        ratio = 1 - 2 * abs(float(summary["epicyclic_cage_speed_rpm"])) / 60.0 / f_i
    no_slip = 0.5 * f_i * (1 - ratio)
    measured = abs(float(summary["cage_speed_rpm"])) / 60.0 if cage_hz is None else cage_hz
    return _frequencies(z, ratio, dm / d, f_i, measured) | {
        "kinematic": _frequencies(z, ratio, dm / d, f_i, no_slip), "slip": 1.0 - measured / no_slip}


def _bearing_type(f):
    value = f.attrs.get("bearing_type", b"")
    return value.decode() if isinstance(value, bytes) else str(value)


def _frequencies(z, ratio, dm_over_d, f_i, f_c):
    """Outer ring fixed, inner ring at f_i, cage at f_c [Hz]; BSF: the ball's spin relative to the
    cage, (d_m / D) (1 - (D cos a / d_m)) (f_i - f_c) (rolling without slip on the inner race)."""
    return {"shaft": f_i, "FTF": f_c, "BPFO": z * f_c, "BPFI": z * (f_i - f_c),
            "BSF": dm_over_d * (1 - ratio) * (f_i - f_c)}


def spectrum(x, rate, pad=1):
    """Single-sided amplitude spectrum of x (Hann window, amplitude-corrected), zero-padded `pad` times."""
    x = np.asarray(x, float) - np.mean(x)
    w = np.hanning(x.size)
    n = x.size * pad
    amp = np.abs(np.fft.rfft(x * w, n)) * 2.0 / np.sum(w)
    return np.fft.rfftfreq(n, 1.0 / rate), amp


def band_pass(x, rate, band):
    """x with its content outside band = (low, high) [Hz] removed (an FFT mask: zero phase)."""
    x = np.asarray(x, float)
    spec = np.fft.rfft(x - np.mean(x))
    freq = np.fft.rfftfreq(x.size, 1.0 / rate)
    spec[(freq < band[0]) | (freq > band[1])] = 0
    return np.fft.irfft(spec, x.size)


def envelope(x):
    """|analytic signal| of x (the Hilbert transform by the FFT)."""
    x = np.asarray(x, float)
    n = x.size
    spec = np.fft.fft(x)
    h = np.zeros(n)
    h[0] = 1
    if n % 2 == 0:
        h[n // 2] = 1
        h[1:n // 2] = 2
    else:
        h[1:(n + 1) // 2] = 2
    return np.abs(np.fft.ifft(spec * h))


def envelope_spectrum(x, rate, band, pad=1):
    """Spectrum of the envelope of x band-passed to `band` (the demodulated impacts)."""
    return spectrum(envelope(band_pass(x, rate, band)), rate, pad)


def resonance_band(out, half_width=0.5):
    """The band around the housing's natural frequency, (1 -+ half_width) f_n [Hz]."""
    f = out.file if hasattr(out, "file") else out
    fn = float(f["housing"].attrs["natural_frequency"])
    return ((1 - half_width) * fn, (1 + half_width) * fn)


def peak_near(freq, amp, f0, rel=0.02):
    """The largest peak within f0 (1 -+ rel): (frequency refined by a parabola through its bin and
    its neighbours, amplitude)."""
    sel = np.nonzero((freq >= f0 * (1 - rel)) & (freq <= f0 * (1 + rel)))[0]
    if sel.size == 0:
        return float("nan"), 0.0
    i = int(sel[np.argmax(amp[sel])])
    if 0 < i < amp.size - 1:
        a, b, c = amp[i - 1], amp[i], amp[i + 1]
        den = a - 2 * b + c
        shift = min(1.0, max(-1.0, 0.5 * (a - c) / den)) if den != 0 else 0.0
        return float(freq[i] + shift * (freq[1] - freq[0])), float(b)
    return float(freq[i]), float(amp[i])


def noise_floor(freq, amp, f0, rel=0.15):
    """The median amplitude within f0 (1 -+ rel): the floor a line at f0 stands on."""
    sel = (freq >= f0 * (1 - rel)) & (freq <= f0 * (1 + rel))
    return float(np.median(amp[sel])) if np.any(sel) else float("nan")


def statistics(x):
    """RMS, kurtosis (4th standardized moment: 3 for Gaussian noise) and crest factor of x."""
    x = np.asarray(x, float) - np.mean(x)
    rms = float(np.sqrt(np.mean(x * x)))
    kurtosis = float(np.mean(x ** 4) / rms ** 4) if rms > 0 else float("nan")
    crest = float(np.max(np.abs(x)) / rms) if rms > 0 else float("nan")
    return {"rms": rms, "kurtosis": kurtosis, "crest_factor": crest}


def energy_table(freq, amp, frequencies, harmonics=3, threshold=4.0):
    """Per characteristic frequency and harmonic: where its line stands, its amplitude, the floor
    around it and whether it carries energy (amplitude > threshold x floor)."""
    rows = []
    for name in ("FTF", "BSF", "BPFO", "BPFI", "shaft"):
        for k in range(1, harmonics + 1):
            f0 = k * frequencies[name]
            if not (0 < f0 < freq[-1]):
                continue
            at, a = peak_near(freq, amp, f0)
            floor = noise_floor(freq, amp, f0)
            rows.append({"name": name, "harmonic": k, "expected_hz": f0, "found_hz": at, "amplitude": a,
                         "floor": floor, "carries_energy": bool(a > threshold * floor)})
    return rows


def export_csv(out, path, start=0.0):
    """The sensor's samples as CSV (time s, displacement m, velocity m/s, acceleration m/s^2, x and
    y), the plain form diagnosis tools read."""
    s = sensor_signal(out, start)
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(["time_s", "displacement_x_m", "displacement_y_m", "velocity_x_m_s", "velocity_y_m_s",
                    "acceleration_x_m_s2", "acceleration_y_m_s2"])
        for i in range(s.time.size):
            w.writerow([repr(float(s.time[i]))] + [repr(float(v)) for v in
                       (*s.displacement[i], *s.velocity[i], *s.acceleration[i])])
    return s.time.size
