"""The critical cage (pocket) friction coefficient of a ball-driven cage (docs/atlas.md, "The critical
cage friction"): raceway's own linear model, after the idea of Nogi, Maniwa and Matsuoka (2018,
docs/references.md), whose formula is not used here.

The model (SI; per ball unless said): the cage centre z = x + i y (mass m_c, planar); Z balls at
angles phi_j turning at the cage speed w; each pocket in contact, its load varying by
k d_j + c_p d_j' about the mean, d_j = w_j - u.e_t,j the pocket's compression (w_j the ball's
circumferential displacement from its rolling position, u the cage's displacement, e_t,j the
circumferential direction at the ball); the pocket's friction mu times that load, along the ball's
sliding on the pocket, which is radial (the ball spins about the bearing's axis relative to the
cage) and points the same way round for a ball pushing its front bar and one pushed by its rear bar;
a spherical pocket's radial guidance k_g = 2 Q_0 / c (its normal turning); the ball held
circumferentially by its mass m_b and the slope c_t of its race contacts' traction against sliding
(inner + outer). The first circumferential harmonic of the balls, v, and the cage obey
(s = lambda - i w, lambda the cage's exponent in the bearing's frame, m~ = 2 m_c / Z):

    (m~ lambda^2 + k_g) z + (1 - i mu) p(s) (z - v) = 0,   b(s) v = p(s) (z - v),
    p(s) = k + c_p s,   b(s) = m_b s^2 + c_t s.

The friction's (1 - i mu) makes the pockets' stiffness circulatory (a force of mu Z k / 2 at right
angles to the displacement, pushing a forward whirl), the balls' traction is a damping fixed in the
cage's rotating frame (s, not lambda). With m_b = c_p = 0 a root crosses lambda = i Omega either at
Omega = w with k_g = m~ w^2 (the drift: cage and balls off-centre together, no friction in it) or at
Omega = w_n = sqrt(Z (k + k_g) / (2 m_c)), the friction's whirl, with the closed form

    mu_c = k / (c_t (w_n - |w|))   for w_n > |w|;   0 (the whirl grows without friction) otherwise.

critical_friction finds mu_c of the whole model (ball mass, pocket damping) by bisection on the
largest real part of the whirl's roots (the drift's left out: the pockets' clearance bounds it);
full_model_eigenvalues is the same physics with every ball its own coordinate (real, in the cage's
frame), the tests' independent check of the reduction. run_inputs and atlas_evidence take the
inputs from a run's output for the atlas.
"""
import math
import re
from dataclasses import dataclass

import numpy as np

# A pocket counts as loaded where its normal force exceeds this [N] (report_data's contact threshold).
CONTACT_FORCE = 1e-3
# The criterion applies where the pockets are in contact at least this share of the window's samples.
PRELOADED_SHARE = 0.5
MU_MAX = 100.0  # the search for mu_c ends here: above it, "no critical friction" (inf)


@dataclass
class CageBallModel:
    """The linear model's inputs (SI): cage mass, ball count, pocket stiffness and damping per pocket,
    race traction slope per ball (inner + outer), cage speed (either sign), ball mass."""
    cage_mass: float
    balls: int
    pocket_stiffness: float
    traction_damping: float
    cage_speed: float
    ball_mass: float = 0.0
    pocket_damping: float = 0.0
    guide_stiffness: float = 0.0

    @property
    def natural_frequency(self):
        """w_n = sqrt(Z (k + k_g) / (2 m_c)) [rad/s]: the cage on its pockets with the balls held."""
        return math.sqrt(self.balls * (self.pocket_stiffness + self.guide_stiffness) / (2.0 * self.cage_mass))

    @property
    def centred(self):
        """Whether the pockets' radial guidance holds the cage against its own centrifugal force
        (k_g >= 2 m_c w^2 / Z); if not, cage and balls drift off together whatever the friction."""
        return self.guide_stiffness >= 2.0 * self.cage_mass * self.cage_speed ** 2 / self.balls


def closed_form(model):
    """mu_c of massless balls without pocket damping: k / (c_t (w_n - |w|)); 0 where w_n <= |w| (the
    whirl grows without friction), inf without traction (the balls then follow the cage and nothing
    pumps). The drift (CageBallModel.centred) is a condition of its own."""
    gap = model.natural_frequency - abs(model.cage_speed)
    if gap <= 0:
        return 0.0
    if not model.traction_damping > 0:
        return math.inf
    return model.pocket_stiffness / (model.traction_damping * gap)


