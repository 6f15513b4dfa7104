// A two-dimensional finite-volume Reynolds solver with cavitation, for the tests alone: a ball in a
// cylindrical pocket, written independently of contact/laws/pocket_film.* (it keeps the pressure flow
// around the pocket, which the law's narrow strips leave out, and takes the surface velocity and the
// gap's rate of change point by point from the rigid motion).
//
// Cylinder of radius r_p (the wall, at rest), axis a; the ball (radius r_b, centre off the axis by e in
// the plane across a, at z = 0) moves with velocity v and angular velocity omega. At the wall point
// (alpha, z): gap h = c - e . n(alpha) + z^2 / (2 r_b); the ball's surface velocity there
// U = v + omega x (r_b n + z a) (its components along t = dn/d(alpha) and a); the gap's rate at the
// fixed point dh/dt = -v . n - z v_a / r_b. Reynolds' equation in the wall's frame,
//   div(h^3 / (12 eta) grad p) = div(h U / 2) + dh/dt,
// in conservative finite volumes on nodes (alpha_i, z_j): alpha periodic, on Sommerfeld's grid about
// the thinnest film, z = width tan(g) with g uniform and p = 0 at z = +-z_max. Reynolds' (Swift-
// Stieber) condition in complementarity form (p >= 0, the residual >= 0 where p = 0), solved by
// Christopherson's projected over-relaxation to a relative change below `tolerance`.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace raceway::contact::test {

struct PocketFdProblem {
  double eta = 0, ball_radius = 0, clearance = 0;
  std::array<double, 2> offset{};
  std::array<double, 3> velocity{}, angular_velocity{};
  int n_alpha = 256, n_z = 121;
  double z_max_in_widths = 30;  ///< z_max in units of sqrt(2 r_b h_min)
  double tolerance = 1e-9;
  int max_sweeps = 60000;
};

struct PocketFdResult {
  std::array<double, 2> force_on_ball{};  ///< N, the pressure's resultant
  int sweeps = 0;
};

