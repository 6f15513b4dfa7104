#include "contact/laws/pocket_film.hpp"

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <numbers>

#include "contact/laws/reynolds_line_film.hpp"

namespace raceway::contact {

namespace {

// The strips go in blocks of `lanes` as Eigen arrays (the compiler's vector units, and the strips'
// divisions and square roots overlap), the lanes past the last strip weighted by zero.
constexpr int lanes = 16;
using Block = Eigen::Array<double, lanes, 1>;

/// What the strips share: the film's constants and the ball's motion in the frame of e (x' towards
/// the thinnest film), where strip gamma = alpha - beta has the normal (cos, sin)(gamma).
struct Strips {
  double c, eps, rb, slope, sqrt_2rb, ratio, load_scale, drag_scale;
  double vx, vy, va, wx, wy, spin_t;
  bool shear;
};

/// The strips' sums in the frame of e: the pressure's resultant, the shear's force and moment.
struct Sums {
  double px = 0, py = 0, sx = 0, sy = 0, sa = 0, mx = 0, my = 0, ma = 0, shear_loss = 0;
};

/// The ratio table's G(t) over a block (ReynoldsRatioTable::at): the arithmetic in the vector units,
/// the nodes gathered lane by lane.
Block load_integral(const Block& t) {
  const ReynoldsRatioTable& table = reynolds_line_ratio_table();
  constexpr int n = ReynoldsRatioTable::intervals;
  // Clamped to [-1, 1] by comparisons, which also send a NaN (a film whose sums come out invalid) to
  // a node rather than an integer conversion of NaN.
  const Block x = ((t >= -1.0).select((t <= 1.0).select(t, 1.0), -1.0) + 1.0) * (n / 2.0);
  const Eigen::Array<int, lanes, 1> node = x.cast<int>().min(n - 1);
  const Block u = x - node.cast<double>(), a = 1.0 - u;
  Block v0, s0, v1, s1;
  for (int i = 0; i < lanes; ++i) {
    const auto k = static_cast<std::size_t>(node[i]);
    v0[i] = table.value(k);
    s0[i] = table.slope(k);
    v1[i] = table.value(k + 1);
    s1[i] = table.slope(k + 1);
  }
  const Block hermite = (1.0 + 2.0 * u) * a.square() * v0 + u * a.square() * s0 + u.square() * (3.0 - 2.0 * u) * v1 +
                        u.square() * (u - 1.0) * s1;
  return hermite.max(0.0);
}

/// One block of strips, (hc, hs) = (cos, sin)(psi / 2) of Sommerfeld's variable psi, weighted by `mask`.
void add_block(const Strips& s, const Block& hc, const Block& hs, const Block& mask, Sums& out) {
  // tan(gamma / 2) = ratio tan(psi / 2) in half-angle form; w2 = cos^2 + u^2 = (1 + grid_eps cos psi) /
  // (1 + grid_eps), so that d(alpha) = root dpsi / (1 + grid_eps cos psi) is in load_scale / w2.
  const Block u = s.ratio * hs, hc2 = hc.square(), u2 = u.square();
  const Block inv_w2 = (hc2 + u2).inverse();
  const Block cg = (hc2 - u2) * inv_w2, sg = 2.0 * u * hc * inv_w2;
  const Block h0 = s.c * (1.0 - s.eps * cg);
  const Block v_t = s.vy * cg - s.vx * sg + s.spin_t;  // the ball's surface around the pocket
  const Block rolling_a = s.rb * (s.wx * sg - s.wy * cg);
  const Block entrainment = 0.5 * (rolling_a - s.va);
  const Block film_rate = (0.5 * s.slope) * v_t * sg - (s.vx * cg + s.vy * sg);
  // The strip's line film (reynolds_line_film.hpp): 24 eta r_b / h0 |(rho, sigma)| G(t), with
  // sigma = sig / sqrt(h0), t = sigma / (rho + |sigma|) = sig / den; one division gives 1/sqrt(h0) and t.
  const Block root_h0 = h0.sqrt(), rho = entrainment.abs(), sig = s.sqrt_2rb * film_rate;
  const Block den = rho * root_h0 + sig.abs();
  const Block den_safe = (den > 0.0).select(den, Block::Ones());
  const Block inv = (root_h0 * den_safe).inverse();
  const Block inv_root_h0 = den_safe * inv, t = sig * root_h0 * inv;
  const Block g = load_integral(t);
  const Block arc = mask * inv_w2;
  const Block load = s.load_scale * arc * (rho.square() * h0 + sig.square()).sqrt() * inv_root_h0.cube() * g;
  out.px -= (load * cg).sum();
  out.py -= (load * sg).sum();
  if (!s.shear) return;
  // Couette: force on the ball -eta v_slide int dA / h, at r_b n from its centre; moment r_b n x F.
  const Block drag = s.drag_scale * arc * inv_root_h0, v_a = s.va + rolling_a;
  const Block f_t = drag * v_t, f_a = -drag * v_a;
  out.sx += (f_t * sg).sum();
  out.sy -= (f_t * cg).sum();
  out.sa += f_a.sum();
  out.mx += s.rb * (sg * f_a).sum();
  out.my -= s.rb * (cg * f_a).sum();
  out.ma -= s.rb * f_t.sum();
  out.shear_loss += (drag * (v_t.square() + v_a.square())).sum();
}

/// All the strips: psi_k = (k + 1/2) dpsi; the half angles of the first block by rotations that
/// double the filled lanes each time (the step dpsi / 2 doubled as it goes), of the next blocks by
/// rotating the block by lanes dpsi / 2: one sine and cosine a call, no trigonometry per strip.
Sums sum_strips(const Strips& s, int points) {
  static_assert((lanes & (lanes - 1)) == 0, "lanes: a power of 2");
  const double dpsi = 2.0 * std::numbers::pi / points;
  Block hc, hs;
  hc[0] = std::cos(0.25 * dpsi);
  hs[0] = std::sin(0.25 * dpsi);
  double turn_c = hc[0] * hc[0] - hs[0] * hs[0], turn_s = 2.0 * hc[0] * hs[0];  // dpsi / 2
  for (int filled = 1; filled < lanes; filled *= 2) {
    for (int i = 0; i < filled; ++i) {
      hc[filled + i] = hc[i] * turn_c - hs[i] * turn_s;
      hs[filled + i] = hs[i] * turn_c + hc[i] * turn_s;
    }
    const double c2 = turn_c * turn_c - turn_s * turn_s;
    turn_s = 2.0 * turn_c * turn_s;
    turn_c = c2;
  }
  const double block_c = turn_c, block_s = turn_s;  // lanes dpsi / 2
  Sums out;
  for (int first = 0; first < points; first += lanes) {
    Block mask = Block::Ones();
    for (int i = points - first; i < lanes; ++i) mask[i] = 0.0;
    add_block(s, hc, hs, mask, out);
    const Block next_c = hc * block_c - hs * block_s;
    hs = hs * block_c + hc * block_s;
    hc = next_c;
  }
  return out;
}

/// The strips' constants for a film at eccentricity ratio eps, e along (cb, sb) in the pocket frame.
Strips make_strips(const PocketFilm& f, const PocketMotion& m, double eps, double cb, double sb) {
  const double c = f.clearance, rb = f.ball_radius, rp = rb + c, eta = f.viscosity;
  const auto& v = m.velocity;
  const auto& w = m.angular_velocity;
  // The grid's eccentricity: the film's, held below grid_eccentricity by a smooth minimum, so that the
  // strips stay dense where the film is thin without leaving the thick side bare (where a separating
  // or sliding ball's film carries its load).
  const double cap = f.grid_eccentricity, q = eps / cap, q2 = q * q, q4 = q2 * q2;
  const double grid_eps = cap < 1.0 ? eps / std::sqrt(std::sqrt(std::sqrt(1.0 + q4 * q4))) : eps;
  const double root = std::sqrt(1.0 - grid_eps * grid_eps);
  const double arc = rp * root * (2.0 * std::numbers::pi / f.points) / (1.0 + grid_eps);  // times 1 / w2
  const double sqrt_2rb = std::sqrt(2.0 * rb);
  return {.c = c, .eps = eps, .rb = rb, .slope = c * eps / rp, .sqrt_2rb = sqrt_2rb,
          .ratio = std::sqrt((1.0 - grid_eps) / (1.0 + grid_eps)), .load_scale = 24.0 * eta * rb * arc,
          .drag_scale = eta * std::numbers::pi * sqrt_2rb * arc, .vx = cb * v[0] + sb * v[1],
          .vy = -sb * v[0] + cb * v[1], .va = v[2], .wx = cb * w[0] + sb * w[1], .wy = -sb * w[0] + cb * w[1],
          .spin_t = rb * w[2], .shear = f.shear};
}

/// The sums turned back from the frame of e to the pocket frame.
void finish(const Sums& s, const Strips& strips, double cb, double sb, PocketFilmForce& out) {
  out.power_loss = -(s.px * strips.vx + s.py * strips.vy) + s.shear_loss;
  const auto turn = [cb, sb](double x, double y) { return std::array<double, 2>{cb * x - sb * y, sb * x + cb * y}; };
  const auto p = turn(s.px, s.py), sh = turn(s.sx, s.sy), mo = turn(s.mx, s.my);
  out.force_on_ball = {p[0] + sh[0], p[1] + sh[1], s.sa};
  out.moment_on_ball = {mo[0], mo[1], s.ma};
  out.pressure_force = std::sqrt(s.px * s.px + s.py * s.py);
  out.shear_force = std::sqrt(s.sx * s.sx + s.sy * s.sy + s.sa * s.sa);
  out.valid = std::isfinite(s.px + s.py + s.sx + s.sy + s.sa + s.mx + s.my + s.ma);
}

}  // namespace

PocketFilmForce evaluate_pocket_film(const PocketFilm& f, const PocketMotion& m) {
  PocketFilmForce out;
  const double size = std::sqrt(m.offset[0] * m.offset[0] + m.offset[1] * m.offset[1]);  // no std::hypot: slow
  double check = size;
  for (int i = 0; i < 3; ++i) check += m.velocity[static_cast<std::size_t>(i)] + m.angular_velocity[static_cast<std::size_t>(i)];
  if (!std::isfinite(check) || f.points < 1 || !(f.clearance > 0) || !(f.ball_radius > 0)) {
    out.valid = false;
    return out;
  }
  // The floored minimum film and the eccentricity ratio the film sees (as the short journal bearing's).
  const double c = f.clearance, floor = f.film_floor, h_min = c - size;
  const double over = h_min - floor;
  const double h_floor = floor > 0 ? 0.5 * (h_min + floor + std::sqrt(over * over + floor * floor)) : std::max(h_min, 0.0);
  out.minimum_film = h_floor;
  const double eps = std::max(0.0, 1.0 - h_floor / c);
  if (!(eps < 1.0)) return out;  // no floor and the film closed: the dry contact alone
  const double cb = size > 0 ? m.offset[0] / size : 1.0, sb = size > 0 ? m.offset[1] / size : 0.0;
  const Strips strips = make_strips(f, m, eps, cb, sb);
  finish(sum_strips(strips, f.points), strips, cb, sb, out);
  return out;
}

}  // namespace raceway::contact
