#!/usr/bin/env python3
"""The table and trend plots of a campaign folder (`raceway campaign FILE -o DIR`, docs/campaigns.md).

    /usr/bin/python3 io/report/campaign_table.py DIR        # what `raceway campaign report DIR` runs

Reads DIR/campaign.json (the scenes, their axis values and settling times, written by raceway) and
every DIR/<id>.h5, and writes DIR/campaign_table.csv and DIR/campaign_table.json (one row per scene:
the swept values as given and in SI, the metrics over the window after the settling time, the run's
steps and wall time, its status and diagnosis; the JSON also holds every column's unit) and
DIR/plots/<metric>_vs_<axis>.png.

The metrics are those of `raceway report` (report_summary.summarize over the same window, planar
and spatial alike: one definition of the cage slip, the vortex metrics of seed 001 eq. 9, the
pocket impacts and forces, the power loss), plus the cage's orbit about the outer ring's centre;
UNITS below lists every column. Exit codes: 0 done, 2 bad folder, 3 numpy/h5py/matplotlib missing.

The table records every scene, also failed and unfinished ones, and is written whole or not at all
(through a file of its own, renamed). SIGUSR1, a batch system's "time is nearly up" sent to every
process of a job, is ignored: the campaign has stopped its scenes already, the table is its last step.
"""
import signal

signal.signal(signal.SIGUSR1, signal.SIG_IGN)  # first, before the imports' seconds

import concurrent.futures
import csv
import functools
import glob
import json
import math
import multiprocessing
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

try:
    import numpy as np
    import report_metrics as rm
    from raceway import RacewayOutput
    from report_data import read_run
    from report_summary import summarize
except ImportError as e:  # pragma: no cover
    print(f"campaign_table: {e}", file=sys.stderr)
    sys.exit(3)

#: Every metric column (in the table's order), its unit and meaning; over t >= the settling time.
UNITS = {
    "cage_speed_rpm": ("rpm", "mean cage angular speed about the bearing axis"),
    "cage_slip": ("1", "1 - mean cage speed / mean kinematic cage speed at the loaded contact angle "
                       "(spatial: cage/rolling_speed; planar: epicyclic from the rings' speeds)"),
    "cage_whirl_radius_m": ("m", "mean distance of the cage centre from the outer ring's centre (the orbit)"),
    "cage_whirl_radius_std_m": ("m", "its standard deviation (the spread of the orbit)"),
    "vortex_radius_ratio": ("1", "(max - min) / mean distance of the cage centre from the vortex centre (seed 001 "
                                 "eq. 9), over the last vortex_turns whole whirl turns of the window: the vortex "
                                 "centre is their mean"),
    "sigma_v": ("1", "vortex velocity deviation ratio: std / mean of the cage centre's speed (seed 001 eq. 9), "
                     "over the same whole turns"),
    "vortex_turns": ("1", "whole whirl turns the vortex metrics are taken over (0: less than one turn in the "
                          "window, then over the whole window about its mean centre)"),
    "whirl_frequency_hz": ("Hz", "mean rate of the cage centre's angle about its mean centre"),
    "impacts_front_per_rev": ("1/rev", "pocket impacts on the front bars per revolution of the driven ring"),
    "impacts_rear_per_rev": ("1/rev", "pocket impacts on the rear bars per revolution of the driven ring"),
    "pocket_force_mean_n": ("N", "mean normal force of the pocket contacts (every pocket and sample)"),
    "pocket_force_peak_n": ("N", "the largest of them"),
    "pocket_force_rms_n": ("N", "RMS pocket force: spatial, net circumferential per pocket; planar, of the bars' "
                                "normal forces (front and rear)"),
    "pocket_force_front_peak_n": ("N", "largest front-bar force"),
    "pocket_force_rear_peak_n": ("N", "largest rear-bar force"),
    "max_element_load_mean_n": ("N", "mean over samples of the largest rolling element's inner-race load"),
    "element_load_min_n": ("N", "smallest inner-race load of any rolling element in the window"),
    "element_load_max_n": ("N", "largest inner-race load of any rolling element in the window"),
    "power_loss_w": ("W", "mean total power loss of the contacts (when the output has it)"),
    "life_l10_mrev": ("1e6 rev", "ISO 281 basic rating life L10 = (C / P)^p at the window's mean load (docs/life.md)"),
    "life_lnm_mrev": ("1e6 rev", "ISO 281 modified rating life a_1 a_ISO L10 (empty without a lubricant)"),
    "life_l10r_mrev": ("1e6 rev", "ISO/TS 16281 reference rating life L10r from the window's race contact loads"),
    "life_l10mr_mrev": ("1e6 rev", "ISO/TS 16281 modified reference rating life a_1 a_ISO L10r"),
    "life_equivalent_load_n": ("N", "ISO 281 dynamic equivalent load P"),
    "life_reference_load_n": ("N", "ISO/TS 16281 reference load P_ref = C / L10r^(1/p)"),
    "cage_motion": ("", "the cage's motion: stable, circling or unstable (io/report/cage_motion.py, docs/atlas.md)"),
    "cage_dynamics_indicator": ("1", "min(1, rms orbit radius / guiding clearance) x (1 - the orbit's spectral "
                                     "peak share): ~0 settled or regular whirl, towards 1 irregular (docs/atlas.md)"),
    "window_revolutions": ("rev", "revolutions of the driven ring relative to the other in the window"),
    "window_samples": ("1", "output samples in the window"),
    "steps": ("1", "integration steps of the whole run"),
    "wall_time_s": ("s", "wall time of the whole run (the last call, when resumed)"),
}
METRICS = [m for m in UNITS if m not in ("window_revolutions", "window_samples", "steps", "wall_time_s",
                                         "cage_motion", "cage_dynamics_indicator")]
