"""The rating lives of one run (docs/life.md), the `life` object of summary.json.

- ISO 281 basic rating life L10 = (C / P)^p and modified rating life L_nm = a_1 a_ISO L10: C computed
  from the geometry (and the published C beside it where the scene or the catalogue gives one: the
  lives then use the published one), P from the load the inner ring's race contacts carry over the
  window (its mean vector), a_ISO from the viscosity ratio kappa = nu / nu_1 and e_C C_u / P.
- ISO/TS 16281 reference rating life L10r from the race contacts' loads themselves: per raceway track
  (inner and outer ring; each gothic arc of a four-point ring), the power mean of the loads over the
  track's rolling elements and the window's samples (the azimuths they pass through): exponent 3
  (balls) or 4 (rollers) on the ring that rotates relative to the load, 10/3 or 9/2 on the other;
  L10mr = a_1 a_ISO L10r with a_ISO at the reference load P_ref = C / L10r^(1/p).

Lives in 10^6 revolutions of one ring relative to the other (`_mrev`) and in hours at the window's
mean relative speed (`_h`). The formulas and tables are in life_tables.py.
"""
import math

import numpy as np

import life_tables as lt

DEFAULT_RELIABILITY = 90.0        # percent: L10
DEFAULT_CONTAMINATION = 0.5       # e_C: ISO 281's "normal cleanliness"
DEFAULT_LUBRICANT_DENSITY = 870.0  # kg/m^3: a mineral oil
RACE_KINDS = {"inner": ("ball_inner_groove", "roller_inner_race", "roller_inner_slice"),
              "outer": ("ball_outer_groove", "roller_outer_race", "roller_outer_slice")}
SLICE_KINDS = ("roller_inner_slice", "roller_outer_slice")  # a spatial roller's slices: one lamina each


def read_life_input(out, n):
    """What the lives need from an output file: the run summary's resolved scene parameters, each
    ring's race contact loads split into tracks ([T x n] each: column j the rolling element j; the
    k-th segment of an element on a ring is its track k) with their contact angles, and the rings'
    speeds about the axis; n rolling elements."""
    summary = out.summary or {}
    found = {"parameters": summary.get("scene_parameters", {}), "overrides": summary.get("scene_overrides") or {},
             "tracks": {}, "speeds": {}}
    for ring, kinds in RACE_KINDS.items():
        for kind in kinds:
            if f"segments/{kind}/normal_force" not in out:
                continue
            q = np.asarray(out[f"segments/{kind}/normal_force"], dtype=float)
            a = np.asarray(out[f"segments/{kind}/contact_angle"], dtype=float) \
                if f"segments/{kind}/contact_angle" in out else np.zeros_like(q)
            named = [f"segments/{kind}/{name}" for name in ("element", "ball") if f"segments/{kind}/{name}" in out]
            element = np.asarray(out[named[0]], dtype=float).astype(int) if named else np.arange(q.shape[1])
            if element.shape != (q.shape[1],) or (element < 0).any() or (element >= n).any():
                continue  # no rolling element for each column: no life from this file
            tracks, seen = [], {}
            for col, j in enumerate(element):
                k = seen.get(int(j), 0)
                seen[int(j)] = k + 1
                while len(tracks) <= k:
                    tracks.append((np.zeros((q.shape[0], n)), np.zeros((q.shape[0], n))))
                tracks[k][0][:, j], tracks[k][1][:, j] = q[:, col], a[:, col]
            found["tracks"][ring] = tracks
            if kind in SLICE_KINDS:
                found.setdefault("laminae", {})[ring] = len(tracks)
    for ring in ("inner_ring", "outer_ring"):
        if f"{ring}/angular_velocity" in out:
            found["speeds"][ring] = np.asarray(out.component(f"{ring}/angular_velocity", "about z"), dtype=float)
    return found


def _value(p, key):
    v = p.get(key, {}).get("value")
    return float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) else None


def _word(p, key):
    v = p.get(key, {}).get("value")
    return v if isinstance(v, str) else ""