def characteristic_polynomial(model, mu):
    """Coefficients (highest power first) of m~ lambda^2 (b + p) + (1 - i mu) p b in lambda."""
    s = np.array([1.0, -1j * abs(model.cage_speed)])  # s = lambda - i w
    p = np.polyadd(model.pocket_damping * s, [model.pocket_stiffness])
    b = np.polyadd(model.ball_mass * np.polymul(s, s), model.traction_damping * s)
    m = 2.0 * model.cage_mass / model.balls
    cage = [m, 0.0, model.guide_stiffness]  # m~ lambda^2 + k_g
    poly = np.polyadd(np.polymul(cage, np.polyadd(b, p)), (1.0 - 1j * mu) * np.polymul(p, b))
    nonzero = np.nonzero(np.abs(poly) > 0)[0]
    return poly[nonzero[0]:] if nonzero.size else poly


def reduced_eigenvalues(model, mu):
    """The exponents lambda [1/s] of the reduced model (cage and the balls' first harmonic)."""
    return np.roots(characteristic_polynomial(model, mu))


def whirl_roots(model, mu, eigenvalues):
    """The exponents less the drift's (cage and balls off-centre together, at rest in the cage's frame:
    the reduced model's root nearest lambda = i |w|, the ball-by-ball model's two nearest 0), whose
    growth the pockets' clearance bounds in the bearing; what is left is the friction's whirl."""
    roots = np.asarray(eigenvalues(model, mu))
    frame, drift = (1j * abs(model.cage_speed), 1) if eigenvalues is reduced_eigenvalues else (0.0, 2)
    return roots[np.argsort(np.abs(roots - frame))[drift:]]


def growth_rate(model, mu, eigenvalues=reduced_eigenvalues, whirl_only=False):
    """The largest real part of the exponents [1/s] (the drift's left out with whirl_only)."""
    roots = whirl_roots(model, mu, eigenvalues) if whirl_only else eigenvalues(model, mu)
    return float(np.max(np.real(roots)))


def critical_friction(model, eigenvalues=reduced_eigenvalues, mu_max=MU_MAX):
    """The smallest mu >= 0 at which the largest real part of the whirl's roots (whirl_roots) crosses
    0 (bisection after a scan); 0 when the whirl grows without friction, inf when stable up to mu_max.
    Real parts within 1e-9 w_n of 0 count as stable (a neutral root)."""
    tol = 1e-9 * model.natural_frequency

    def unstable(mu):
        return growth_rate(model, mu, eigenvalues, whirl_only=True) > tol

    if unstable(0.0):
        return 0.0
    grid = np.concatenate([np.linspace(0.0, 1.0, 41)[1:], np.geomspace(1.0, mu_max, 41)[1:]])
    low = 0.0
    for high in grid:
        if unstable(high):
            for _ in range(60):
                mid = 0.5 * (low + high)
                low, high = (low, mid) if unstable(mid) else (mid, high)
            return 0.5 * (low + high)
        low = high
    return math.inf


def full_model_matrices(model, mu):
    """Stiffness and damping matrices of the model ball by ball in the cage's rotating frame (real
    coordinates: the cage's a, b along the frame's axes, then each ball's w_j; pockets at 2 pi j / Z),
    and the pockets' circumferential directions e_t (Z x 2). The pocket compressions are
    d = w - e_t u; the cage's equation is m_c (u'' + 2 w J u' - w^2 u) = sum of the pocket loads."""
    z, w = model.balls, abs(model.cage_speed)
    phi = 2.0 * math.pi * np.arange(z) / z
    e_t = np.column_stack([-np.sin(phi), np.cos(phi)])
    e_r = np.column_stack([np.cos(phi), np.sin(phi)])
    push = e_t + mu * e_r  # the pocket load's direction on the cage, friction included
    k, cp, mc = model.pocket_stiffness, model.pocket_damping, model.cage_mass
    gyro = np.array([[0.0, -2.0 * w], [2.0 * w, 0.0]])
    n = 2 + z
    stiff, damp = np.zeros((n, n)), np.zeros((n, n))
    stiff[:2, :2] = k * push.T @ e_t + model.guide_stiffness * e_r.T @ e_r - mc * w * w * np.eye(2)
    stiff[:2, 2:] = -k * push.T
    damp[:2, :2] = cp * push.T @ e_t + mc * gyro
    damp[:2, 2:] = -cp * push.T
    stiff[2:, 2:] = k * np.eye(z)
    stiff[2:, :2] = -k * e_t
    damp[2:, 2:] = (model.traction_damping + cp) * np.eye(z)
    damp[2:, :2] = -cp * e_t
    return stiff, damp, e_t


