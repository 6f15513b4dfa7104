#!/usr/bin/env python3
"""The table and trend plots of a campaign folder (`raceway campaign FILE -o DIR`, docs/campaigns.md).

    /usr/bin/python3 io/report/campaign_table.py DIR        # what `raceway campaign report DIR` runs

Reads DIR/campaign.json (the scenes, their axis values and settling times, written by raceway) and
every DIR/<id>.h5, and writes DIR/campaign_table.csv and DIR/campaign_table.json (one row per scene:
the swept values as given and in SI, the metrics over the window after the settling time, the run's
steps and wall time, its status and diagnosis) and DIR/plots/<metric>_vs_<axis>.png.

Metrics, over the samples with t >= settling time:
  cage_speed_rpm            mean cage angular speed about the bearing axis
  cage_slip                 1 - mean cage speed / mean epicyclic (kinematic) cage speed
  cage_whirl_radius_m       mean distance of the cage centre from the outer ring's centre (orbit)
  cage_whirl_radius_std_m   its standard deviation (the spread of the orbit)
  pocket_force_mean_n       mean normal force of the pocket contacts (every pocket and sample)
  pocket_force_peak_n       the largest of them
  max_element_load_mean_n   mean over samples of the largest rolling element's inner-race load
Spatial scenes also get the cage-centroid metrics of `raceway report` (io/report/cage_metrics.cpp,
seed 001 eq. 9) over the same window, when RACEWAY_EXECUTABLE names the raceway executable (raceway
campaign sets it): vortex_radius_ratio, sigma_v, whirl_frequency_hz, pocket_force_rms_n (RMS net
circumferential pocket force) and power_loss_w (mean total).
Exit codes: 0 done, 2 bad folder, 3 numpy/h5py/matplotlib missing.
"""
import csv
import glob
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

try:
    import numpy as np
    from raceway_output import RacewayOutput
except ImportError as e:  # pragma: no cover
    print(f"campaign_table: {e}", file=sys.stderr)
    sys.exit(3)

METRICS = ["cage_speed_rpm", "cage_slip", "cage_whirl_radius_m", "cage_whirl_radius_std_m", "pocket_force_mean_n",
           "pocket_force_peak_n", "max_element_load_mean_n"]
RPM = 60.0 / (2.0 * np.pi)
#: The campaign file's metric names (campaign.metrics) and their columns.
COLUMNS_OF = {"cage_speed": ["cage_speed_rpm"], "cage_slip": ["cage_slip"],
              "cage_whirl_radius": ["cage_whirl_radius_m", "cage_whirl_radius_std_m"],
              "pocket_force": ["pocket_force_mean_n", "pocket_force_peak_n"],
              "max_element_load": ["max_element_load_mean_n"], "steps": ["steps"], "wall_time": ["wall_time_s"]}


def _axial(w):
    """The component about z of a [T] (planar) or [T x 3] (spatial) angular velocity."""
    w = np.asarray(w, dtype=float)
    return w if w.ndim == 1 else w[:, 2]


def _epicyclic(out, params):
    if "cage/epicyclic_speed" in out:
        return np.asarray(out["cage/epicyclic_speed"], dtype=float)
    ratio = params["bearing.roller_diameter"]["value"] / params["bearing.pitch_diameter"]["value"]
    wi, wo = _axial(out["inner_ring/angular_velocity"]), _axial(out["outer_ring/angular_velocity"])
    return 0.5 * (wi * (1 - ratio) + wo * (1 + ratio))


def _segment_kinds(out, word):
    return [k for k in out.segment_kinds() if word in k]


def _forces(out, kinds, keep):
    blocks = [np.asarray(out[f"segments/{k}/normal_force"], dtype=float)[keep] for k in kinds]
    return np.concatenate(blocks, axis=1) if blocks else np.zeros((int(keep.sum()), 0))


def _element_loads(out, keep):
    """[T x elements]: each rolling element's inner-race normal force (its segments summed)."""
    kinds = [k for k in out.segment_kinds() if "inner" in k and ("groove" in k or "race" in k)]
    if not kinds:
        return np.zeros((int(keep.sum()), 0))
    kind = kinds[0]
    force = np.asarray(out[f"segments/{kind}/normal_force"], dtype=float)[keep]
    if f"segments/{kind}/ball" in out:
        owner = np.asarray(out[f"segments/{kind}/ball"]).astype(int).ravel()
        loads = np.zeros((force.shape[0], owner.max() + 1))
        for j, b in enumerate(owner):
            loads[:, b] += force[:, j]
        return loads
    return force


def scene_metrics(path, settling_time):
    """The metrics of one output file over t >= settling_time (a dict), and its summary."""
    with RacewayOutput(path) as out:
        t = np.asarray(out["time"], dtype=float)
        keep = t >= settling_time - 1e-12 * max(1.0, abs(settling_time))
        summary = out.summary
        params = summary.get("scene_parameters", {})
        cage = _axial(out["cage/angular_velocity"])[keep]
        epi = _epicyclic(out, params)[keep]
        cage_xy = np.asarray(out["cage/position"], dtype=float)[keep][:, :2]
        ring_xy = np.asarray(out["outer_ring/position"], dtype=float)[keep][:, :2]
        radius = np.hypot(*(cage_xy - ring_xy).T)
        pocket = _forces(out, _segment_kinds(out, "pocket") + _segment_kinds(out, "cage_bar"), keep)
        loads = _element_loads(out, keep)
        m = {
            "cage_speed_rpm": float(np.mean(cage) * RPM),
            "cage_slip": float(1.0 - np.mean(cage) / np.mean(epi)) if np.mean(epi) != 0 else float("nan"),
            "cage_whirl_radius_m": float(np.mean(radius)),
            "cage_whirl_radius_std_m": float(np.std(radius)),
            "pocket_force_mean_n": float(np.mean(pocket)) if pocket.size else 0.0,
            "pocket_force_peak_n": float(np.max(pocket)) if pocket.size else 0.0,
            "max_element_load_mean_n": float(np.mean(np.max(loads, axis=1))) if loads.size else 0.0,
            "samples": int(keep.sum()),
        }
    return m, summary