#: The campaign file's metric names (campaign.metrics; solver/driver/campaign_file.cpp) and their columns.
COLUMNS_OF = {"cage_speed": ["cage_speed_rpm"], "cage_slip": ["cage_slip"],
              "cage_whirl_radius": ["cage_whirl_radius_m", "cage_whirl_radius_std_m"],
              "vortex": ["vortex_radius_ratio", "sigma_v", "vortex_turns", "whirl_frequency_hz"],
              "impacts": ["impacts_front_per_rev", "impacts_rear_per_rev"],
              "pocket_force": ["pocket_force_mean_n", "pocket_force_peak_n", "pocket_force_rms_n",
                               "pocket_force_front_peak_n", "pocket_force_rear_peak_n"],
              "max_element_load": ["max_element_load_mean_n"],
              "element_load_range": ["element_load_min_n", "element_load_max_n"],
              "power_loss": ["power_loss_w"],
              "life": ["life_l10_mrev", "life_lnm_mrev", "life_l10r_mrev", "life_l10mr_mrev", "life_equivalent_load_n",
                       "life_reference_load_n"],
              "steps": ["steps"], "wall_time": ["wall_time_s"]}


def _number(value):
    return float(value) if isinstance(value, (int, float)) and math.isfinite(value) else None


def _pocket_columns(summary, window_revolutions):
    """Impacts per revolution (the report's contact events: the onsets of the step-resolved pocket
    statistics where the file has them, else runs of samples above its threshold on one bar of one
    pocket, the runs its impact markers mark), RMS and peaks of the bar forces (peaks: the steps' too)."""
    p = summary.get("pocket_forces")
    if not p:
        return {}
    front, rear = p["front"], p["rear"]
    rms = p.get("rms_circumferential_force_n")
    if rms is None:
        rms = math.sqrt(0.5 * (front["rms_n"] ** 2 + rear["rms_n"] ** 2))
    per_rev = (lambda n: n / window_revolutions) if window_revolutions > 0 else (lambda n: None)
    return {"impacts_front_per_rev": per_rev(front["events"]), "impacts_rear_per_rev": per_rev(rear["events"]),
            "pocket_force_rms_n": rms, "pocket_force_front_peak_n": front["peak_n"],
            "pocket_force_rear_peak_n": rear["peak_n"]}


def _life_columns(life):
    """The rating lives of report_life.summarize_life (None where it has none)."""
    ref = life.get("reference", {})
    return {"life_l10_mrev": _number(life.get("l10_mrev")), "life_lnm_mrev": _number(life.get("lnm_mrev")),
            "life_l10r_mrev": _number(ref.get("l10r_mrev")), "life_l10mr_mrev": _number(ref.get("l10mr_mrev")),
            "life_equivalent_load_n": _number(life.get("equivalent_load_n")),
            "life_reference_load_n": _number(ref.get("reference_load_n"))}


