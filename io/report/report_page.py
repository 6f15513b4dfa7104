"""report.html of `raceway report`: one self-contained page (figures embedded as PNG data, the
numbers, the scene text and the build) to open in a browser or send to a colleague."""
import base64
import html
import math
import os

from report_life import life_rows
from report_power import power_rows, thermal_rows
from report_rollers import rows as roller_rows
from report_rollers_plots import CAPTIONS as ROLLER_CAPTIONS

CAPTIONS = {
    "cage_speed.png": "Cage speed about the bearing axis against the kinematic cage speed; the slip is over the shaded "
                      "window (time means).",
    "cage_centroid.png": "Cage centre orbit (the window in colour, earlier samples grey) and its distance from the "
                         "window's mean centre.",
    "pocket_force_time.png": "Pocket (bar) forces, every sample: the largest front and rear bar force over the pockets, "
                             "and the peak of every impact.",
    "pocket_force_azimuth.png": "Pocket forces against the pocket's azimuth over the window: time mean and peak per bin.",
    "contact_angle.png": "Load-weighted mean contact angle of the groove contacts; angles below the model's resolution "
                         "(the integrator's tolerance on the ball positions over (f - 1/2) D) are drawn as 0, and the "
                         "figure is left out when every angle is below it.",
    "contact_pressure.png": "Largest Hertz pressure of each contact kind.",
    "film_thickness.png": "Thinnest central film thickness of the loaded contacts of each kind.",
    "cage_land_force.png": "Normal force between the cage and its guiding land.",
    **ROLLER_CAPTIONS,
    "friction.png": "Friction torque on the driven ring (the contacts' moment against its rotation) and the power "
                    "loss of each contact kind.",
}


def _fmt(v, unit="", scale=1.0, digits=4):
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "-"
    return f"{scale * v:.{digits}g}{(' ' + unit) if unit else ''}"


def _speed_rows(summary):
    """The cage speed, its kinematic reference and the slip: one reference row for line contacts
    (planar: rolling at 0 deg, the nominal and the loaded angle are one) and for ball bearings whose
    loaded angle gives the nominal one's speed to the digits shown (a deep groove bearing under
    radial load), else two."""
    cs = summary["cage_speed"]
    out = [("cage speed (mean)", _fmt(cs["mean_rpm"], "rpm", digits=6))]
    if summary.get("model_kind") == "planar" or "rolling_rpm" not in cs:
        label = ("kinematic cage speed, rollers rolling without slip (mean)" if summary.get("model_kind") == "planar"
                 else "kinematic cage speed, nominal contact angle (mean)")
        return out + [(label, _fmt(cs["epicyclic_rpm"], "rpm", digits=6)), ("slip against it", _fmt(cs["slip"], "%", 100))]
    rolling, nominal = _fmt(cs["rolling_rpm"], "rpm", digits=6), _fmt(cs["epicyclic_rpm"], "rpm", digits=6)
    if rolling == nominal:
        return out + [("kinematic cage speed, loaded contact angle = nominal (mean)", rolling),
                      ("slip against it (the run's cage_slip)", _fmt(cs["slip"], "%", 100))]
    return out + [("kinematic cage speed, loaded contact angle (mean)", rolling),
                  ("slip against it (the run's cage_slip)", _fmt(cs["slip"], "%", 100)),
                  ("kinematic cage speed, nominal contact angle (mean; reference only)", nominal)]


def _angle_rows(summary):
    angles = summary.get("contact_angle", {})
    resolution = angles.get("resolution_deg")
    out = []
    for key, value in angles.items():
        if key.endswith("loaded_mean_deg"):
            text = _fmt(value, "deg")
            if resolution is not None and value == 0:
                text = f"0 (below the model's resolution, {_fmt(resolution, 'deg', digits=2)})"
            out.append((f"{key[:-len('_loaded_mean_deg')]} contact angle (load-weighted mean)", text))
    return out


def _whirl_rows(c):
    if c.get("whirl", "whirling") != "whirling":
        return [("cage whirl", c["whirl_note"]), ("cage centre from the bearing axis (mean)",
                                                  _fmt(c["axis_radius_mean_m"], "um", 1e6))]
    return [("cage vortex radius (mean)", _fmt(c["vortex_radius_mean_m"], "um", 1e6)),
            ("cage whirl / cage speed", _fmt(c["whirl_to_cage_speed_ratio"])), ("sigma_v", _fmt(c["sigma_v"]))]


def _pocket_rows(p):
    steps = p["statistics"]["events_peaks_impulses_contact_time"] == "steps"
    onsets = ("contacts start from zero force, at every integrator step" if steps
              else f"runs of samples above {_fmt(p['threshold_n'], 'N', digits=3)}")
    return [("pocket contacts in the window, front / rear bar (" + onsets + ")",
             f"{p['front']['events']} / {p['rear']['events']}"),
            (f"pocket impacts in the whole run (runs of output samples above {_fmt(p['threshold_n'], 'N', digits=3)} "
             "on one bar of one pocket, marked in the pocket force figure)", str(p["impacts"]["count"])),
            ("front / rear bar force (peak)", f"{_fmt(p['front']['peak_n'], 'N')} / {_fmt(p['rear']['peak_n'], 'N')}")]