def full_model_eigenvalues(model, mu):
    """The exponents of the model with each ball its own coordinate (full_model_matrices), in the
    cage's rotating frame (its real parts are the bearing frame's: the frame turns uniformly).
    Massless balls take c_t w_j' = -k d_j (first order in w_j; no pocket damping then)."""
    stiff, damp, e_t = full_model_matrices(model, mu)
    n, mc, mb = len(stiff), model.cage_mass, model.ball_mass
    if mb > 0:
        inv = np.diag(1.0 / np.array([mc, mc] + [mb] * (n - 2)))
        return np.linalg.eigvals(np.block([[np.zeros((n, n)), np.eye(n)], [-inv @ stiff, -inv @ damp]]))
    if model.pocket_damping != 0:
        raise ValueError("massless balls with pocket damping: not a first-order system here")
    # states [u (2), u' (2), w (Z)]: m_c u'' = -(stiff u + damp u' + coupling w); c_t w' = -k w + k e_t u
    k, ct, z = model.pocket_stiffness, model.traction_damping, n - 2
    a = np.zeros((4 + z, 4 + z))
    a[0:2, 2:4] = np.eye(2)
    a[2:4, 0:2] = -stiff[:2, :2] / mc
    a[2:4, 2:4] = -damp[:2, :2] / mc
    a[2:4, 4:] = -stiff[:2, 2:] / mc
    a[4:, 4:] = -k / ct * np.eye(z)
    a[4:, 0:2] = k / ct * e_t
    return np.linalg.eigvals(a)


# ---- the inputs from a run (docs/atlas.md, "The critical cage friction") --------------------------

def _param(params, key, default=None):
    return params.get(key, {}).get("value", default)


def _ball_mass(model_text):
    """The ball's mass [kg] from the model's description (its first ball's line); 0 when absent."""
    found = re.search(r"ball\[0\]\s+mass\s+([0-9.eE+-]+)\s*kg", model_text or "")
    return float(found[1]) if found else 0.0


def not_applicable(params, bearing):
    """Why the criterion does not apply to the run's bearing and contacts, or None."""
    if bearing.get("rolling_element", "ball") != "ball":
        return "a roller bearing (the criterion is the ball pocket's)"
    if (bearing.get("land_clearance") or 0.0) > 0:
        return "a land-guided cage (it rides its land, not its balls)"
    if _param(params, "contact.ball_cage.normal", "hertz") != "hertz":
        return "a lubricated pocket (its film's shear is not a friction coefficient)"
    if _param(params, "contact.ball_race.traction", "tanh") not in ("tanh", "none"):
        return "a race traction law other than tanh (its slope is not taken)"
    return None


def tanh_slope(mu, scale, load, slip):
    """d F / d(slip) of mu Q tanh(slip / scale) [N s/m]."""
    return mu * load / scale / np.cosh(np.asarray(slip, dtype=float) / scale) ** 2


def traction_damping(out, params, window, balls):
    """c_t per ball: the slope of its race contacts' tanh traction at their sliding, summed over its
    inner and outer contacts, averaged over the window and the balls [N s/m]."""
    if _param(params, "contact.ball_race.traction", "tanh") == "none":
        return 0.0
    mu = _param(params, "contact.ball_race.friction_coefficient", 0.1)
    scale = _param(params, "contact.ball_race.slip_velocity_scale", 0.05)
    total = 0.0
    for kind in ("ball_inner_groove", "ball_outer_groove"):
        if f"segments/{kind}/normal_force" not in out:
            continue
        q = np.asarray(out[f"segments/{kind}/normal_force"], dtype=float)[window]
        slip = np.asarray(out[f"segments/{kind}/slip_velocity"], dtype=float)[window]
        total += float(np.sum(np.mean(tanh_slope(mu, scale, q, slip), axis=0)))
    return total / balls