def scene_metrics(path, settling_time):
    """The metrics of one output file over t >= settling_time (a dict), and its run summary."""
    run = read_run(path)
    report, _ = summarize(run, settling_time)
    w = rm.select_window(run.time, settling_time)
    with RacewayOutput(path, at_segment_rows=True) as out:  # the segment rows' samples
        summary = out.summary
        keep = np.zeros(len(run.time), dtype=bool)
        keep[w.slice] = True
        cage_xy = np.asarray(out["cage/position"], dtype=float)[keep][:, :2]
        ring_xy = np.asarray(out["outer_ring/position"], dtype=float)[keep][:, :2]
        relative = np.abs(np.asarray(out.component("inner_ring/angular_velocity", "about z"), dtype=float)
                          - np.asarray(out.component("outer_ring/angular_velocity", "about z"), dtype=float))
        pocket = [np.asarray(out[f"segments/{k}/normal_force"], dtype=float)[keep] for k in out.segment_kinds()
                  if "pocket" in k or "cage_bar" in k]
    radius = np.hypot(*(cage_xy - ring_xy).T)
    pocket = np.concatenate(pocket, axis=1) if pocket else np.zeros((int(keep.sum()), 0))
    revolutions = float(rm.time_mean(run.time, relative, w)) * w.length / (2 * math.pi)
    cs, centroid, loads = report["cage_speed"], report["cage_centroid"], run.element_load[w.slice]
    m = {
        "cage_speed_rpm": cs["mean_rpm"],
        "cage_slip": cs["slip"],
        "cage_whirl_radius_m": float(np.mean(radius)),
        "cage_whirl_radius_std_m": float(np.std(radius)),
        "vortex_radius_ratio": _number(centroid["vortex_radius_ratio"]),
        "sigma_v": _number(centroid["sigma_v"]),
        "vortex_turns": centroid["vortex_turns"],
        "whirl_frequency_hz": _number(centroid["whirl_frequency_hz"]),
        "cage_motion": report["cage_motion"]["motion_class"],
        "cage_dynamics_indicator": _number(report["cage_motion"]["cage_dynamics_indicator"]),
        "pocket_force_mean_n": float(np.mean(pocket)) if pocket.size else 0.0,
        "pocket_force_peak_n": float(np.max(pocket)) if pocket.size else 0.0,
        "max_element_load_mean_n": float(np.mean(np.max(loads, axis=1))) if loads.size else 0.0,
        "element_load_min_n": float(np.min(loads)) if loads.size else 0.0,
        "element_load_max_n": float(np.max(loads)) if loads.size else 0.0,
        "power_loss_w": _number(report.get("power_loss", {}).get("total_mean_w")),
        "window_revolutions": revolutions,
        "samples": w.samples,
    }
    m.update(_pocket_columns(report, revolutions))
    m.update(_life_columns(report.get("life", {})))
    return m, summary


def _statuses(folder):
    """The latest exit code and diagnosis of every scene from DIR/campaign_status_*.json: one file per
    call of a whole campaign (campaign_status_N.json) or of an array task (campaign_status_<id>_N.json),
    the later calls' last."""
    found = {}
    paths = glob.glob(os.path.join(folder, "campaign_status_*.json"))
    for path in sorted(paths, key=lambda p: (os.path.getmtime(p), int(p.rsplit("_", 1)[1].split(".")[0]))):
        with open(path, encoding="utf-8") as f:
            found.update(json.load(f).get("scenes_this_call", {}))
    return found


