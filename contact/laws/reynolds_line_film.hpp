// The load of a rigid, isoviscous line-contact film that rolls and squeezes at once: a cylinder of
// radius R on a plane (film h(x) = h0 + x^2 / 2R), entrainment speed u_m (mean surface speed
// relative to the contact) and approach rate dh0/dt, with Reynolds' (Swift-Stieber) cavitation
// condition at the outlet. The two motions' pressures do not add: a squeeze moves the outlet, and a
// separating film cavitates where rolling alone would carry load; adding Martin's rolling load to the
// full-film squeeze load overestimates the force by up to 28 % on approach and more on separation.
//
// With x = sqrt(2 R h0) X, H = 1 + X^2 and p = 12 eta b P / h0^2 (b = rolling plus squeeze weights
// below), the Reynolds equation d/dX (H^3 dP/dX) = a dH/dX + s integrates once to
//   H^3 dP/dX = a H + s X + C,   a = cos(phi), s = sin(phi),
// with the direction phi = atan2(sigma, rho) of the motion, rho = |u_m|, sigma = (dh0/dt) sqrt(2 R / h0)
// (sigma < 0 approaching). Inlet at X = -inf (P = 0), outlet X_c with P = dP/dX = 0, so
// C = -(a H(X_c) + s X_c) and X_c solves P(X_c) = 0, closed forms of int H^-2, H^-3, X H^-3; the root
// is unique on the branch where the pressure falls to the outlet (2 a X_c + s > 0), where P(X_c) falls
// monotonically in X_c. The load per unit length is
//   w = 24 eta R / h0 * sqrt(rho^2 + sigma^2) * G(phi),   G(phi) = int P dX = -int X dP/dX dX,
// G(0) = C_M / 12 (Martin, C_M = 2.4475), G(-pi/2) = pi / 8 (the full-film squeeze,
// 3 sqrt(2) pi eta R^1.5 (-dh0/dt) / h0^1.5), G(pi/2) = 0 (pure separation: all cavitated).
// Closed form and root finding here rather than a library: no Debian package solves this one-parameter
// lubrication problem; tests/contact/test_reynolds_line_film.cpp checks it against a finite-difference
// Reynolds solver with cavitation.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>

namespace raceway::contact {

/// G(phi) and the outlet X_c for a motion direction phi in [-pi/2, pi/2] (clamped).
struct ReynoldsLineSolution {
  double load_integral = 0;  ///< G(phi)
  double outlet = 0;         ///< X_c (+inf for pure approach, -inf for pure separation)
};
ReynoldsLineSolution reynolds_line_solution(double phi);
/// G(phi) as the laws take it: reynolds_line_solution tabulated once (1025 nodes) and interpolated by
/// cubic Hermite splines, within 2e-9 of it and smooth to the last bits (the root finding's
/// round-off grows near pure approach, where the pressure balance cancels).
double reynolds_line_load_integral(double phi);
/// The same G as a function of t = sigma / (|rho| + |sigma|) in [-1, 1] (phi = atan2(t, 1 - |t|)), for
/// callers that have rho >= 0 and sigma and would rather not take an arctangent: tabulated once (1025
/// nodes) from reynolds_line_load_integral and interpolated by cubic Hermite splines, within 1e-6 of it.
double reynolds_line_load_integral_of_ratio(double t);

/// The table behind reynolds_line_load_integral_of_ratio, for loops that would rather inline the
/// lookup (the pocket film's strips): at(t) is that function.
class ReynoldsRatioTable {
 public:
  static constexpr int intervals = 1024;
  static constexpr double step = 2.0 / intervals;
  ReynoldsRatioTable();
  double at(double t) const {
    const double x = (std::clamp(t, -1.0, 1.0) + 1.0) * (intervals / 2.0);
    const int i = std::min(static_cast<int>(x), intervals - 1);
    const double u = x - i;
    const auto k = static_cast<std::size_t>(i);
    const double h00 = (1 + 2 * u) * (1 - u) * (1 - u), h10 = u * (1 - u) * (1 - u);
    const double h01 = u * u * (3 - 2 * u), h11 = u * u * (u - 1);
    return std::max(0.0, h00 * value_[k] + h10 * slope_[k] + h01 * value_[k + 1] + h11 * slope_[k + 1]);
  }
  double value(std::size_t k) const { return value_[k]; }  ///< G at node k (t = -1 + k step)
  double slope(std::size_t k) const { return slope_[k]; }  ///< step dG/dt at node k

 private:
  std::array<double, intervals + 1> value_{}, slope_{};  ///< G and step dG/dt at the nodes
};
const ReynoldsRatioTable& reynolds_line_ratio_table();

/// The film's load per unit length [N/m] of a rigid cylinder of radius R on a plane at film
/// thickness h0 > 0, entrainment speed u_m (either sign) and approach rate dh0/dt (< 0 approaching),
/// Reynolds' cavitation condition. 0 without motion.
double reynolds_line_load_per_length(double viscosity, double reduced_radius, double film_thickness,
                                     double entrainment_speed, double film_rate);

}  // namespace raceway::contact
