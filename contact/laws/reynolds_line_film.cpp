#include "contact/laws/reynolds_line_film.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace raceway::contact {

namespace {

constexpr double pi = std::numbers::pi;

// Integrals from the inlet X = -inf to x, H = 1 + X^2, written in g = atan(x) (no cancellation
// near the inlet): int H^-2 = (g + pi/2)/2 + sin(2g)/4, int H^-3 = 3 (g + pi/2)/8 + sin(2g)/4 +
// sin(4g)/32, int X H^-3 = -cos^4(g)/4, int X H^-2 = -cos^2(g)/2, int X^2 H^-3 = int H^-2 - int H^-3.
struct InletIntegrals {
  double h2, h3, xh3, xh2, x2h3;
};
InletIntegrals inlet_integrals(double g) {
  const double t = g + pi / 2, c = std::cos(g), c2 = c * c;
  InletIntegrals i{};
  i.h2 = 0.5 * t + 0.25 * std::sin(2 * g);
  i.h3 = 0.375 * t + 0.25 * std::sin(2 * g) + std::sin(4 * g) / 32.0;
  i.xh3 = -0.25 * c2 * c2;
  i.xh2 = -0.5 * c2;
  i.x2h3 = i.h2 - i.h3;
  return i;
}

/// P(X_c) with the outlet at X_c = tan(g) (C from dP/dX = 0 there), times cos^2(g) to keep it
/// bounded as X_c -> +inf; and the load integral G for that outlet.
struct OutletState {
  double pressure_scaled, load;
};
OutletState outlet_state(double g, double a, double s) {
  const InletIntegrals i = inlet_integrals(g);
  const double c = std::cos(g), sn = std::sin(g);
  // C cos^2 g = -(a (cos^2 g + sin^2 g) + s sin g cos g) = -(a + s sin g cos g).
  const double c_scaled = -(a + s * sn * c);
  const double c2 = c * c;
  const double pressure_scaled = c2 * (a * i.h2 + s * i.xh3) + c_scaled * i.h3;
  // G = -(a int X H^-2 + s int X^2 H^-3 + C int X H^-3); C int X H^-3 = -c_scaled cos^2 g / 4.
  const double load = -(a * i.xh2 + s * i.x2h3) + c_scaled * 0.25 * c2;
  return {pressure_scaled, load};
}

}  // namespace

ReynoldsLineSolution reynolds_line_solution(double phi) {
  phi = std::clamp(phi, -pi / 2, pi / 2);
  const double a = std::cos(phi), s = std::sin(phi);
  constexpr double inf = std::numeric_limits<double>::infinity();
  if (a <= 1e-14) return s < 0 ? ReynoldsLineSolution{pi / 8, inf} : ReynoldsLineSolution{0.0, -inf};
  // The outlet lies where the pressure falls (2 a X + s > 0), X > -s / 2a; there P(X_c) falls
  // monotonically from > 0 to -inf (scaled: to a negative limit). Bisection in g = atan(X_c),
  // to the last bit: a fixed number of halvings keeps the law a smooth function for the Jacobian's
  // finite differences (the error of 80 halvings is below one ulp of g).
  double lo = std::atan(-s / (2 * a)), hi = pi / 2;
  for (int it = 0; it < 80; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (outlet_state(mid, a, s).pressure_scaled > 0 ? lo : hi) = mid;
  }
  const double g = 0.5 * (lo + hi);
  return {std::max(0.0, outlet_state(g, a, s).load), std::tan(g)};
}

namespace {

/// G(phi) tabulated once on a uniform grid over [-pi/2, pi/2] and interpolated by cubic Hermite
/// splines (node slopes by central differences of the solution): smooth to the last bits, which the
/// root finding is not near pure approach (its pressure balance cancels there), and a few flops a
/// call. Interpolation error below 5e-9 of pi/8 (checked in the tests against the solution).
class LoadTable {
 public:
  static constexpr int intervals = 1024;
  LoadTable() {
    const double step = pi / intervals, d = 1e-5;
    for (int i = 0; i <= intervals; ++i) {
      const double phi = -pi / 2 + step * i;
      value_[static_cast<std::size_t>(i)] = reynolds_line_solution(phi).load_integral;
      // One-sided at the ends (G is flat in approach, and falls to 0 with a flat tail in separation).
      const double lo = std::max(phi - d, -pi / 2), hi = std::min(phi + d, pi / 2);
      slope_[static_cast<std::size_t>(i)] =
          (reynolds_line_solution(hi).load_integral - reynolds_line_solution(lo).load_integral) / (hi - lo);
    }
  }
  double at(double phi) const {
    const double step = pi / intervals;
    const double x = (std::clamp(phi, -pi / 2, pi / 2) + pi / 2) / step;
    const int i = std::min(static_cast<int>(x), intervals - 1);
    const double t = x - i;
    const std::size_t k = static_cast<std::size_t>(i);
    const double h00 = (1 + 2 * t) * (1 - t) * (1 - t), h10 = t * (1 - t) * (1 - t);
    const double h01 = t * t * (3 - 2 * t), h11 = t * t * (t - 1);
    return std::max(0.0, h00 * value_[k] + h10 * step * slope_[k] + h01 * value_[k + 1] + h11 * step * slope_[k + 1]);
  }

 private:
  std::array<double, intervals + 1> value_{}, slope_{};
};

}  // namespace

double reynolds_line_load_integral(double phi) {
  static const LoadTable table;
  return table.at(phi);
}

// G(t), t = sigma / (|rho| + |sigma|): nodes uniform in t over [-1, 1], values and slopes from the
// phi table (dG/dt = G'(phi) dphi/dt, dphi/dt = 1 / ((1 - |t|)^2 + t^2)), Hermite between them.
ReynoldsRatioTable::ReynoldsRatioTable() {
  const double d = 1e-6;
  for (int i = 0; i <= intervals; ++i) {
    const double t = -1.0 + step * i;
    const auto g = [](double x) { return reynolds_line_load_integral(std::atan2(x, 1.0 - std::abs(x))); };
    value_[static_cast<std::size_t>(i)] = g(t);
    const double lo = std::max(t - d, -1.0), hi = std::min(t + d, 1.0);
    slope_[static_cast<std::size_t>(i)] = step * (g(hi) - g(lo)) / (hi - lo);
  }
}

const ReynoldsRatioTable& reynolds_line_ratio_table() {
  static const ReynoldsRatioTable table;
  return table;
}

double reynolds_line_load_integral_of_ratio(double t) { return reynolds_line_ratio_table().at(t); }

double reynolds_line_load_per_length(double viscosity, double reduced_radius, double h0, double u_m,
                                     double film_rate) {
  const double rho = std::abs(u_m), sigma = film_rate * std::sqrt(2.0 * reduced_radius / h0);
  const double magnitude = std::hypot(rho, sigma);
  if (!(magnitude > 0)) return 0.0;
  const double phi = std::atan2(sigma, rho);
  return 24.0 * viscosity * reduced_radius / h0 * magnitude * reynolds_line_load_integral(phi);
}

}  // namespace raceway::contact