def build_table(folder):
    with open(os.path.join(folder, "campaign.json"), encoding="utf-8") as f:
        manifest = json.load(f)
    statuses = _statuses(folder)
    rows = []
    for sid, scene in manifest["scenes"].items():
        row = {"scene": sid}
        row.update(scene["axis_values"])
        path = os.path.join(folder, sid + ".h5")
        status = statuses.get(sid, {})
        readable = os.path.exists(path)
        if readable:
            try:
                metrics, summary = scene_metrics(path, scene["settling_time_s"])
            except Exception as e:  # a damaged file is a row that says so, not a missing table
                readable = False
                status = {"exit_code": 1, "attempts": status.get("attempts", 1),
                          "diagnosis": f"{sid}.h5 cannot be read: {type(e).__name__}: {e}"}
        if readable:
            params = summary.get("scene_parameters", {})
            for name, key in manifest["axes"].items():
                manifest.setdefault("axis_units", {})[name] = params.get(key, {}).get("unit", "")
                value = params.get(key, {}).get("value")
                row[f"{name}_si"] = value if isinstance(value, (int, float)) else None
            row.update({k: metrics.get(k) for k in METRICS + ["cage_motion", "cage_dynamics_indicator"]})
            row["window_revolutions"] = metrics["window_revolutions"]
            row["window_samples"] = metrics["samples"]
            row["steps"] = summary.get("steps")
            row["wall_time_s"] = summary.get("wall_time_s")
            row["status"] = "done"
        else:
            row["status"] = "failed" if status.get("exit_code", 0) not in (0, 4) else "not finished"
        row["attempts"] = status.get("attempts", 1 if os.path.exists(path) else 0)
        row["diagnosis"] = status.get("diagnosis", "")
        rows.append(row)
    return manifest, rows


def metric_columns(manifest):
    """The metric columns the campaign asked for, in the order of METRICS."""
    asked = [c for name in manifest.get("metrics", COLUMNS_OF) for c in COLUMNS_OF[name]]
    return [m for m in METRICS if m in asked], [c for c in ("steps", "wall_time_s") if c in asked]


def write_table(folder, manifest, rows):
    metrics, run = metric_columns(manifest)
    motion = ["cage_motion", "cage_dynamics_indicator"] if "vortex_radius_ratio" in metrics else []
    columns = ["scene"] + list(manifest["axes"]) + [f"{a}_si" for a in manifest["axes"]] + metrics + motion + \
        ["window_revolutions", "window_samples"] + run + ["status", "attempts", "diagnosis"]
    units = {c: UNITS[c][0] for c in columns if c in UNITS}
    units.update({f"{a}_si": manifest.get("axis_units", {}).get(a, "") for a in manifest["axes"]})
    def replace(name, write):  # whole or not at all: a kill mid-write leaves the previous table
        own = os.path.join(folder, f".{name}.{os.getpid()}")
        with open(own, "w", newline="", encoding="utf-8") as f:
            write(f)
        os.replace(own, os.path.join(folder, name))

    def write_csv(f):
        w = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: r.get(k, "") for k in columns})
    replace("campaign_table.csv", write_csv)
    replace("campaign_table.json", lambda f: json.dump(
        {"campaign": manifest["campaign"], "columns": columns, "units": units,
         "meaning": {c: UNITS[c][1] for c in columns if c in UNITS}, "rows": rows}, f, indent=1))


#: Trend plots: 1200 x 750 px, labels at a size that reads on a page.
PLOT_SIZE_IN, PLOT_DPI = (12.0, 7.5), 100
#: A metric's readable name on a plot: its column without the unit suffix, in words.
METRIC_LABELS = {"cage_slip": "cage slip (loaded contact angle)", "vortex_radius_ratio": "vortex radius ratio",
                 "sigma_v": "vortex velocity deviation sigma_v", "impacts_front_per_rev": "front-bar impacts per revolution",
                 "impacts_rear_per_rev": "rear-bar impacts per revolution",
                 "max_element_load_mean_n": "largest rolling-element load (mean)"}
UNIT_SUFFIXES = ("_rpm", "_m", "_n", "_hz", "_w", "_s", "_per_rev")


def metric_label(metric, unit=None):
    """ "cage_whirl_radius_std_m" -> "cage whirl radius std [m]" (`unit`: another unit than the column's)."""
    name = METRIC_LABELS.get(metric)
    if name is None:
        name = metric
        for suffix in UNIT_SUFFIXES:
            if name.endswith(suffix):
                name = name[:-len(suffix)]
                break
        name = name.replace("_", " ")
    unit = unit or UNITS[metric][0]
    return f"{name} [{unit}]" if unit not in ("1", "") else name


def axis_values(rows, axis):
    """The swept values in the sweep's own unit, as the campaign file gives them ("2400 rpm" -> 2400,
    "rpm") when every value is a number with one and the same unit; else the SI values and their unit
    (None: fall back)."""
    numbers, units = [], set()
    for r in rows:
        text = str(r.get(axis, "")).strip()
        head, _, unit = text.partition(" ")
        try:
            numbers.append(float(head))
        except ValueError:
            return None
        units.add(unit.strip())
    return (numbers, units.pop()) if len(units) == 1 else None


