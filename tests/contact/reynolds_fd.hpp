// A finite-difference Reynolds solver with cavitation, for the tests alone: the reference the
// lubricated laws are checked against, written independently of them.
//
// One-dimensional film h(x) on [-x_max, x_max] with p = 0 at both ends; the Reynolds equation
//   d/dx (h^3 / (12 eta) dp/dx) = u_m dh/dx + dh/dt        (dh/dt a uniform squeeze rate)
// in conservative finite volumes (flux h^3/(12 eta) dp/dx at the faces, the source integrated
// exactly over each cell), on nodes x = width tan(g), g uniform (fine where the film
// is thin). Cavitation by Reynolds' (Swift-Stieber) condition in its complementarity form, as
// Christopherson's projected relaxation has it: p >= 0, the residual of the discretised equation
// >= 0 where p = 0 and = 0 where p > 0. Solved exactly by Howard's policy iteration (each step a
// tridiagonal solve with, at each node, the equation or p = 0, whichever the last iterate makes
// binding); on an M-matrix it ends in finitely many steps (the cavitation boundary moves a node or
// so per step). Half-Sommerfeld (Guembel) is the other choice:
// the full-film solution with its negative part dropped (`guembel`).
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace raceway::contact::test {

struct ReynoldsProfile {
  std::vector<double> x, p;
  double load = 0;  ///< int p dx, trapezoidal [N/m]
};

/// film(x): the film thickness [m]; u: entrainment speed; rate: dh/dt [m/s]; nodes x = width tan(g)
/// (width: the scale of the contact, where the nodes are densest) up to |x| = x_max.
inline ReynoldsProfile solve_reynolds_fd(const std::function<double(double)>& film, double viscosity, double u,
                                         double rate, double width, double x_max, int nodes, bool guembel = false) {
  const int n = nodes;
  const double g_max = std::atan(x_max / width);
  std::vector<double> x(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) x[static_cast<std::size_t>(i)] = width * std::tan(-g_max + 2 * g_max * i / (n - 1));
  // Faces between nodes i and i+1: conductance k = h^3 / (12 eta dx) at the midpoint.
  std::vector<double> k(static_cast<std::size_t>(n - 1)), mid(static_cast<std::size_t>(n - 1));
  for (int i = 0; i + 1 < n; ++i) {
    const std::size_t s = static_cast<std::size_t>(i);
    mid[s] = 0.5 * (x[s] + x[s + 1]);
    const double h = film(mid[s]);
    k[s] = h * h * h / (12 * viscosity * (x[s + 1] - x[s]));
  }
  // Row i (interior): k[i-1] p[i-1] - (k[i-1] + k[i]) p[i] + k[i] p[i+1] = S_i, with
  // S_i = u (h(mid_i) - h(mid_{i-1})) + rate (mid_i - mid_{i-1}). As an M-matrix system: A p = -S
  // with A = -(that operator) (positive diagonal); residual r = A p + S >= 0 in the cavitated zone.
  std::vector<double> source(static_cast<std::size_t>(n), 0.0);
  for (int i = 1; i + 1 < n; ++i) {
    const std::size_t s = static_cast<std::size_t>(i);
    source[s] = u * (film(mid[s]) - film(mid[s - 1])) + rate * (mid[s] - mid[s - 1]);
  }
  std::vector<double> p(static_cast<std::size_t>(n), 0.0);
  std::vector<char> cavitated(static_cast<std::size_t>(n), 0);
  const auto residual = [&](std::size_t i) {  // (A p + S)_i
    return (k[i - 1] + k[i]) * p[i] - k[i - 1] * p[i - 1] - k[i] * p[i + 1] + source[i];
  };
  for (int iteration = 0; iteration < n; ++iteration) {  // the boundary may move a node a step
    // Thomas algorithm on rows: cavitated -> p_i = 0; else (A p)_i = -S_i.
    std::vector<double> lower(static_cast<std::size_t>(n)), diag(static_cast<std::size_t>(n)),
        upper(static_cast<std::size_t>(n)), rhs(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      const std::size_t s = static_cast<std::size_t>(i);
      if (i == 0 || i == n - 1 || cavitated[s]) {
        lower[s] = upper[s] = 0;
        diag[s] = 1;
        rhs[s] = 0;
      } else {
        lower[s] = -k[s - 1];
        upper[s] = -k[s];
        diag[s] = k[s - 1] + k[s];
        rhs[s] = -source[s];
      }
    }
    for (std::size_t i = 1; i < static_cast<std::size_t>(n); ++i) {
      const double m = lower[i] / diag[i - 1];
      diag[i] -= m * upper[i - 1];
      rhs[i] -= m * rhs[i - 1];
    }
    p.back() = rhs.back() / diag.back();
    for (std::size_t i = static_cast<std::size_t>(n - 1); i-- > 0;) p[i] = (rhs[i] - upper[i] * p[i + 1]) / diag[i];
    if (guembel) break;  // the full film; its negative part is dropped below
    bool changed = false;
    for (std::size_t i = 1; i + 1 < static_cast<std::size_t>(n); ++i) {
      const char now = p[i] < residual(i) ? 1 : 0;  // min(p, A p + S) = 0: the smaller one binds
      changed |= now != cavitated[i];
      cavitated[i] = now;
    }
    if (!changed) break;
  }
  ReynoldsProfile out;
  out.x = x;
  out.p = p;
  for (std::size_t i = 0; i + 1 < p.size(); ++i)
    out.load += 0.5 * (std::max(p[i], 0.0) + std::max(p[i + 1], 0.0)) * (x[i + 1] - x[i]);
  return out;
}

}  // namespace raceway::contact::test