def bearing_geometry(p, nominal_contact_angle=0.0):
    """The geometry the standards take (mm, rad) from the resolved scene parameters."""
    kind = _word(p, "bearing.type")
    ball = kind not in ("cylindrical_roller", "tapered_roller")
    g = {"type": kind, "ball": ball, "z": int(_value(p, "bearing.rolling_elements") or 0),
         "dw": 1e3 * (_value(p, "bearing.ball_diameter" if ball else "bearing.roller_diameter") or math.nan),
         "dpw": 1e3 * (_value(p, "bearing.pitch_diameter") or math.nan), "lwe": None, "fi": None, "fe": None,
         "alpha": 0.0, "rows": 1}
    if ball:
        g["fi"], g["fe"] = _value(p, "bearing.inner_conformity"), _value(p, "bearing.outer_conformity")
        if kind == "angular_contact_ball":
            g["alpha"] = _value(p, "bearing.contact_angle") or nominal_contact_angle
        elif kind == "four_point_contact_ball":  # rated as a double-row angular contact bearing (i = 2)
            g["alpha"] = _value(p, "bearing.arc_contact_angle") or nominal_contact_angle
            g["rows"] = 2
    else:
        g["lwe"] = 1e3 * (_value(p, "bearing.roller_length") or math.nan)
        if kind == "tapered_roller":  # rated at the cup angle, the catalogues' contact angle
            g["alpha"] = _value(p, "bearing.cup_angle") or 0.0
    return g


def carried_load(tracks, element_xy):
    """Radial and axial load (N) the race contacts carry: the window's mean of sum Q cos(a) along
    each element's azimuth, and of sum Q sin(a) (each [T x n] with the elements' positions)."""
    psi = np.arctan2(element_xy[..., 1], element_xy[..., 0])
    fx = sum(np.sum(q * np.cos(a) * np.cos(psi), axis=1) for q, a in tracks)
    fy = sum(np.sum(q * np.cos(a) * np.sin(psi), axis=1) for q, a in tracks)
    fz = sum(np.sum(q * np.sin(a), axis=1) for q, a in tracks)
    return float(math.hypot(np.mean(fx), np.mean(fy))), float(abs(np.mean(fz)))


def _published(p, key, scene_text, overrides, designation):
    value = _value(p, f"life.{key}")
    if value is None:
        return None, None
    given = key in scene_text or f"life.{key}" in overrides
    return value, (f"published: given by the scene ([life] {key})" if given or not designation
                   else f"published: the catalogue's for the {designation} (docs/catalogue.md)")


def _hours(mrev, rpm):
    return mrev * 1e6 / (60.0 * rpm) if rpm > 0 and math.isfinite(mrev) else None


def window_operation(run, li, s, race="inner"):
    """The load a race's contacts carry over the window slice s (F_r, F_a, N), the rings' relative
    speed (r/min) and whether the inner ring is the one rotating relative to the load. A tapered
    bearing's load is the cup's (race "outer"): the cone shares its axial load with the back rib."""
    fr, fa = carried_load([(q[s], a[s]) for q, a in li["tracks"][race]], run.element_xy[s])
    speed = {ring: float(np.mean(li["speeds"][ring][s])) if ring in li["speeds"] else 0.0
             for ring in ("inner_ring", "outer_ring")}
    rpm = abs(speed["inner_ring"] - speed["outer_ring"]) * 60 / (2 * math.pi)
    return fr, fa, rpm, abs(speed["inner_ring"]) >= abs(speed["outer_ring"])


def load_ratings(run, li, g):
    """C, C_0, C_u: computed from the geometry, published where the scene or catalogue gives them."""
    p, ball = li["parameters"], g["ball"]
    c_iso, fc, bm, gamma = lt.dynamic_load_rating(ball, g["z"], g["dw"], g["dpw"], g["alpha"], g["lwe"], g["rows"])
    c0_iso, f0 = lt.static_load_rating(ball, g["z"], g["dw"], g["dpw"], g["alpha"], g["lwe"], g["rows"])
    designation = _word(p, "bearing.designation")
    published = {key: _published(p, key, run.scene_text, li["overrides"], designation)
                 for key in ("dynamic_load_rating", "static_load_rating", "fatigue_load_limit")}
    c_pub, c_src = published["dynamic_load_rating"]
    c0_pub, c0_src = published["static_load_rating"]
    cu_pub, cu_src = published["fatigue_load_limit"]
    c = c_pub if c_pub is not None else c_iso
    c0 = c0_pub if c0_pub is not None else c0_iso
    out = {"gamma": gamma, "dynamic_load_rating_n": c,
           "dynamic_load_rating_source": c_src or "ISO 281 from the geometry",
           "dynamic_load_rating_iso281_n": c_iso, "f_c": fc, "b_m": bm,
           "static_load_rating_n": c0, "static_load_rating_source": c0_src or "ISO 76 from the geometry",
           "static_load_rating_iso76_n": c0_iso, "f_0": f0}
    if c is None or c0 is None:
        return out
    out["fatigue_load_limit_n"] = cu_pub if cu_pub is not None else lt.fatigue_load_limit(ball, c0, g["dpw"])
    out["fatigue_load_limit_source"] = cu_src or ("estimated: C_0 / {} {} (ISO 281's estimate)".format(
        22 if ball else 8.2, "" if g["dpw"] <= 100 else f"(100 / D_pw)^{0.5 if ball else 0.3}").replace("  ", " "))
    return out


