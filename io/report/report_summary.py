"""The metrics of one run as the summary.json object of `raceway report` (report_metrics.py defines them).

Every number over time is a window value: a time (or sample) mean over the stated window, unless its
key says `peak`, `max` or `min`. The window is the second half of the run by default.
"""
import math

import numpy as np

import cage_motion
import report_metrics as rm
from report_bridges import summarize_bridges
from report_life import summarize_life
from report_power import summarize_power, summarize_thermal
from report_rollers import summarize_rollers

DEG = 180.0 / math.pi


def _mean(x):
    return float(np.mean(x)) if np.size(x) else math.nan


def cage_speed(run, w):
    s = rm.speed_stats(run.cage_speed, run.epicyclic_speed, w)
    out = {"mean_rad_s": s["mean_rad_s"], "mean_rpm": s["mean_rpm"], "min_rad_s": s["min_rad_s"],
           "max_rad_s": s["max_rad_s"], "epicyclic_rad_s": s["kinematic_rad_s"], "epicyclic_rpm": s["kinematic_rpm"],
           "slip": s["slip"], "slip_nominal": s["slip"], "direction": rm.cage_direction(s["mean_rad_s"])}
    # One slip: against the kinematic speed at the loaded contact angle (the run summary's cage_slip
    # and the campaign tables' too); the nominal angle's only as slip_nominal.
    if run.rolling_speed is not None:
        r = rm.speed_stats(run.cage_speed, run.rolling_speed, w)
        out.update({"rolling_rad_s": r["kinematic_rad_s"], "rolling_rpm": r["kinematic_rpm"], "slip": r["slip"]})
    if run.kind == "planar":
        out["reference"] = "epicyclic speed of line contacts at 0 deg from the rings' speeds (rolling = epicyclic)"
    elif run.rolling_speed is not None:
        out["reference"] = ("slip: 1 - cage / rolling, rolling the kinematic speed at the load-weighted mean contact "
                            "angle of the inner-groove contacts per sample, then the window mean; slip_nominal: "
                            "against the epicyclic speed at the nominal contact angle")
    else:
        out["reference"] = "epicyclic at the nominal contact angle (the file has no /cage/rolling_speed)"
    return out


def contact_angles(run, w):
    """Load-weighted mean contact angle of each groove kind over the window (time mean), in deg;
    an angle below the model's resolution (rm.contact_angle_resolution) is reported as 0."""
    out = {}
    resolution = rm.contact_angle_resolution(run.geometry)
    for kind in ("ball_inner_groove", "ball_outer_groove"):
        seg = run.contact.get(kind)
        if not seg or "contact_angle" not in seg:
            continue
        q = seg["normal_force"][w.slice]
        a = np.abs(seg["contact_angle"][w.slice])
        total = float(np.sum(q))
        mean = float(np.sum(q * a) / total) if total > 0 else math.nan
        loaded = q > 0
        peak = float(np.max(a[loaded])) if loaded.any() else math.nan
        out[f"{kind}_loaded_mean_deg"] = rm.above_resolution(mean, resolution) * DEG
        out[f"{kind}_max_deg"] = rm.above_resolution(peak, resolution) * DEG
    if out and math.isfinite(resolution):
        out["resolution_deg"] = resolution * DEG
        out["note"] = ("angles below the resolution are 0: the integrator's tolerance on the ball positions "
                       "(element_position_tolerance) over the distance from the ball centre to the nearer groove's "
                       "curvature centre ((f - 1/2) D)")
    return out


def contact_fields(run, w):
    """Per ball contact kind: the largest Hertz pressure over its segments and the thinnest film of
    its loaded contacts, each per sample, then the window mean (and the peak / minimum)."""
    out = {}
    for kind, seg in run.contact.items():
        q = seg["normal_force"]
        if not np.any(q[w.slice] > 0):
            continue
        entry = {}
        # A kind whose segments leave max_pressure at 0 (a spatial roller's slices: the report's
        # `rollers` section estimates theirs) has no pressure here.
        if "max_pressure" in seg and np.any(seg["max_pressure"][w.slice] > 0):
            largest = np.max(np.where(q > 0, seg["max_pressure"], 0.0), axis=1)
            entry["max_pressure_largest_mean_pa"] = float(rm.time_mean(run.time, largest, w))
            entry["max_pressure_peak_pa"] = float(np.max(largest[w.slice]))
        if "film_thickness" in seg and np.any(seg["film_thickness"][w.slice] > 0):
            with np.errstate(all="ignore"):
                thinnest = np.nanmin(np.where(q > 0, seg["film_thickness"], np.nan), axis=1)
            loaded = thinnest[w.slice]
            entry["film_thickness_thinnest_mean_m"] = float(np.nanmean(loaded))
            entry["film_thickness_min_m"] = float(np.nanmin(loaded))
        if entry:
            out[kind] = entry
    return out


