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
  const double ratio = std::sqrt((1.0 - eps) / (1.0 + eps)), root = std::sqrt(1.0 - eps * eps);
  const double dpsi = 2.0 * std::numbers::pi / f.points;
  double px = 0, py = 0;                  // the pressure's resultant on the ball
  double sx = 0, sy = 0, sa = 0;          // the shear's force on the ball
  double mx = 0, my = 0, ma = 0;          // and its moment about the ball's centre
  double shear_loss = 0;
  for (int k = 0; k < f.points; ++k) {
    // Sommerfeld's variable psi about the thinnest film (direction beta of e): alpha - beta from psi.
    const double psi = (k + 0.5) * dpsi;
    const double gamma = 2.0 * std::atan2(ratio * std::sin(0.5 * psi), std::cos(0.5 * psi));
    const double weight = root / (1.0 + eps * std::cos(psi)) * dpsi;  // d(alpha)
    const double cg = std::cos(gamma), sg = std::sin(gamma);
    const double ca = cb * cg - sb * sg, sa_ = sb * cg + cb * sg;  // n(alpha)
    const double h0 = c * (1.0 - eps * cg);
    const double dh0_ds = c * eps * sg / rp;
    const double v_n = v[0] * ca + v[1] * sa_;
    const double v_t = -v[0] * sa_ + v[1] * ca + rb * w[2];             // the ball's surface around the pocket
    const double v_a = v[2] + rb * (w[0] * sa_ - w[1] * ca);             // and along the axis
    const double entrainment = 0.5 * (rb * (w[0] * sa_ - w[1] * ca) - v[2]);
    const double film_rate = -v_n + 0.5 * v_t * dh0_ds;
    const double load = reynolds_line_load_per_length(eta, rb, h0, entrainment, film_rate) * rp * weight;
    px -= load * ca;
    py -= load * sa_;
    if (!f.shear) continue;
    // Couette: force on the ball -eta v_slide int dA / h, at r_b n from its centre.
    const double drag = eta * std::numbers::pi * std::sqrt(2.0 * rb / h0) * rp * weight;
    const double ft_x = -drag * v_t * -sa_, ft_y = -drag * v_t * ca, ft_a = -drag * v_a;
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