inline PocketFdResult solve_pocket_fd(const PocketFdProblem& q) {
  const double pi = std::numbers::pi;
  const double rb = q.ball_radius, c = q.clearance, rp = rb + c, eta = q.eta;
  const double e = std::hypot(q.offset[0], q.offset[1]), beta = std::atan2(q.offset[1], q.offset[0]);
  const double eps = e / c, ratio = std::sqrt((1 - eps) / (1 + eps));
  const int na = q.n_alpha, nz = q.n_z;
  std::vector<double> alpha(static_cast<std::size_t>(na)), z(static_cast<std::size_t>(nz));
  for (int i = 0; i < na; ++i) {
    const double psi = -pi + 2 * pi * i / na;
    alpha[static_cast<std::size_t>(i)] = beta + 2 * std::atan2(ratio * std::sin(psi / 2), std::cos(psi / 2));
  }
  const double width = std::sqrt(2 * rb * (c - e)), g_max = std::atan(q.z_max_in_widths);
  for (int j = 0; j < nz; ++j) z[static_cast<std::size_t>(j)] = width * std::tan(-g_max + 2 * g_max * j / (nz - 1));
  const auto& v = q.velocity;
  const auto& w = q.angular_velocity;
  const auto gap = [&](double a, double zz) {
    return c - q.offset[0] * std::cos(a) - q.offset[1] * std::sin(a) + zz * zz / (2 * rb);
  };
  // Ball surface velocity around (t) and along (a) the pocket at (alpha, z): v + omega x (r_b n + z a).
  const auto u_t = [&](double a, double zz) {
    const double ca = std::cos(a), sa = std::sin(a);
    return -v[0] * sa + v[1] * ca + rb * w[2] + zz * (-w[1] * sa - w[0] * ca);
  };
  const auto u_a = [&](double a) { return v[2] + rb * (w[0] * std::sin(a) - w[1] * std::cos(a)); };
  const auto rate = [&](double a, double zz) {
    return -v[0] * std::cos(a) - v[1] * std::sin(a) - zz * v[2] / rb;
  };
  const auto wrap = [&](int i) { return (i + na) % na; };
  const auto a_face = [&](int i) {  // the face between alpha_i and alpha_{i+1}
    double hi = alpha[static_cast<std::size_t>(wrap(i + 1))];
    const double lo = alpha[static_cast<std::size_t>(i)];
    if (hi < lo) hi += 2 * pi;
    return std::array<double, 2>{0.5 * (lo + hi), hi - lo};
  };
  // Conductances and sources, node by node (interior z only).
  const std::size_t n = static_cast<std::size_t>(na) * static_cast<std::size_t>(nz);
  std::vector<double> ke(n, 0), kn(n, 0), source(n, 0);  // ke: to (i+1, j); kn: to (i, j+1)
  const auto at = [&](int i, int j) { return static_cast<std::size_t>(i) * static_cast<std::size_t>(nz) + static_cast<std::size_t>(j); };
  for (int i = 0; i < na; ++i) {
    const auto [am, da] = a_face(i);
    const auto [al, dal] = a_face(wrap(i - 1));
    const double cell_a = 0.5 * (da + dal) * rp;  // arc length of the cell
    (void)al;
    for (int j = 0; j < nz; ++j) {
      const double zj = z[static_cast<std::size_t>(j)];
      if (j + 1 < nz) {
        const double zm = 0.5 * (zj + z[static_cast<std::size_t>(j + 1)]), dz = z[static_cast<std::size_t>(j + 1)] - zj;
        const double h = gap(alpha[static_cast<std::size_t>(i)], zm);
        kn[at(i, j)] = h * h * h / (12 * eta) * cell_a / dz;
      }
      const double zl = j > 0 ? 0.5 * (zj + z[static_cast<std::size_t>(j - 1)]) : zj;
      const double zu = j + 1 < nz ? 0.5 * (zj + z[static_cast<std::size_t>(j + 1)]) : zj;
      const double cell_z = zu - zl;
      {
        const double h = gap(am, zj);
        ke[at(i, j)] = h * h * h / (12 * eta) * cell_z / (da * rp);
      }
      if (j == 0 || j == nz - 1) continue;
      const double ai = alpha[static_cast<std::size_t>(i)];
      // Couette flux out of the cell: faces around (alpha) and along (z), plus dh/dt over the cell.
      const double out_e = gap(am, zj) * u_t(am, zj) / 2 * cell_z;
      const double in_w = gap(al, zj) * u_t(al, zj) / 2 * cell_z;
      const double out_n = gap(ai, zu) * u_a(ai) / 2 * cell_a;
      const double in_s = gap(ai, zl) * u_a(ai) / 2 * cell_a;
      source[at(i, j)] = out_e - in_w + out_n - in_s + rate(ai, zj) * cell_a * cell_z;
    }
  }
  // sum_nb k (p_nb - p) = source; projected over-relaxation.
  std::vector<double> p(n, 0.0);
  const double omega = 1.9;
  PocketFdResult out;
  for (int sweep = 0; sweep < q.max_sweeps; ++sweep) {
    double change = 0, size = 0;
    for (int i = 0; i < na; ++i) {
      const int ip = wrap(i + 1), im = wrap(i - 1);
      for (int j = 1; j + 1 < nz; ++j) {
        const std::size_t s = at(i, j);
        const double k_e = ke[s], k_w = ke[at(im, j)], k_n = kn[s], k_s = kn[at(i, j - 1)];
        const double sum = k_e * p[at(ip, j)] + k_w * p[at(im, j)] + k_n * p[at(i, j + 1)] + k_s * p[at(i, j - 1)];
        const double gauss_seidel = (sum - source[s]) / (k_e + k_w + k_n + k_s);
        const double next = std::max(0.0, p[s] + omega * (gauss_seidel - p[s]));
        change = std::max(change, std::abs(next - p[s]));
        size = std::max(size, next);
        p[s] = next;
      }
    }
    out.sweeps = sweep + 1;
    if (size > 0 && change < q.tolerance * size) break;
  }
  // The pressure's force on the ball: -int p n dA.
  for (int i = 0; i < na; ++i) {
    const auto [am, da] = a_face(i);
    const auto [al, dal] = a_face(wrap(i - 1));
    (void)am, (void)al;
    const double ai = alpha[static_cast<std::size_t>(i)], cell_a = 0.5 * (da + dal) * rp;
    for (int j = 1; j + 1 < nz; ++j) {
      const double cell_z = 0.5 * (z[static_cast<std::size_t>(j + 1)] - z[static_cast<std::size_t>(j - 1)]);
      const double f = p[at(i, j)] * cell_a * cell_z;
      out.force_on_ball[0] -= f * std::cos(ai);
      out.force_on_ball[1] -= f * std::sin(ai);
    }
  }
  return out;
}

}  // namespace raceway::contact::test
