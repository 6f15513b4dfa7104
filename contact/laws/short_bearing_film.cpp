#include "contact/laws/short_bearing_film.hpp"

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
  double fx = 0, fy = 0, inverse_film = 0;
  for (int k = 0; k < f.points; ++k) {
    const double psi = (k + 0.5) * dpsi;
    const double phi = 2.0 * std::atan2(ratio * std::sin(0.5 * psi), std::cos(0.5 * psi));
    const double weight = root / (1.0 + eps * std::cos(psi)) * dpsi;  // d(phi)
    const double cp = std::cos(phi), sp = std::sin(phi);
    const double h = c * (1.0 - eps * cp);
    const double g = rolling * sp - 12.0 * mu * (rate_x * cp + rate_y * sp);
    inverse_film += weight / h;
    if (g >= 0) continue;  // cavitated
    const double w = -g * l_cubed / (12.0 * h * h * h);
    fx -= w * R * cp * weight;
    fy -= w * R * sp * weight;
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
