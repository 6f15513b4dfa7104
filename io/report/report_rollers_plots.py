"""The roller figures of `raceway report` for spatial roller runs (report_rollers.py computes them):
the slice-load heat maps, the rib forces and power, the rollers' tilt and skew."""
import numpy as np

import report_rollers
from report_plots import figure, save, scale_to_window, shade_window

CAPTIONS = {
    "slice_load_heatmap.png": "Slice loads along the roller (slice 0 at its -z end) against the roller's azimuth, "
                              "inner and outer race: the mean over the window's samples whose roller is in the "
                              "azimuth bin (blank: none). Misalignment shows as loads piled up at one end.",
    "rib_forces.png": "Rib (flange) contacts: the normal force and power loss of each rib, summed over the rollers.",
    "roller_tilt_skew.png": "Roller tilt (in the radial plane) and skew (about the radial direction), every roller, "
                            "at its azimuth.",
}


def slice_heatmap(run, s, folder):
    r = s["rollers"]
    races = list(r["slices"].items())
    fig, axes = figure(run, "slice load against azimuth and position along the roller (window)", ncols=len(races))
    axes = np.atleast_1d(axes)
    width = 360.0 / len(r["bin_centre_deg"])
    for ax, (race, e) in zip(axes, races):
        heat = np.asarray([[np.nan if v is None else v for v in row] for row in e["load_bin_mean_n"]], dtype=float)
        image = ax.imshow(np.ma.masked_invalid(heat), aspect="auto", origin="lower", cmap="viridis",
                          extent=(0.0, len(r["bin_centre_deg"]) * width, -0.5, e["slices"] - 0.5),
                          interpolation="nearest")
        fig.colorbar(image, ax=ax, label="slice load [N]")
        ax.set_xlim(0, 360)
        ax.set_xticks(range(0, 361, 45))
        ax.grid(False)
        ax.set_xlabel("roller azimuth [deg] (0 = +x, counter-clockwise)")
        ax.set_ylabel("slice (0: roller's -z end)")
        ax.set_title(f"{race} race: peak slice load {e['slice_load_peak_n']:.4g} N; load centre "
                     f"{e['load_centre_offset']:+.3g} (-1: -z end), -z half {100 * e['minus_z_half_share']:.3g} %",
                     fontsize=11)
    return save(fig, folder, "slice_load_heatmap.png")


def rib_forces(run, s, folder):
    ribs = report_rollers.series(run)["ribs"]
    means = s["rollers"]["ribs"]
    fig, (ax, ax2) = figure(run, "rib (flange) contacts, summed over the rollers", ncols=2)
    for rib, r in ribs.items():
        ax.plot(run.time, r["force"], lw=0.7, label=f"{rib} (mean {means[rib]['force_mean_n']:.4g} N)")
        if r["power"] is not None:
            ax2.plot(run.time, r["power"], lw=0.7, label=f"{rib} (mean {means[rib].get('power_loss_mean_w'):.4g} W)")
    for a, label in ((ax, "rib normal force [N]"), (ax2, "rib power loss [W]")):
        shade_window(a, s)
        a.set_xlabel("time [s]")
        a.set_ylabel(label)
        a.legend(loc="upper right", fontsize=9)
    scale_to_window(ax, run, s, *[r["force"] for r in ribs.values()])
    scale_to_window(ax2, run, s, *[r["power"] for r in ribs.values() if r["power"] is not None])
    return save(fig, folder, "rib_forces.png")


def tilt_skew(run, s, folder):
    data = report_rollers.series(run)
    fig, axes = figure(run, "roller tilt and skew (every roller)", ncols=2)
    for ax, what in zip(axes, ("tilt", "skew")):
        e = s["rollers"][what]
        values = data[what] * 1e3
        ax.plot(run.time, values, lw=0.5, alpha=0.6)
        ax.plot(run.time, np.mean(values, axis=1), lw=1.5, color="k",
                label=f"mean over rollers (window {e['mean_mrad']:.3g} mrad, rms {e['rms_mrad']:.3g}, "
                      f"max |.| {e['max_abs_mrad']:.3g})")
        shade_window(ax, s)
        scale_to_window(ax, run, s, values)
        ax.set_xlabel("time [s]")
        ax.set_ylabel(f"{what} [mrad]")
        ax.legend(loc="lower right", fontsize=9)
    return save(fig, folder, "roller_tilt_skew.png")


def plots(summary):
    """The roller figures this summary has data for."""
    r = summary.get("rollers")
    if not r:
        return []
    out = [slice_heatmap] if r["slices"] else []
    if r.get("ribs"):
        out.append(rib_forces)
    if "tilt" in r:
        out.append(tilt_skew)
    return out