def measured_traction_damping(out, window, ball_mass):
    """c_t as the run shows it: the races' circumferential force on each ball (its mass times its
    circumferential acceleration less the pocket's force) against the ball's circumferential speed,
    the least-squares slope over the window and the balls, the ball's angle's cosine and sine (its
    weight, once a revolution) and a constant fitted beside it [N s/m]; NaN without the series. The
    ball's own rattling in its pocket is the excitation: the slope of the race contacts as they are
    (a spinning contact's grid, the ball's spin following), not of the tanh law at the centre's slip."""
    need = ("balls/position", "balls/velocity", "balls/acceleration", "segments/ball_pocket/circumferential_force")
    if not ball_mass > 0 or not all(n in out for n in need):
        return math.nan
    pos = np.asarray(out["balls/position"], dtype=float)[window]
    vel = np.asarray(out["balls/velocity"], dtype=float)[window]
    acc = np.asarray(out["balls/acceleration"], dtype=float)[window]
    pocket = np.asarray(out["segments/ball_pocket/circumferential_force"], dtype=float)[window]
    num = den = 0.0
    for j in range(pos.shape[1]):
        angle = np.arctan2(pos[:, j, 1], pos[:, j, 0])
        e_t = np.column_stack([-np.sin(angle), np.cos(angle)])
        speed = np.sum(vel[:, j, :2] * e_t, axis=1)
        race = ball_mass * np.sum(acc[:, j, :2] * e_t, axis=1) - pocket[:, j]
        basis = np.column_stack([np.ones_like(angle), np.cos(angle), np.sin(angle)])
        # The speed's and the force's parts that the nuisance terms do not explain.
        dv = speed - basis @ np.linalg.lstsq(basis, speed, rcond=None)[0]
        df = race - basis @ np.linalg.lstsq(basis, race, rcond=None)[0]
        num -= float(np.sum(dv * df))
        den += float(np.sum(dv * dv))
    return num / den if den > 0 else math.nan


def pocket_law(out, window):
    """The pockets' mean normal force over the window and all pockets, the share of (sample, pocket)
    pairs in contact, and the Hertz constant K of Q = K delta^1.5 (from the elastic energy
    E = 2/5 K delta^2.5 of a contact; NaN when no pocket touched)."""
    q = np.asarray(out["segments/ball_pocket/normal_force"], dtype=float)[window]
    on = q > CONTACT_FORCE
    hertz = math.nan
    if on.any():
        delta = np.asarray(out["segments/ball_pocket/approach"], dtype=float)[window][on]
        energy = np.asarray(out["segments/ball_pocket/elastic_energy"], dtype=float)[window][on]
        hertz = float(np.median(2.5 * energy / delta ** 2.5))
    return float(np.mean(q)), float(np.mean(on)), hertz


def _read_window(out, start, end):
    """What the criterion reads from an open output over start <= t <= end (a dict), or the reason it
    does not apply (a str)."""
    params = out.summary.get("scene_parameters", {})
    bearing = out.bearing
    why = not_applicable(params, bearing)
    if why is None and "segments/ball_pocket/normal_force" not in out:
        why = "no pocket diagnostics in the output"
    if why is not None:
        return why
    t = np.asarray(out.time, dtype=float)
    window = (t >= start) & (t <= (t[-1] if end is None else end))
    balls = int(bearing["element_count"])
    ball_mass = _ball_mass(out.attrs.get("model", ""))
    load, share, hertz = pocket_law(out, window)
    return {"params": params, "clearance": bearing["pocket_clearance"], "balls": balls, "ball_mass": ball_mass,
            "load": load, "share": share, "hertz": hertz,
            "speed": float(np.mean(np.asarray(out["cage/angular_velocity"], dtype=float)[window, 2])),
            "law_c_t": traction_damping(out, params, window, balls),
            "run_c_t": measured_traction_damping(out, window, ball_mass)}