def rows(summary, element):
    """(quantity, value) pairs of the main numbers; means are window means."""
    c = summary["cage_centroid"]
    out = [("window", f"{summary['window']['start_s']:.6g} .. {summary['window']['end_s']:.6g} s "
                      f"({summary['window']['samples']} samples)")]
    out += _speed_rows(summary) + _angle_rows(summary) + _whirl_rows(c)
    ld = summary[f"{element}_load"]
    out += [(f"largest {element} load (mean)", _fmt(ld["largest_mean_n"], "N")),
            (f"largest {element} load (peak)", _fmt(ld["max_n"], "N")),
            ("load zone", "loaded all round" if ld["loaded_all_round"] else
             f"{_fmt(ld['load_zone_width_deg'], 'deg', digits=3)} wide, centred at "
             f"{_fmt(ld['load_zone_centre_deg'], 'deg', digits=3)}")]
    if "pocket_forces" in summary:
        out += _pocket_rows(summary["pocket_forces"])
    for kind, e in summary.get("contact", {}).items():
        if "max_pressure_largest_mean_pa" in e:
            out.append((f"{kind} max pressure (mean / peak)", f"{_fmt(e['max_pressure_largest_mean_pa'], 'GPa', 1e-9)}"
                        f" / {_fmt(e['max_pressure_peak_pa'], 'GPa', 1e-9)}"))
        if "film_thickness_thinnest_mean_m" in e:
            out.append((f"{kind} thinnest film (mean / min)", f"{_fmt(e['film_thickness_thinnest_mean_m'], 'um', 1e6)}"
                        f" / {_fmt(e['film_thickness_min_m'], 'um', 1e6)}"))
    if "cage_land" in summary:
        out.append(("cage-land force (mean / peak)", f"{_fmt(summary['cage_land']['force_mean_n'], 'N')} / "
                                                     f"{_fmt(summary['cage_land']['force_peak_n'], 'N')}"))
    fr = summary.get("friction", {})
    if "friction_torque_mean_n_m" in fr:
        out.append(("friction torque (mean)", _fmt(fr["friction_torque_mean_n_m"], "mN m", 1e3)))
    if "power_loss_mean_w" in fr:
        out.append(("power loss (mean)", _fmt(fr["power_loss_mean_w"], "W")))
    return out


def write_page(run, summary, folder, pngs, name="report.html"):
    """Writes folder/name and returns its path."""
    esc = html.escape
    parts = ["<!DOCTYPE html><html><head><meta charset='utf-8'>",
             f"<title>raceway report: {esc(run.scene_name)}</title>",
             "<style>body{font-family:sans-serif;max-width:1640px;margin:auto;padding:1em}"
             "table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:3px 8px;text-align:left}"
             "img{width:100%;max-width:1600px}pre{background:#f5f5f5;padding:.5em;overflow-x:auto;font-size:85%}"
             "figcaption{color:#444;margin-bottom:1.5em}</style></head><body>",
             f"<h1>{esc(run.scene_name)}</h1>",
             f"<p>{esc(run.kind)} bearing, {run.elements} {esc(run.element)}s; file <code>{esc(run.path)}</code>. "
             "Values are means over the window unless marked peak. Time plots show the whole run with the "
             "window shaded; their vertical axes are scaled to the window.</p>",
             "<h2>Numbers</h2><table><tr><th>quantity</th><th>value</th></tr>"]
    parts += [f"<tr><td>{esc(k)}</td><td>{esc(v)}</td></tr>" for k, v in rows(summary, run.element)]
    if summary.get("rollers"):
        w = summary["rollers"]["window"]
        parts.append(f"</table><h2>Rollers: slices, ribs, tilt and skew</h2><p>Window {w['start_s']:.6g} .. "
                     f"{w['end_s']:.6g} s; slices numbered from the roller's -z end.</p>"
                     "<table><tr><th>quantity</th><th>value</th></tr>")
        parts += [f"<tr><td>{esc(k)}</td><td>{esc(v)}</td></tr>" for k, v in roller_rows(summary)]
    if summary.get("power_balance"):
        parts.append("</table><h2>Power balance</h2><p>Work over the window, integrated over the solver's steps "
                     "(docs/output_layout.md, \"Power balance\"); the residual is the integrator's own dissipation."
                     "</p><table><tr><th>quantity</th><th>value</th></tr>")
        parts += [f"<tr><td>{esc(k)}</td><td>{esc(v)}</td></tr>" for k, v in power_rows(summary["power_balance"])]
    if summary.get("thermal"):
        parts.append("</table><h2>Thermal network</h2><p>Temperatures at the window's ends, heat flows averaged "
                     "over it (docs/lubrication.md, \"Thermal network\").</p>"
                     "<table><tr><th>quantity</th><th>value</th></tr>")
        parts += [f"<tr><td>{esc(k)}</td><td>{esc(v)}</td></tr>" for k, v in thermal_rows(summary["thermal"])]
    parts.append("</table><h2>Rating life</h2><table><tr><th>quantity</th><th>value</th></tr>")
    parts += [f"<tr><td>{esc(k)}</td><td>{esc(v)}</td></tr>" for k, v in life_rows(summary.get("life", {}))]
    parts.append("</table><p>docs/life.md: the standards' formulas and what is estimated.</p>"
                 "<p>All metrics: <code>summary.json</code> beside this page.</p><h2>Figures</h2>")
    for png in pngs:
        with open(os.path.join(folder, png), "rb") as fh:
            data = base64.b64encode(fh.read()).decode("ascii")
        parts.append(f"<figure><img alt='{esc(png)}' src='data:image/png;base64,{data}'>"
                     f"<figcaption>{esc(CAPTIONS.get(png, png))}</figcaption></figure>")
    if summary.get("notes"):
        parts.append(f"<h2>Notes</h2><p>{esc(summary['notes'])}</p>")
    parts.append("<h2>Build</h2><table>")
    parts += [f"<tr><td>{esc(k)}</td><td>{esc(str(v))}</td></tr>" for k, v in run.build.items()]
    parts.append(f"</table><h2>Scene</h2><pre>{esc(run.scene_text)}</pre></body></html>\n")
    path = os.path.join(folder, name)
    with open(path, "w", encoding="utf-8") as fh:
        fh.write("\n".join(parts))
    return path
