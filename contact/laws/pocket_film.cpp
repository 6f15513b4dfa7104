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
  // The motion in the frame of e (x' towards the thinnest film): the strips' normals are then
  // (cos, sin)(gamma), gamma = alpha - beta, and the sums turn back to the pocket frame at the end.
  const double vx = cb * v[0] + sb * v[1], vy = -sb * v[0] + cb * v[1];
  const double wx = cb * w[0] + sb * w[1], wy = -sb * w[0] + cb * w[1];
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
  const double sqrt_2rb = std::sqrt(2.0 * rb), slope = c * eps / rp, spin_t = rb * w[2];
  // d(alpha) = root dpsi / (1 + grid_eps cos psi) = root dpsi / (1 + grid_eps) / w2 (w2 below).
  const double arc = rp * root * dpsi / (1.0 + grid_eps);
  const double load_scale = 24.0 * eta * rb * arc, drag_scale = eta * std::numbers::pi * sqrt_2rb * arc;
  const ReynoldsRatioTable& table = reynolds_line_ratio_table();
  double px = 0, py = 0;                  // the pressure's resultant on the ball (frame of e)
  double sx = 0, sy = 0, sa = 0;          // the shear's force on the ball
  double mx = 0, my = 0, ma = 0;          // and its moment about the ball's centre
  double shear_loss = 0;
  for (int k = 0; k < f.points; ++k) {
    // Sommerfeld's variable psi about the thinnest film: tan(gamma / 2) = ratio tan(psi / 2), in
    // half-angle form; w2 = cos^2 + u^2 = (1 + grid_eps cos psi) / (1 + grid_eps).
    const double u = ratio * half_s, hc2 = half_c * half_c, u2 = u * u;
    const double inv_w2 = 1.0 / (hc2 + u2);
    const double cg = (hc2 - u2) * inv_w2, sg = 2.0 * u * half_c * inv_w2;  // n(gamma)
    const double next_c = half_c * step_c - half_s * step_s;
    half_s = half_s * step_c + half_c * step_s;
    half_c = next_c;
    const double h0 = c * (1.0 - eps * cg);
    const double v_t = vy * cg - vx * sg + spin_t;                       // the ball's surface around the pocket
    const double rolling_a = rb * (wx * sg - wy * cg);
    const double v_a = v[2] + rolling_a;                                 // and along the axis
    const double entrainment = 0.5 * (rolling_a - v[2]);
    const double film_rate = -(vx * cg + vy * sg) + 0.5 * v_t * slope * sg;
    // The strip's line film (reynolds_line_film.hpp): 24 eta r_b / h0 |(rho, sigma)| G(t), with
    // sigma = s / sqrt(h0), t = sigma / (rho + |sigma|) = s / den; one division gives 1/sqrt(h0) and t.
    const double root_h0 = std::sqrt(h0);
    const double rho = std::abs(entrainment), s = film_rate * sqrt_2rb;
    const double den = rho * root_h0 + std::abs(s), den_safe = den > 0 ? den : 1.0;
    const double inv = 1.0 / (root_h0 * den_safe);
    const double inv_root_h0 = den_safe * inv, t = s * root_h0 * inv;
    const double magnitude_root_h0 = std::sqrt(rho * rho * h0 + s * s);  // |(rho, sigma)| sqrt(h0)
    const double load = load_scale * inv_w2 * magnitude_root_h0 * (inv_root_h0 * inv_root_h0 * inv_root_h0) * table.at(t);
    px -= load * cg;
    py -= load * sg;
    if (!f.shear) continue;
    // Couette: force on the ball -eta v_slide int dA / h, at r_b n from its centre.
    const double drag = drag_scale * inv_w2 * inv_root_h0;
    const double ft_x = drag * v_t * sg, ft_y = -drag * v_t * cg, ft_a = -drag * v_a;
    sx += ft_x, sy += ft_y, sa += ft_a;
    // r_b n x F, n = (cg, sg, 0).
    mx += rb * sg * ft_a;
    my -= rb * cg * ft_a;
    ma -= rb * drag * v_t;
    shear_loss += drag * (v_t * v_t + v_a * v_a);
  }
  out.power_loss = -(px * vx + py * vy) + shear_loss;
  // Back to the pocket frame.
  const auto turn = [cb, sb](double x, double y) { return std::array<double, 2>{cb * x - sb * y, sb * x + cb * y}; };
  const auto p = turn(px, py), sh = turn(sx, sy), mo = turn(mx, my);
  out.force_on_ball = {p[0] + sh[0], p[1] + sh[1], sa};
  out.moment_on_ball = {mo[0], mo[1], ma};
  out.pressure_force = std::hypot(px, py);
  out.shear_force = std::sqrt(sx * sx + sy * sy + sa * sa);
  out.valid = std::isfinite(px + py + sx + sy + sa + mx + my + ma);
  return out;
}

}  // namespace raceway::contact
