"""The animation of `raceway report --animate`: the bearing seen along its axis.

Left: the outer and inner ring (their centres as computed), the rolling elements at their
positions, the cage (a ring at the pitch radius turning with the cage angle, a tick per pocket), and
pocket forces drawn as arrows on the elements as they happen (front bar blue, rear red; length
proportional to the force). The element size is schematic. Right: the cage centre's orbit,
magnified (its own axes in um), with the trace so far. Written as MP4 through ffmpeg when matplotlib
finds it, else as an animated GIF (pillow). Frames are evenly spaced samples over the whole run.
"""
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.animation as animation  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.patches import Circle  # noqa: E402


def writer(fps):
    """(writer, extension): ffmpeg's MP4 if available, else pillow's GIF."""
    if animation.writers.is_available("ffmpeg"):
        return animation.FFMpegWriter(fps=fps, bitrate=2400), ".mp4"
    return animation.PillowWriter(fps=fps), ".gif"


def animate(run, summary, folder, frames=240, fps=24, name="cage"):
    """Writes folder/name.mp4 (or .gif) and returns its path."""
    t = run.time
    idx = np.unique(np.linspace(0, len(t) - 1, max(2, min(frames, len(t)))).round().astype(int))
    pitch = run.geometry.get("pitch_radius") or float(np.mean(np.hypot(run.element_xy[0, :, 0], run.element_xy[0, :, 1])))
    n = run.elements
    r_el = 0.8 * pitch * math.sin(math.pi / n)  # schematic element size
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(12, 6), dpi=80, gridspec_kw={"width_ratios": [1.2, 1]})
    fig.suptitle(f"{run.scene_name}: the bearing along its axis", fontsize=12)
    s = 1e3  # mm
    lim = 1.45 * (pitch + r_el) * s
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    outer = Circle((0, 0), (pitch + 1.3 * r_el) * s, fill=False, lw=2, color="0.3")
    inner = Circle((0, 0), (pitch - 1.3 * r_el) * s, fill=False, lw=2, color="0.3")
    ax.add_patch(outer)
    ax.add_patch(inner)
    cage = Circle((0, 0), pitch * s, fill=False, lw=1.5, color="tab:green")
    ax.add_patch(cage)
    elements = [ax.add_patch(Circle((0, 0), r_el * s, color="tab:orange", alpha=0.8)) for _ in range(n)]
    pocket_ticks, = ax.plot([], [], color="tab:green", lw=2)
    peak = max(float(np.max(run.bar_front)) if run.bar_front is not None else 0.0,
               float(np.max(run.bar_rear)) if run.bar_rear is not None else 0.0, 1e-12)
    arrows = ax.quiver(np.zeros(2 * n), np.zeros(2 * n), np.zeros(2 * n), np.zeros(2 * n), angles="xy",
                       scale_units="xy", scale=1, color=["tab:blue"] * n + ["tab:red"] * n, width=0.006)
    label = ax.text(0.02, 0.97, "", transform=ax.transAxes, va="top", fontsize=10)
    um = 1e6 * run.cage_xy
    ax2.plot(um[:, 0], um[:, 1], color="0.85", lw=0.5)
    trace, = ax2.plot([], [], color="tab:green", lw=1)
    dot, = ax2.plot([], [], "o", color="tab:green")
    ax2.set_aspect("equal", adjustable="datalim")
    ax2.set_title("cage centre orbit (magnified)")
    ax2.set_xlabel("x [um]")
    ax2.set_ylabel("y [um]")
    ax2.ticklabel_format(useOffset=False, style="plain")
    arrow_len = 0.9 * r_el * s / peak

    def draw(frame):
        i = idx[frame]
        cx, cy = run.cage_xy[i] * s
        cage.center = (cx, cy)
        for ring, body in ((inner, "inner"), (outer, "outer")):
            ring.center = (0, 0)
        xy = run.element_xy[i] * s
        for k, e in enumerate(elements):
            e.center = tuple(xy[k])
        ang = run.cage_angle[i] + 2 * math.pi * (np.arange(n) + 0.5) / n
        px = np.column_stack([cx + 0.9 * pitch * s * np.cos(ang), cx + 1.1 * pitch * s * np.cos(ang),
                              np.full(n, np.nan)]).ravel()
        py = np.column_stack([cy + 0.9 * pitch * s * np.sin(ang), cy + 1.1 * pitch * s * np.sin(ang),
                              np.full(n, np.nan)]).ravel()
        pocket_ticks.set_data(px, py)
        if run.bar_front is not None:
            az = np.arctan2(xy[:, 1], xy[:, 0])
            tangent = np.column_stack([-np.sin(az), np.cos(az)]) * (1 if run.direction > 0 else -1)
            # The front bar pushes the element back, the rear bar forward.
            u = np.concatenate([-tangent * (run.bar_front[i][:, None] * arrow_len),
                                tangent * (run.bar_rear[i][:, None] * arrow_len)])
            arrows.set_offsets(np.concatenate([xy, xy]))
            arrows.set_UVC(u[:, 0], u[:, 1])
        trace.set_data(um[:i + 1, 0], um[:i + 1, 1])
        dot.set_data([um[i, 0]], [um[i, 1]])
        label.set_text(f"t = {t[i] * 1e3:.2f} ms   cage {run.cage_speed[i] * 60 / (2 * math.pi):.1f} rpm")
        return [cage, pocket_ticks, arrows, trace, dot, label, *elements]

    anim = animation.FuncAnimation(fig, draw, frames=len(idx), blit=False)
    w, ext = writer(fps)
    path = os.path.join(folder, name + ext)
    anim.save(path, writer=w)
    plt.close(fig)
    return path