SPATIAL_METRICS = ["vortex_radius_ratio", "sigma_v", "whirl_frequency_hz", "pocket_force_rms_n", "power_loss_w"]


def report_metrics(folder, sid, settling_time):
    """`raceway report --no-plots` of a spatial scene over t >= settling_time: its cage-centroid
    metrics, or {} without RACEWAY_EXECUTABLE (a failed report is an error)."""
    exe = os.environ.get("RACEWAY_EXECUTABLE")
    if not exe:
        return {}
    out = os.path.join(folder, "reports", sid)
    # Run from a rank of mpirun: the child must not take mpirun's environment for its own (its
    # MPI_Init would fail), so it starts as a singleton.
    env = {k: v for k, v in os.environ.items()
           if not k.startswith(("OMPI_", "PMIX_", "OPAL_", "ORTE_")) or k.startswith("OMPI_ALLOW_RUN_AS_ROOT")}
    subprocess.run([exe, "report", os.path.join(folder, sid + ".h5"), "-o", out, "--no-plots",
                    "--window-start", repr(settling_time)], check=True, capture_output=True, env=env)
    with open(os.path.join(out, "summary.json"), encoding="utf-8") as f:
        r = json.load(f)
    centroid = r["cage_centroid"]
    return {"vortex_radius_ratio": centroid["vortex_radius_ratio"], "sigma_v": centroid["sigma_v"],
            "whirl_frequency_hz": centroid["whirl_frequency_hz"],
            "pocket_force_rms_n": r.get("pocket_forces", {}).get("rms_circumferential_force_n"),
            "power_loss_w": r.get("power_loss", {}).get("total_mean_w")}


def _statuses(folder):
    """The latest exit code and diagnosis of every scene from DIR/campaign_status_*.json."""
    found = {}
    for path in sorted(glob.glob(os.path.join(folder, "campaign_status_*.json")),
                       key=lambda p: int(p.rsplit("_", 1)[1].split(".")[0])):
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
        if os.path.exists(path):
            metrics, summary = scene_metrics(path, scene["settling_time_s"])
            params = summary.get("scene_parameters", {})
            for name, key in manifest["axes"].items():
                manifest.setdefault("axis_units", {})[name] = params.get(key, {}).get("unit", "")
                value = params.get(key, {}).get("value")
                row[f"{name}_si"] = value if isinstance(value, (int, float)) else None
            row.update({k: metrics[k] for k in METRICS})
            if summary.get("model_kind") == "spatial":
                row.update(report_metrics(folder, sid, scene["settling_time_s"]))
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
    if any(k in r for r in rows for k in SPATIAL_METRICS):
        metrics = metrics + SPATIAL_METRICS
    columns = ["scene"] + list(manifest["axes"]) + [f"{a}_si" for a in manifest["axes"]] + metrics + \
        ["window_samples"] + run + ["status", "attempts", "diagnosis"]
    with open(os.path.join(folder, "campaign_table.csv"), "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: r.get(k, "") for k in columns})
    with open(os.path.join(folder, "campaign_table.json"), "w", encoding="utf-8") as f:
        json.dump({"campaign": manifest["campaign"], "columns": columns, "rows": rows}, f, indent=1)


def plot_trends(folder, manifest, rows):
    """metric against each swept value (one line per value of a second axis, when there is one)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    done = [r for r in rows if r["status"] == "done"]
    axes = list(manifest["axes"])
    os.makedirs(os.path.join(folder, "plots"), exist_ok=True)
    written = []
    for axis in axes:
        others = [a for a in axes if a != axis]
        spatial = [m for m in SPATIAL_METRICS if any(m in r for r in done)]
        for metric in metric_columns(manifest)[0] + spatial:
            fig, ax = plt.subplots(figsize=(6, 4))
            groups = {}
            for r in done:
                groups.setdefault(r[others[0]] if others else "", []).append(r)
            for label, group in groups.items():
                group = sorted(group, key=lambda r: r[f"{axis}_si"] if r[f"{axis}_si"] is not None else 0)
                x = [r[f"{axis}_si"] for r in group]
                ax.plot(x, [r[metric] for r in group], "o-", label=f"{others[0]} = {label}" if others else None)
            unit = manifest.get("axis_units", {}).get(axis, "")
            ax.set_xlabel(f"{axis} ({manifest['axes'][axis]}){f' [{unit}]' if unit else ''}")
            ax.set_ylabel(metric)
            ax.set_title(f"{manifest['campaign']}: {metric}")
            if others:
                ax.legend(fontsize="small")
            ax.grid(True, alpha=0.3)
            fig.tight_layout()
            path = os.path.join(folder, "plots", f"{metric}_vs_{axis}.png")
            fig.savefig(path, dpi=90)
            plt.close(fig)
            written.append(path)
    return written


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
