"""The report's vibration part (docs/vibration.md): for a run with a housing (/housing), the sensor's
statistics, the characteristic frequencies after the run's slip, the spectrum and the envelope
spectrum with those frequencies marked, the table of which of them carry energy, and the sensor's
signal as CSV. Nothing for a run without a housing."""
import os

import numpy as np

import raceway.vibration as vib


def analyse(path, start):
    """The vibration summary of the run at `path` from `start` [s] on, or None without a housing."""
    import h5py
    with h5py.File(path, "r") as f:
        if "housing" not in f:
            return None
        s = vib.sensor_signal(f, start)
        if s.time.size < 16:
            return None
        freqs = vib.characteristic_frequencies(f)
        band = vib.resonance_band(f)
    x = s.acceleration[:, 1]  # vertical (y): the load's direction in the shipped scenes
    freq, amp = vib.spectrum(x, s.rate)
    env_freq, env_amp = vib.envelope_spectrum(x, s.rate, band, pad=4)
    table = vib.energy_table(env_freq, env_amp, freqs)
    return {"signal": s, "frequencies": freqs, "band_hz": band, "statistics": vib.statistics(x),
            "spectrum": (freq, amp), "envelope_spectrum": (env_freq, env_amp), "table": table}


def summary_of(result):
    """What summary.json keeps: numbers only."""
    f = result["frequencies"]
    return {"sensor_rate_hz": result["signal"].rate, "axis": "y", "band_hz": list(result["band_hz"]),
            "statistics": result["statistics"], "slip": f["slip"],
            "frequencies_hz": {k: f[k] for k in ("shaft", "FTF", "BSF", "BPFO", "BPFI")},
            "kinematic_frequencies_hz": {k: f["kinematic"][k] for k in ("shaft", "FTF", "BSF", "BPFO", "BPFI")},
            "lines": result["table"]}


def export(path, folder, start):
    """The sensor's CSV in the report folder; returns its path or None."""
    import h5py
    with h5py.File(path, "r") as f:
        if "housing" not in f:
            return None
        out = os.path.join(folder, "sensor.csv")
        vib.export_csv(f, out, start)
    return out


def plot(result, folder):
    """vibration.png: the spectrum and the envelope spectrum, characteristic frequencies marked."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 1, figsize=(9, 6.5))
    f = result["frequencies"]
    colours = {"FTF": "tab:gray", "BSF": "tab:green", "BPFO": "tab:red", "BPFI": "tab:blue", "shaft": "tab:orange"}
    for ax, (freq, amp), title, top in (
            (axes[0], result["spectrum"], "acceleration spectrum (y)", min(result["signal"].rate / 2,
                                                                             2 * result["band_hz"][1])),
            (axes[1], result["envelope_spectrum"],
             "envelope spectrum, band {:.0f}-{:.0f} Hz".format(*result["band_hz"]), 5 * max(f["BPFI"], f["BPFO"]))):
        sel = freq <= top
        ax.plot(freq[sel], amp[sel], lw=0.7, color="k")
        for name, colour in colours.items():
            for k in range(1, 4):
                if k * f[name] < top:
                    ax.axvline(k * f[name], color=colour, lw=0.8, ls="--" if k > 1 else "-",
                               label=name if k == 1 else None)
        ax.set_title(title)
        ax.set_xlabel("frequency [Hz]")
        ax.set_ylabel("amplitude [m/s^2]")
    axes[1].legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    name = "vibration.png"
    fig.savefig(os.path.join(folder, name), dpi=110)
    plt.close(fig)
    return name