def modification(p, g, rpm):
    """a_1 and the lubrication of a_ISO: reliability, e_C, nu, nu_1, kappa (None where not known), notes."""
    reliability = _value(p, "life.reliability") or DEFAULT_RELIABILITY
    eta = _value(p, "lubricant.viscosity") or 0.0
    rho = _value(p, "life.lubricant_density") or DEFAULT_LUBRICANT_DENSITY
    nu = eta / rho * 1e6 if eta > 0 else None
    nu1 = lt.reference_viscosity(rpm, g["dpw"]) if rpm > 0 else None
    kappa = nu / nu1 if nu and nu1 else None
    notes = []
    if kappa is None:
        why = "the scene has no [lubricant]" if nu is None else "the rings do not turn"
        notes.append(f"no modified lives: {why}")
    elif kappa < 0.1:
        notes.append(f"no modified lives: kappa = {kappa:.3g} is below ISO 281's range (0.1 to 4)")
    return {"reliability_percent": reliability, "a1": lt.a1(reliability),
            "contamination_factor": _value(p, "life.contamination_factor") or DEFAULT_CONTAMINATION,
            "kinematic_viscosity_mm2_s": nu, "lubricant_density_kg_m3": rho, "rated_viscosity_mm2_s": nu1,
            "kappa": kappa}, notes


def summarize_life(run, w):
    """The `life` object of summary.json over the window w (report_metrics.select_window)."""
    li = run.life_input or {}
    p = li.get("parameters") or {}
    if not p or "inner" not in li.get("tracks", {}) or "outer" not in li["tracks"]:
        return {"note": "no life: the file has no run summary (an interrupted run) or no race contacts"}
    g = bearing_geometry(p, float(run.geometry.get("nominal_contact_angle", 0.0) or 0.0))
    ratings = load_ratings(run, li, g)
    if "fatigue_load_limit_n" not in ratings:
        return {"note": f"no life: D_w cos(alpha) / D_pw = {ratings['gamma']:.4f} is outside ISO 281's f_c table and "
                        "the scene gives no [life] dynamic_load_rating"}
    race = "outer" if g["type"] == "tapered_roller" else "inner"
    fr, fa, rpm, inner_rotating = window_operation(run, li, w.slice, race)
    c, cu = ratings["dynamic_load_rating_n"], ratings["fatigue_load_limit_n"]
    pe, x, y, e = lt.equivalent_load(g["type"], fr, fa, ratings["static_load_rating_n"], ratings["f_0"], g["alpha"])
    exponent = 3.0 if g["ball"] else 10 / 3
    l10 = (c / pe) ** exponent if pe > 0 else math.inf
    mod, notes = modification(p, g, rpm)
    kappa, e_c = mod["kappa"], mod["contamination_factor"]
    a_iso = lt.a_iso(g["ball"], kappa, e_c * cu / pe) if kappa and pe > 0 else None
    lnm = mod["a1"] * a_iso * l10 if a_iso is not None else None
    out = {"standards": "ISO 281:2007 (C, P, L10, a_1, a_ISO), ISO 76:2006 (C_0), ISO/TS 16281:2008 (L10r)",
           "bearing_type": g["type"], "rolling_elements": g["z"], "element_diameter_mm": g["dw"],
           "pitch_diameter_mm": g["dpw"], "contact_angle_deg": math.degrees(g["alpha"]), "rows": g["rows"]}
    out.update(ratings)
    out.update({"radial_load_n": fr, "axial_load_n": fa,
                "load_note": f"the window's mean load the {race} race contacts carry",
                "equivalent_load_n": pe, "x": x, "y": y, "e": e,
                "speed_rpm": rpm, "rotating_ring": "inner_ring" if inner_rotating else "outer_ring",
                "l10_mrev": l10, "l10_h": _hours(l10, rpm)})
    out.update(mod)
    out.update({"a_iso": a_iso, "lnm_mrev": lnm, "lnm_h": _hours(lnm, rpm) if lnm is not None else None})
    out["reference"] = reference_life(li, w.slice, g, c, ratings["gamma"], inner_rotating, exponent, rpm, mod["a1"],
                                      e_c, cu, kappa)
    if notes:
        out["notes"] = notes
    return out


def lamina_share(li, g):
    """A spatial roller's slice as a lamina: its width over L_we (the slices cut the roller's
    length with its corners, roller_length + 2 r_c, into equal parts); None for whole-length
    contacts (planar rollers, balls)."""
    counts = set(li.get("laminae", {}).values())
    if not counts:
        return None
    if len(counts) != 1:
        raise ValueError(f"the inner and outer race slices differ in number ({sorted(counts)})")
    corner = _value(li.get("parameters", {}), "bearing.corner_radius") or 0.0
    return (g["lwe"] + 2e3 * corner) / (counts.pop() * g["lwe"])


