#include "contact/laws/short_bearing_film.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace raceway::contact {

double strip_pressure_width_cubed(double land_width, double z1, double z2) {
  return 6.0 * (0.25 * land_width * land_width * (z2 - z1) - (z2 * z2 * z2 - z1 * z1 * z1) / 3.0);
}

ShortBearingForce evaluate_short_bearing(const ShortBearingFilm& f, std::array<double, 2> e,
                                         std::array<double, 2> e_rate, double journal_speed, double bore_speed) {
  ShortBearingForce out;
  const double size = std::hypot(e[0], e[1]);
  if (!std::isfinite(size) || !std::isfinite(e_rate[0]) || !std::isfinite(e_rate[1]) ||
      !std::isfinite(journal_speed) || !std::isfinite(bore_speed) || f.points < 1 || !(f.clearance > 0)) {
    out.valid = false;
    return out;
  }
  // The frame of e: x' along e (the thinnest film), y' across it.
  const double cb = size > 0 ? e[0] / size : 1.0, sb = size > 0 ? e[1] / size : 0.0;
  const double rate_x = cb * e_rate[0] + sb * e_rate[1], rate_y = -sb * e_rate[0] + cb * e_rate[1];
  // The floored minimum film and the eccentricity ratio the film sees.
  const double h_min = f.clearance - size, floor = f.film_floor;
  const double h_floor = floor > 0 ? 0.5 * (h_min + floor + std::hypot(h_min - floor, floor)) : std::max(h_min, 0.0);
  out.minimum_film = h_floor;
  const double eps = std::max(0.0, 1.0 - h_floor / f.clearance);
  if (!(eps < 1.0)) return out;  // no floor and the film closed: the dry contact alone
  const double c = f.clearance, mu = f.viscosity, R = f.radius, L = f.width;
  const double l_cubed = f.pressure_width_cubed > 0 ? f.pressure_width_cubed : L * L * L;
  const double rolling = 6.0 * mu * (journal_speed + bore_speed) * eps * c;  // times sin(phi)
  const double ratio = std::sqrt((1.0 - eps) / (1.0 + eps)), root = std::sqrt(1.0 - eps * eps);
  const double dpsi = 2.0 * std::numbers::pi / f.points;
  // d(phi) = root dpsi / (1 + eps cos psi) = arc / w2 (w2 below), and the pressure's constant.
  const double arc = root * dpsi / (1.0 + eps), pressure = l_cubed / 12.0 * R;
  // The half angles psi_k / 2 by rotation: (hc, hs) = (cos, sin)(psi_k / 2), no trigonometry per point.
  double hc = std::cos(0.25 * dpsi), hs = std::sin(0.25 * dpsi);
  const double step_c = hc * hc - hs * hs, step_s = 2.0 * hc * hs;  // the step dpsi / 2 by doubling
  double fx = 0, fy = 0, inverse_film = 0;
  for (int k = 0; k < f.points; ++k) {
    // phi = 2 atan(ratio tan(psi / 2)) in half-angle form: w2 = hc^2 + u^2 = (1 + eps cos psi) / (1 + eps).
    const double u = ratio * hs, hc2 = hc * hc, u2 = u * u;
    const double inv_w2 = 1.0 / (hc2 + u2);
    const double cp = (hc2 - u2) * inv_w2, sp = 2.0 * u * hc * inv_w2;
    const double next_c = hc * step_c - hs * step_s;
    hs = hs * step_c + hc * step_s;
    hc = next_c;
    const double weight = arc * inv_w2;
    const double inv_h = 1.0 / (c * (1.0 - eps * cp));
    const double g = rolling * sp - 12.0 * mu * (rate_x * cp + rate_y * sp);
    inverse_film += weight * inv_h;
    // The cavitated half carries nothing: w = max(0, -g) L^3 / (12 h^3).
    const double w = std::max(0.0, -g) * pressure * (inv_h * inv_h * inv_h) * weight;
    fx -= w * cp;
    fy -= w * sp;
  }
  out.on_journal = {cb * fx - sb * fy, sb * fx + cb * fy};
  // Couette shear of the relative rotation: tau = mu R (omega_j - omega_b) / h over the surface.
  const double relative = journal_speed - bore_speed;
  out.couette_torque = -mu * R * R * R * L * relative * inverse_film;
  out.power_loss = -out.couette_torque * relative + std::max(0.0, -(fx * rate_x + fy * rate_y));
  out.valid = std::isfinite(fx) && std::isfinite(fy);
  return out;
}

}  // namespace raceway::contact