def centroid(run, w, cage_mean):
    m = rm.centroid_metrics(run.time, run.cage_xy[:, 0], run.cage_xy[:, 1], run.cage_vxy[:, 0], run.cage_vxy[:, 1],
                            w, cage_mean)
    land = None if run.land_force is None else float(np.mean(run.land_force[w.slice] > 0))
    m.update(rm.whirl_state(m, land))
    for key in ("land_clearance", "pocket_clearance", "pitch_radius"):
        m[f"{key}_m"] = run.geometry.get(key, math.nan)
    return m


STEP_KEYS = ("peak_n", "impulse_n_s", "events", "contact_time_s", "mean_duration_s", "duty_cycle")


def _use_step_statistics(run, w, front, rear):
    """Replaces the sampled events, peaks, impulses and contact times of each pocket's bars by the
    step-resolved ones where the file has them (the RMS stays sampled); says which were used."""
    if run.pocket_steps is None:
        return {"events_peaks_impulses_contact_time": "samples", "rms": "samples",
                "note": "from the output samples, runs above the threshold (the file has no /cage/pocket_step_*)"}
    for bar, stats in (("front", front), ("rear", rear)):
        for k, s in enumerate(stats):
            steps = rm.step_contact_stats(run.pocket_steps[bar], k, w)
            s.update({key: steps[key] for key in STEP_KEYS})
    return {"events_peaks_impulses_contact_time": "steps", "rms": "samples",
            "note": "events, peaks, impulses and contact times from every integrator step (/cage/pocket_step_*: "
                    "events are onsets from zero force, no threshold, over the intervals in the window); the RMS, "
                    "the azimuth bins and the impacts from the output samples"}


def pocket_forces(run, w, direction, threshold):
    if run.bar_front is None:
        return None
    if threshold is None:
        threshold = rm.default_contact_threshold(run.bar_front, run.bar_rear, w)
    front = [rm.contact_stats(run.time, run.bar_front[:, k], w, threshold) for k in range(run.elements)]
    rear = [rm.contact_stats(run.time, run.bar_rear[:, k], w, threshold) for k in range(run.elements)]
    source = _use_step_statistics(run, w, front, rear)
    ft, rt = rm.total_stats(front, w), rm.total_stats(rear, w)
    p = {"threshold_n": threshold, "direction": direction, "statistics": source,
         "rear_impulse_fraction": rm.ratio_or_nan(rt["impulse_n_s"], ft["impulse_n_s"] + rt["impulse_n_s"])}
    if run.pocket_circumferential is not None:
        fc = run.pocket_circumferential
        wts = rm.trapezoid_weights(run.time, w)
        sq = float(np.sum(wts[:, None] * fc[w.slice] ** 2))
        p["rms_circumferential_force_n"] = math.sqrt(sq / (run.elements * w.length))
        p["mean_net_circumferential_force_n"] = float(np.sum(wts * np.sum(fc[w.slice], axis=1))) / w.length
    p["front"], p["rear"] = ft, rt
    per = lambda stats: {k: [s[k] for s in stats] for k in ("rms_n", "peak_n", "impulse_n_s", "events",
                                                             "mean_duration_s", "duty_cycle")}
    p["front_per_pocket"], p["rear_per_pocket"] = per(front), per(rear)
    p["impacts"] = rm.impacts(run.time, run.bar_front, run.bar_rear, threshold)
    p["impacts"]["note"] = "every impact of the whole run (not only the window): peak sample of each contact"
    return p