def _model(w, cage_mass, c_t):
    """CageBallModel of what _read_window read."""
    params, load = w["params"], w["load"]
    hunt_crossley = _param(params, "contact.ball_cage.damping", "hunt_crossley") == "hunt_crossley"
    spherical = _param(params, "cage.pocket_shape", "cylindrical") == "spherical"
    return CageBallModel(
        cage_mass=float(cage_mass) if cage_mass else math.nan, balls=w["balls"],
        pocket_stiffness=1.5 * w["hertz"] ** (2.0 / 3.0) * load ** (1.0 / 3.0),  # dQ/d delta at the mean load
        traction_damping=c_t, cage_speed=w["speed"], ball_mass=w["ball_mass"],
        pocket_damping=_param(params, "contact.ball_cage.damping_factor", 0.0) * load if hunt_crossley else 0.0,
        guide_stiffness=2.0 * load / w["clearance"] if spherical else 0.0)


def run_inputs(path, start, end=None, cage_mass=None):
    """The model's inputs from a run's output over start <= t <= end: CageBallModel or None, and the
    evidence (the pocket friction coefficient, the mean pocket load, the contact share, the traction
    slopes, why the criterion does not apply)."""
    from raceway import RacewayOutput

    with RacewayOutput(path, at_segment_rows=True) as out:  # the segment rows' samples
        params = out.summary.get("scene_parameters", {})
        w = _read_window(out, start, end)
    mu = 0.0 if _param(params, "contact.ball_cage.traction", "tanh") == "none" else \
        _param(params, "contact.ball_cage.friction_coefficient", 0.1)
    evidence = {"pocket_friction": mu}
    if isinstance(w, str):
        evidence["critical_pocket_friction_note"] = w
        return None, evidence
    # The run's slope where it has one (positive), else the law's at the contacts' sliding.
    c_t = w["run_c_t"] if w["run_c_t"] > 0 else w["law_c_t"]
    evidence.update({"mean_pocket_load_n": w["load"], "pocket_contact_share": w["share"],
                     "cage_speed_rad_s": w["speed"], "traction_damping_n_s_m": c_t,
                     "traction_damping_law_n_s_m": w["law_c_t"], "traction_damping_run_n_s_m": w["run_c_t"]})
    if not (w["load"] > 0 and math.isfinite(w["hertz"])):
        evidence["critical_pocket_friction_note"] = "no pocket touched in the window"
        return None, evidence
    model = _model(w, cage_mass, c_t)
    evidence.update({"pocket_stiffness_n_m": model.pocket_stiffness, "ball_mass_kg": model.ball_mass,
                     "cage_mass_kg": model.cage_mass, "guide_stiffness_n_m": model.guide_stiffness,
                     "pocket_damping_n_s_m": model.pocket_damping, "centred": bool(model.centred)})
    if w["share"] < PRELOADED_SHARE:
        evidence["critical_pocket_friction_note"] = (
            f"the pockets touch {w['share']:.2g} of the time (< {PRELOADED_SHARE:g}): not preloaded, the linear "
            "criterion is a rough guide")
    return model, evidence


def atlas_evidence(path, start, end=None, cage_mass=None):
    """The atlas's columns (critical_pocket_friction, pocket_friction, pocket_friction_margin = mu / mu_c)
    and the evidence; `applies` only where the model's assumptions hold (ball-driven, preloaded
    pockets)."""
    model, ev = run_inputs(path, start, end, cage_mass)
    ev.update({"critical_pocket_friction": math.nan, "pocket_friction_margin": math.nan,
               "critical_pocket_friction_applies": False})
    if model is None or not math.isfinite(model.cage_mass):
        ev.setdefault("critical_pocket_friction_note", "no cage mass")
        return ev
    mu_c = critical_friction(model)
    ev["critical_pocket_friction"] = mu_c
    ev["critical_pocket_friction_closed_form"] = closed_form(model)
    ev["pocket_friction_margin"] = ev["pocket_friction"] / mu_c if mu_c > 0 else math.inf
    ev["critical_pocket_friction_applies"] = "critical_pocket_friction_note" not in ev
    return ev


def criterion_reason(ev):
    """The classification's extra reason when the pocket friction exceeds the critical one (evidence:
    the simulated class is not changed), else None."""
    margin = ev.get("pocket_friction_margin", math.nan)
    if not margin > 1:
        return None
    where = "" if ev.get("critical_pocket_friction_applies") else f" ({ev.get('critical_pocket_friction_note')})"
    return (f"pocket friction {ev['pocket_friction']:.3g} above the linear criterion's critical "
            f"{ev['critical_pocket_friction']:.3g} (margin {margin:.3g}){where}")
