#include "contact/laws/pocket_film.hpp"

#include <cmath>
#include <numbers>

#include "contact/laws/reynolds_line_film.hpp"

namespace raceway::contact {

PocketFilmForce evaluate_pocket_film(const PocketFilm& f, const PocketMotion& m) {
  PocketFilmForce out;
  const double size = std::hypot(m.offset[0], m.offset[1]);
  double check = size;
  for (int i = 0; i < 3; ++i) check += m.velocity[static_cast<std::size_t>(i)] + m.angular_velocity[static_cast<std::size_t>(i)];
  if (!std::isfinite(check) || f.points < 1 || !(f.clearance > 0) || !(f.ball_radius > 0)) {
    out.valid = false;
    return out;
  }
  // The floored minimum film and the eccentricity ratio the film sees (as the short journal bearing's).
  const double c = f.clearance, floor = f.film_floor, h_min = c - size;
  const double h_floor = floor > 0 ? 0.5 * (h_min + floor + std::hypot(h_min - floor, floor)) : std::max(h_min, 0.0);
  out.minimum_film = h_floor;
  const double eps = std::max(0.0, 1.0 - h_floor / c);
  if (!(eps < 1.0)) return out;  // no floor and the film closed: the dry contact alone
  const double cb = size > 0 ? m.offset[0] / size : 1.0, sb = size > 0 ? m.offset[1] / size : 0.0;
  const double rb = f.ball_radius, rp = rb + c, eta = f.viscosity;
  const auto& v = m.velocity;
  const auto& w = m.angular_velocity;
  // The grid's eccentricity: the film's, held below grid_eccentricity by a smooth minimum, so that the
  // strips stay dense where the film is thin without leaving the thick side bare (where a separating
  // or sliding ball's film carries its load).
  const double cap = f.grid_eccentricity, q = eps / cap, q2 = q * q, q4 = q2 * q2;
  const double grid_eps = cap < 1.0 ? eps / std::sqrt(std::sqrt(std::sqrt(1.0 + q4 * q4))) : eps;
  const double ratio = std::sqrt((1.0 - grid_eps) / (1.0 + grid_eps)), root = std::sqrt(1.0 - grid_eps * grid_eps);
  const double dpsi = 2.0 * std::numbers::pi / f.points;
  // The strips' half angles psi/2 by rotation (no trigonometry in the loop): (c, s) = (cos, sin)(psi_k / 2).
  const double step_c = std::cos(0.5 * dpsi), step_s = std::sin(0.5 * dpsi);
  double half_c = std::cos(0.25 * dpsi), half_s = std::sin(0.25 * dpsi);
  const double sqrt_2rb = std::sqrt(2.0 * rb);
  double px = 0, py = 0;                  // the pressure's resultant on the ball
  double sx = 0, sy = 0, sa = 0;          // the shear's force on the ball
  double mx = 0, my = 0, ma = 0;          // and its moment about the ball's centre
  double shear_loss = 0;
  for (int k = 0; k < f.points; ++k) {
    // Sommerfeld's variable psi about the thinnest film (direction beta of e): tan(gamma / 2) =
    // ratio tan(psi / 2), gamma = alpha - beta, in half-angle form.
    const double u = ratio * half_s, w2 = half_c * half_c + u * u;
    const double cg = (half_c * half_c - u * u) / w2, sg = 2.0 * u * half_c / w2;
    const double cos_psi = half_c * half_c - half_s * half_s;
    const double weight = root / (1.0 + grid_eps * cos_psi) * dpsi;  // d(alpha)
    const double next_c = half_c * step_c - half_s * step_s;
    half_s = half_s * step_c + half_c * step_s;
    half_c = next_c;
    const double ca = cb * cg - sb * sg, sa_ = sb * cg + cb * sg;  // n(alpha)
    const double h0 = c * (1.0 - eps * cg);
    const double dh0_ds = c * eps * sg / rp;
    const double v_n = v[0] * ca + v[1] * sa_;
    const double v_t = -v[0] * sa_ + v[1] * ca + rb * w[2];             // the ball's surface around the pocket
    const double rolling_a = rb * (w[0] * sa_ - w[1] * ca);
    const double v_a = v[2] + rolling_a;                                 // and along the axis
    const double entrainment = 0.5 * (rolling_a - v[2]);
    const double film_rate = -v_n + 0.5 * v_t * dh0_ds;
    // The strip's line film (reynolds_line_film.hpp): 24 eta r_b / h0 |(rho, sigma)| G(phi).
    const double root_h0 = std::sqrt(h0);
    const double rho = std::abs(entrainment), sigma = film_rate * sqrt_2rb / root_h0;
    const double magnitude = std::sqrt(rho * rho + sigma * sigma);
    const double sum = rho + std::abs(sigma);
    const double load =
        sum > 0 ? 24.0 * eta * rb / h0 * magnitude * reynolds_line_load_integral_of_ratio(sigma / sum) * rp * weight
                : 0.0;
    px -= load * ca;
    py -= load * sa_;
    if (!f.shear) continue;
    // Couette: force on the ball -eta v_slide int dA / h, at r_b n from its centre.
    const double drag = eta * std::numbers::pi * sqrt_2rb / root_h0 * rp * weight;
    const double ft_x = drag * v_t * sa_, ft_y = -drag * v_t * ca, ft_a = -drag * v_a;
    sx += ft_x, sy += ft_y, sa += ft_a;
    // r_b n x F, n = (ca, sa_, 0).
    mx += rb * sa_ * ft_a;
    my -= rb * ca * ft_a;
    ma += rb * (ca * ft_y - sa_ * ft_x);
    shear_loss += drag * (v_t * v_t + v_a * v_a);
  }
  out.force_on_ball = {px + sx, py + sy, sa};
  out.moment_on_ball = {mx, my, ma};
  out.pressure_force = std::hypot(px, py);
  out.shear_force = std::sqrt(sx * sx + sy * sy + sa * sa);
  out.power_loss = -(px * v[0] + py * v[1]) + shear_loss;
  out.valid = std::isfinite(px + py + sx + sy + sa + mx + my + ma);
  return out;
}

}  // namespace raceway::contact