def element_load(run, w, bins):
    """Inner-race loads: peak, time mean of the largest, per-element time means and the load zone."""
    q = run.element_load[w.slice]
    largest = np.max(q, axis=1)
    i, k = np.unravel_index(int(np.argmax(q)), q.shape)
    az = rm.azimuth(run.element_xy[w.slice, :, 0], run.element_xy[w.slice, :, 1])
    b = rm.bin_by_azimuth(az, q, bins)
    peak_bin = float(np.nanmax(b["mean"])) if np.isfinite(b["mean"]).any() else 0.0
    threshold = max(0.01 * peak_bin, 1e-3)
    z = rm.load_zone(b, threshold)
    out = {"max_n": float(q[i, k]), "max_azimuth_deg": float(az[i, k]) * DEG, "max_time_s": float(run.time[w.begin + i]),
           "max_element": int(k), "largest_mean_n": float(np.mean(largest)),
           "mean_per_element_n": [float(v) for v in np.mean(q, axis=0)],
           "max_bin_mean_n": peak_bin, "load_zone_threshold_n": threshold,
           "load_zone_start_deg": z["start"] * DEG, "load_zone_end_deg": z["end"] * DEG,
           "load_zone_width_deg": z["width"] * DEG, "load_zone_centre_deg": z["centre"] * DEG,
           "loaded_all_round": bool(z["all_round"]),
           "note": "max_n is the peak sample; largest_mean_n the window mean of the largest element load"}
    return out, b


def friction(run, w):
    out = {}
    if run.driven_moment is not None:
        m = float(np.mean(run.driven_moment[w.slice]))
        sign = 1.0 if np.mean(run.driven_speed[w.slice]) >= 0 else -1.0
        # The contacts' moment on the driven ring opposes its rotation; the drive supplies the negative.
        out["driven_ring"] = run.geometry.get("driven_ring", "")
        out["friction_torque_mean_n_m"] = -sign * m
        out["drive_power_mean_w"] = -float(np.mean(run.driven_moment[w.slice] * run.driven_speed[w.slice]))
    if run.power_loss:
        total = 0.0
        for kind, p in run.power_loss.items():
            v = float(rm.time_mean(run.time, p, w))
            out[f"{kind}_power_loss_mean_w"] = v
            total += v
        out["power_loss_mean_w"] = total
    return out


def summarize(run, window_start=None, bin_width_deg=5.0, contact_threshold=None):
    """The summary.json object and a few headline lines for the log."""
    if not (bin_width_deg > 0 and bin_width_deg <= 360):
        raise ValueError(f"--bin-width {bin_width_deg} deg is not in (0, 360]")
    w = rm.select_window(run.time, window_start)
    bins = bin_width_deg / DEG
    s = {"report_format": 2, "input": run.path, "scene_name": run.scene_name, "model_kind": run.kind,
         "rolling_element": run.element, f"{run.element}_count": run.elements,
         "window": {"start_s": w.t_begin, "end_s": w.t_end, "samples": w.samples,
                    "default_second_half": w.default_second_half,
                    "note": "means are over this window unless a key says peak, max or min"}}
    cs = cage_speed(run, w)
    s["cage_speed"] = cs
    angles = contact_angles(run, w)
    if angles:
        s["contact_angle"] = angles
    s["cage_centroid"] = centroid(run, w, cs["mean_rad_s"])
    s["cage_motion"] = cage_motion.motion_summary(run, w)  # stable / circling / unstable (docs/atlas.md)
    az = {"bin_width_deg": bin_width_deg}
    pf = pocket_forces(run, w, cs["direction"], contact_threshold)
    if pf:
        s["pocket_forces"] = pf
        pa = rm.azimuth(run.element_xy[w.slice, :, 0], run.element_xy[w.slice, :, 1])
        for bar, f in (("front", run.bar_front), ("rear", run.bar_rear)):
            b = rm.bin_by_azimuth(pa, f[w.slice], bins)
            az["bin_centre_deg"] = list(b["centre"] * DEG)
            az[f"{bar}_force_mean_n"], az[f"{bar}_force_max_n"] = list(b["mean"]), list(b["max"])
    load, b = element_load(run, w, bins)
    s[f"{run.element}_load"] = load
    az["bin_centre_deg"] = list(b["centre"] * DEG)
    for key in ("mean", "min", "max"):
        az[f"{run.element}_load_{key}_n"] = list(b[key])
    s["azimuth"] = az
    bridges = summarize_bridges(run, w, bins)
    if bridges:
        s["cage_bridges"] = bridges
    fields = contact_fields(run, w)
    if fields:
        s["contact"] = fields
    if run.land_force is not None:
        lf = run.land_force
        s["cage_land"] = {"force_mean_n": float(rm.time_mean(run.time, lf, w)), "force_peak_n": float(np.max(lf[w.slice])),
                          "contact_fraction": float(np.mean(lf[w.slice] > 0))}
    fr = friction(run, w)
    if fr:
        s["friction"] = fr
        if "power_loss_mean_w" in fr:
            s["power_loss"] = {"total_mean_w": fr["power_loss_mean_w"]}
    balance = summarize_power(run.power_balance, w)
    if balance:
        s["power_balance"] = balance
    thermal = summarize_thermal(run.thermal, w)
    if thermal:
        s["thermal"] = thermal
    rollers = summarize_rollers(run, w, bins)
    if rollers:
        s["rollers"] = rollers
    s["life"] = summarize_life(run, w)
    if run.notes:
        s["notes"] = "; ".join(run.notes)
    return s, headlines(s, run)