def _draw_trend(folder, manifest, done, axis, metric, plt):
    """One plot: `metric` against `axis` in the sweep's own units, one line per value of the other
    axis (if any)."""
    axes = list(manifest["axes"])
    others = [a for a in axes if a != axis]
    fig, ax = plt.subplots(figsize=PLOT_SIZE_IN)
    given = axis_values(done, axis)
    unit = given[1] if given else manifest.get("axis_units", {}).get(axis, "")
    x_of = {id(r): v for r, v in zip(done, given[0])} if given else {id(r): r[f"{axis}_si"] for r in done}
    # Lengths of micrometres in um, not as 1e-6 m.
    values = [abs(r[metric]) for r in done if isinstance(r.get(metric), (int, float)) and math.isfinite(r[metric])]
    scale, y_unit = (1e6, "um") if UNITS[metric][0] == "m" and values and max(values) < 1e-3 else (1.0, None)
    groups = {}
    for r in done:
        groups.setdefault(r[others[0]] if others else "", []).append(r)
    for label, group in groups.items():
        group = sorted(group, key=lambda r: x_of[id(r)] if x_of[id(r)] is not None else 0)
        x = [x_of[id(r)] for r in group]
        y = [scale * r[metric] if r.get(metric) is not None else np.nan for r in group]
        ax.plot(x, y, "o-", ms=7, lw=1.5, label=f"{others[0]} = {label}" if others else None)
    key = manifest["axes"][axis]
    ax.set_xlabel(f"{key.replace('_', ' ').replace('.', ' ')}{f' [{unit}]' if unit else ''}", fontsize=14)
    ax.set_ylabel(metric_label(metric, y_unit), fontsize=14)
    ax.set_title(f"{manifest['campaign']}: {metric_label(metric, y_unit)} against {axis}", fontsize=15)
    ax.tick_params(labelsize=12)
    if others:
        ax.legend(fontsize=12)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    path = os.path.join(folder, "plots", f"{metric}_vs_{axis}.png")
    fig.savefig(path, dpi=PLOT_DPI)
    plt.close(fig)
    return path


def _draw_share(folder, manifest, done, jobs):
    """The plots of `jobs` ((axis, metric) pairs), in a process of the pool."""
    import matplotlib.pyplot as plt
    return [_draw_trend(folder, manifest, done, axis, metric, plt) for axis, metric in jobs]


def plot_trends(folder, manifest, rows):
    """metric against each swept value (one line per value of a second axis, when there is one).

    The plots (tens of them, about 50 ms each) are drawn by a pool of processes, one per core this
    process may use: the campaign's last step, when its ranks are done. matplotlib is not thread-safe,
    so processes (forked after its import), not threads."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    done = [r for r in rows if r["status"] == "done"]
    os.makedirs(os.path.join(folder, "plots"), exist_ok=True)
    jobs = [(axis, metric) for axis in manifest["axes"] for metric in metric_columns(manifest)[0]]
    workers = min(len(jobs), len(os.sched_getaffinity(0)))
    if workers <= 1:
        return _draw_share(folder, manifest, done, jobs)
    shares = [jobs[k::workers] for k in range(workers)]  # round robin: the shares alike
    with concurrent.futures.ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("fork")) as pool:
        drawn = list(pool.map(functools.partial(_draw_share, folder, manifest, done), shares))
    by_job = {job: path for share, paths in zip(shares, drawn) for job, path in zip(share, paths)}
    return [by_job[job] for job in jobs]


def main(argv):
    if len(argv) != 2 or not os.path.isfile(os.path.join(argv[1], "campaign.json")):
        print("usage: campaign_table.py DIR (a campaign folder with campaign.json)", file=sys.stderr)
        return 2
    manifest, rows = build_table(argv[1])
    write_table(argv[1], manifest, rows)
    plots = plot_trends(argv[1], manifest, rows)
    done = sum(r["status"] == "done" for r in rows)
    print(f"[raceway] campaign table: {done} of {len(rows)} scenes in {argv[1]}/campaign_table.csv, "
          f"{len(plots)} plots in {argv[1]}/plots", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