def reference_life(li, s, g, c, gamma, inner_rotating, exponent, rpm, a1, e_c, cu, kappa):
    """ISO/TS 16281 over the window: every track's rating and equivalent load, L10r, L10mr."""
    ball = g["ball"]
    qci, qce = lt.contact_ratings(ball, c, g["z"], gamma, g["alpha"], g["fi"], g["fe"], g["rows"])
    share = lamina_share(li, g)
    if share is not None:  # ISO/TS 16281's lamina rating q_c = Q_c (w / L_we)^(7/9)
        qci, qce = qci * share ** (7 / 9), qce * share ** (7 / 9)
    tracks, pairs = [], []
    for ring, qc, rotating in (("inner", qci, inner_rotating), ("outer", qce, not inner_rotating)):
        for k, (q, _) in enumerate(li["tracks"][ring]):
            qe = lt.equivalent_contact_load(q[s], ball, rotating)
            pairs.append((qc, qe))
            tracks.append({"ring": ring, "track": k, "rotating_relative_to_load": rotating, "rating_n": qc,
                           "equivalent_load_n": qe, "power_mean_exponent": (3 if rotating else 10 / 3) if ball
                           else (4 if rotating else 4.5)})
    l10r = lt.reference_life(ball, pairs)
    p_ref = c / l10r ** (1 / exponent) if math.isfinite(l10r) and l10r > 0 else 0.0
    a_iso = lt.a_iso(ball, kappa, e_c * cu / p_ref) if kappa and p_ref > 0 else None
    l10mr = a1 * a_iso * l10r if a_iso is not None else None
    return {"l10r_mrev": l10r, "l10r_h": _hours(l10r, rpm), "reference_load_n": p_ref, "a_iso": a_iso,
            "l10mr_mrev": l10mr, "l10mr_h": _hours(l10mr, rpm) if l10mr is not None else None,
            "tracks": tracks,
            "mean": "per track, the power mean of its contact loads over its rolling elements and the window's samples "
                    "(exponent 3 / 4 for balls / rollers on the ring rotating relative to the load, 10/3 / 9/2 on "
                    "the other); planar rollers: whole-length contacts, which a lamina calculation with equal "
                    "slices reproduces; spatial rollers: one track per slice (a lamina, numbered from the roller's -z "
                    "end), rated q_c = Q_c (w / L_we)^(7/9)"}


def life_rows(life):
    """(quantity, value) rows of the report page's life table."""
    if "l10_mrev" not in life:
        return [("life", life.get("note", "not computed"))]

    def number(value):
        return "-" if value is None else f"{value:.3g}"

    def lives(mrev, hours):
        if mrev is None:
            return "-"
        return f"{mrev:.4g} x 10^6 rev" + (f" ({hours:.4g} h)" if hours is not None else "")
    ref = life["reference"]
    c_line = f"{life['dynamic_load_rating_n'] / 1e3:.4g} kN ({life['dynamic_load_rating_source']})"
    if life["dynamic_load_rating_iso281_n"] is not None and "published" in life["dynamic_load_rating_source"]:
        c_line += f"; ISO 281 from the geometry: {life['dynamic_load_rating_iso281_n'] / 1e3:.4g} kN"
    return [
        ("basic dynamic load rating C", c_line),
        ("static load rating C_0, fatigue load limit C_u",
         f"{life['static_load_rating_n'] / 1e3:.4g} kN, {life['fatigue_load_limit_n'] / 1e3:.4g} kN "
         f"({life['fatigue_load_limit_source']})"),
        ("load F_r, F_a -> P", f"{life['radial_load_n']:.4g} N, {life['axial_load_n']:.4g} N -> "
                               f"{life['equivalent_load_n']:.4g} N at {life['speed_rpm']:.4g} r/min"),
        ("ISO 281 L10 (basic)", lives(life["l10_mrev"], life["l10_h"])),
        (f"ISO 281 L_nm (a_1 = {life['a1']:.3g}, a_ISO = {number(life['a_iso'])}, kappa = {number(life['kappa'])}, "
         f"e_C = {life['contamination_factor']:.3g})",
         lives(life["lnm_mrev"], life["lnm_h"])),
        ("ISO/TS 16281 L10r (from the contact loads)", lives(ref["l10r_mrev"], ref["l10r_h"])),
        (f"ISO/TS 16281 L10mr (P_ref = {ref['reference_load_n']:.4g} N)", lives(ref["l10mr_mrev"], ref["l10mr_h"])),
    ]