def headlines(s, run):
    w, cs = s["window"], s["cage_speed"]
    reference = (f"kinematic at the loaded contact angle {cs['rolling_rpm']:.2f} rpm" if "rolling_rpm" in cs
                 and run.kind == "spatial" else f"epicyclic {cs['epicyclic_rpm']:.2f} rpm")
    lines = [f"window {w['start_s']:.6g} .. {w['end_s']:.6g} s ({w['samples']} samples): cage {cs['mean_rpm']:.2f} rpm "
             f"(mean), {reference}, slip {100 * cs['slip']:.3f} %"]
    c = s["cage_centroid"]
    if c["whirl"] == "whirling":
        lines.append(f"cage centroid: vortex radius {1e6 * c['vortex_radius_mean_m']:.3g} um (ratio "
                     f"{c['vortex_radius_ratio']:.3f}), sigma_v {c['sigma_v']:.3f} over the last {c['vortex_turns']} "
                     f"whole whirl turns ({c['vortex_window_s']:.4g} s), whirl {c['whirl_frequency_rad_s']:.3g} "
                     f"rad/s = {c['whirl_to_cage_speed_ratio']:.3f} x cage speed")
    else:
        lines.append(f"cage centroid: {c['whirl_note']}; centre {1e6 * c['axis_radius_mean_m']:.3g} um from the "
                     "bearing axis (mean)")
    if "pocket_forces" in s:
        p = s["pocket_forces"]
        source = ("at every step" if p["statistics"]["events_peaks_impulses_contact_time"] == "steps"
                  else f"in the samples, threshold {p['threshold_n']:.3g} N")
        lines.append(f"pocket forces ({source}): front {p['front']['events']} contacts, peak "
                     f"{p['front']['peak_n']:.3g} N; rear {p['rear']['events']} contacts, peak {p['rear']['peak_n']:.3g} "
                     f"N; {p['impacts']['count']} impacts in the whole run's samples")
    ld = s[f"{run.element}_load"]
    zone = ("loaded all round" if ld["loaded_all_round"] else
            f"load zone {ld['load_zone_width_deg']:.0f} deg wide centred at {ld['load_zone_centre_deg']:.0f} deg")
    lines.append(f"inner-race {run.element} load: largest {ld['largest_mean_n']:.4g} N (mean), peak {ld['max_n']:.4g} N; "
                 f"{zone}")
    if "friction" in s and "friction_torque_mean_n_m" in s["friction"]:
        fr = s["friction"]
        lines.append(f"friction torque {fr['friction_torque_mean_n_m']:.4g} N m (mean), power loss "
                     f"{fr.get('power_loss_mean_w', math.nan):.4g} W (mean)")
    life = s.get("life", {})
    if "l10_mrev" in life:
        lnm = life["lnm_mrev"]
        lines.append(f"rating life (10^6 rev): ISO 281 L10 {life['l10_mrev']:.4g} at P {life['equivalent_load_n']:.4g} N"
                     + (f", L_nm {lnm:.4g}" if lnm is not None else "")
                     + f"; ISO/TS 16281 L10r {life['reference']['l10r_mrev']:.4g} from the contact loads (docs/life.md)")
    return lines
