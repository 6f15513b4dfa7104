// Point-contact laws (contact/laws/point_contact.hpp).
//
// Hertz's elliptical contact, after Johnson, Contact Mechanics (1985), ch. 3 (pressure on an
// elliptical region) and sec. 4.2, and Harris & Kotzalas, Essential Concepts of Bearing Technology
// (2007), ch. 6. The gap between the undeformed bodies is A x^2 + B y^2 with A = kx/2, B = ky/2.
// Under the semi-ellipsoidal pressure p = p0 sqrt(1 - (x/a)^2 - (y/b)^2), a >= b (a along the
// direction of the smaller curvature), the combined surface displacement inside the ellipse is
// (L - M x^2 - N y^2) / (pi E*) with (e^2 = 1 - (b/a)^2 = m; K, E complete elliptic integrals of
// modulus e)
//   L = pi p0 b K,  M = pi p0 b (K - E) / (e^2 a^2),  N = pi p0 b ((a/b)^2 E - K) / (e^2 a^2).
// Matching it to delta - A x^2 - B y^2 gives N/M = B/A, i.e. Harris & Kotzalas' curvature
// difference
//   F(rho) = (B - A) / (B + A) = ((k^2 + 1) E - 2 K) / ((k^2 - 1) E),  k = a / b
// (the same relation as (K - E) / ((a/b)^2 E - K) = A/B in table 9-4 of a handbook chapter
// "9 Contact Stresses", www.yumpu.com/en/document/view/11396479/9-contact-stresses/35), and, from
// M + N and L with Q = 2/3 pi a b p0,
//   b^3 = 3 E Q / (pi k E* (kx + ky)),  a = k b,  delta = 3 K Q / (2 pi k b E*),  Q = K_s delta^1.5.
// F(rho) = F(m) is solved for m = e^2 by safeguarded Newton; F is a smooth function of m with
// F = 3m/8 + 3m^2/16 + O(m^3) at the circle, evaluated near the circle from the power series of K
// and E (no 0/0), from std::comp_ellint_1/2 elsewhere. Hamrock & Brewe's (1983) closed forms are
// used only inside the EHL fits (and as the tests' comparison).
#include "contact/laws/point_contact.hpp"

#include "contact/laws/viscosity.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>

namespace raceway::contact {
namespace {

constexpr double pi = std::numbers::pi;

/// Same bits: true when a and b are the same double, bit for bit (-0 and 0 differ, a NaN equals
/// itself), so a factor kept for a is the one b would give.
inline bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

// ---- the ellipticity relation F(m), m = e^2 = 1 - 1/k^2 -----------------------------------------

// Below this m the relation is evaluated from series: the direct form loses about 1e-16 / m^2 of
// relative accuracy to cancellation; at 0.25 both agree to ~1e-14.
constexpr double series_limit = 0.25;
constexpr int series_terms = 36;  // 0.25^36 ~ 2e-22: series truncation far below round-off

struct EllipticitySeries {
  // F(m) = m P(m) / Q(m), P and Q polynomials in m (coefficients without the common pi/2).
  std::array<double, series_terms> p{}, q{};
};

constexpr EllipticitySeries make_series() {
  // K(m) = pi/2 sum t_n^2 m^n, E(m) = pi/2 sum t_n^2 m^n / (1 - 2n), t_n = (2n-1)!! / (2n)!!.
  std::array<double, series_terms + 2> kc{}, ec{};
  double t = 1;
  for (int n = 0; n < series_terms + 2; ++n) {
    if (n > 0) t *= (2.0 * n - 1.0) / (2.0 * n);
    kc[static_cast<std::size_t>(n)] = t * t;
    ec[static_cast<std::size_t>(n)] = t * t / (1.0 - 2.0 * n);
  }
  // Numerator (2-m) E - 2 (1-m) K = pi/2 sum c_j m^j with c_0 = c_1 = 0; P(m) = sum c_{j+2} m^j.
  EllipticitySeries s;
  for (int j = 0; j < series_terms; ++j) {
    const auto i = static_cast<std::size_t>(j + 2);
    s.p[static_cast<std::size_t>(j)] = 2 * ec[i] - ec[i - 1] - 2 * kc[i] + 2 * kc[i - 1];
    s.q[static_cast<std::size_t>(j)] = ec[static_cast<std::size_t>(j)];
  }
  return s;
}
constexpr EllipticitySeries ellipticity_series = make_series();

struct ValueSlope {
  double value, slope;
};

// F(m) and dF/dm.
ValueSlope curvature_difference(double m) {
  if (m < series_limit) {
    double p = 0, dp = 0, q = 0, dq = 0;
    for (int j = series_terms - 1; j >= 0; --j) {  // Horner, with derivatives
      const auto i = static_cast<std::size_t>(j);
      dp = dp * m + p;
      p = p * m + ellipticity_series.p[i];
      dq = dq * m + q;
      q = q * m + ellipticity_series.q[i];
    }
    return {m * p / q, (p + m * dp) / q - m * p * dq / (q * q)};
  }
  const double e = std::sqrt(m);
  const double kk = std::comp_ellint_1(e), ee = std::comp_ellint_2(e);
  const double num = (2 - m) * ee - 2 * (1 - m) * kk, den = m * ee;
  // dK/dm = (E - (1-m) K) / (2 m (1-m)), dE/dm = (E - K) / (2m) give
  // d num/dm = 3 (K - E) / 2 and d den/dm = (3E - K) / 2.
  const double dnum = 1.5 * (kk - ee), dden = 0.5 * (3 * ee - kk);
  return {num / den, (dnum * den - num * dden) / (den * den)};
}

// The m in [0, 1) with F(m) = target, target in [0, 1).
double solve_eccentricity_squared(double target, double curvature_ratio) {
  if (target <= 0) return 0;
  double lo = 0, hi = 1;
  // Start: F ~ 3m/8 near the circle; else Brewe & Hamrock's k ~ (kmax/kmin)^(2/pi).
  double m;
  if (target < 0.05) {
    m = 8 * target / 3;
  } else {
    const double k0 = std::pow(curvature_ratio, 2 / pi);
    m = 1 - 1 / (k0 * k0);
  }
  for (int iteration = 0; iteration < 200; ++iteration) {
    const ValueSlope f = curvature_difference(m);
    const double r = f.value - target;
    if (r == 0) break;
    (r < 0 ? lo : hi) = m;
    double next = m - r / f.slope;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);  // bisection when Newton leaves
    if (std::abs(next - m) <= 1e-16 * m || hi - lo <= 4 * std::numeric_limits<double>::epsilon() * m) {
      m = next;
      break;
    }
    m = next;
  }
  return m;
}

// ---- traction grid -------------------------------------------------------------------------------

// Area and first moments of the part of the unit disk inside [x0, x1] x [y0, y1], exactly:
// the vertical chord at x is [max(y0, -s), min(y1, s)], s = sqrt(1 - x^2); between the abscissae
// where s crosses |y0| and |y1| the chord ends are either constant or +-s, and the integrals of
// 1, x, s, x s, s^2 have closed forms.
struct Moments {
  double area = 0, mx = 0, my = 0;
};

Moments disk_rectangle_moments(double x0, double x1, double y0, double y1) {
  x0 = std::max(x0, -1.0);
  x1 = std::min(x1, 1.0);
  Moments out;
  if (!(x1 > x0)) return out;
  std::array<double, 6> cuts{};
  int n = 0;
  cuts[static_cast<std::size_t>(n++)] = x0;
  cuts[static_cast<std::size_t>(n++)] = x1;
  for (const double y : {y0, y1}) {
    if (std::abs(y) >= 1) continue;
    const double c = std::sqrt(1 - y * y);
    for (const double x : {-c, c})
      if (x > x0 && x < x1) cuts[static_cast<std::size_t>(n++)] = x;
  }
  for (int i = 1; i < n; ++i)  // insertion sort of at most six abscissae
    for (int j = i; j > 0 && cuts[static_cast<std::size_t>(j)] < cuts[static_cast<std::size_t>(j - 1)]; --j)
      std::swap(cuts[static_cast<std::size_t>(j)], cuts[static_cast<std::size_t>(j - 1)]);
  auto root = [](double x) { return std::sqrt(std::max(0.0, 1 - x * x)); };
  auto int_s = [&](double x) { return 0.5 * (x * root(x) + std::asin(std::clamp(x, -1.0, 1.0))); };
  auto int_xs = [&](double x) {
    const double r = root(x);
    return -r * r * r / 3;
  };
  auto int_s2 = [](double x) { return x - x * x * x / 3; };
  for (int i = 0; i + 1 < n; ++i) {
    const double u = cuts[static_cast<std::size_t>(i)], v = cuts[static_cast<std::size_t>(i + 1)];
    if (!(v > u)) continue;
    const double s_mid = root(0.5 * (u + v));
    const bool upper_curve = y1 >= s_mid, lower_curve = y0 <= -s_mid;
    const double hi_mid = upper_curve ? s_mid : y1, lo_mid = lower_curve ? -s_mid : y0;
    if (!(hi_mid > lo_mid)) continue;
    const double d1 = v - u, dx = 0.5 * (v * v - u * u);
    const double ds = int_s(v) - int_s(u), dxs = int_xs(v) - int_xs(u), ds2 = int_s2(v) - int_s2(u);
    // Integrals of the upper end h(x) and lower end l(x): of h, x h, h^2 (same for l).
    const double h = upper_curve ? ds : y1 * d1, xh = upper_curve ? dxs : y1 * dx;
    const double h2 = upper_curve ? ds2 : y1 * y1 * d1;
    const double l = lower_curve ? -ds : y0 * d1, xl = lower_curve ? -dxs : y0 * dx;
    const double l2 = lower_curve ? ds2 : y0 * y0 * d1;
    out.area += h - l;
    out.mx += xh - xl;
    out.my += 0.5 * (h2 - l2);
  }
  return out;
}

// The grid in the unit disk (coordinates x/ax, y/ay): cells that overlap it, with their exact
// overlap area, the centroid of the overlap and the Hertz pressure shape sqrt(1 - r^2) there.
struct GridCell {
  double x, y;   // centroid, unit disk
  double area;   // unit disk
  double load;   // fraction of the normal load: area * shape / sum(area * shape)
  double shape;  // sqrt(1 - x^2 - y^2)
  int shape_index;  // of `shape` in the grid's distinct shapes
};
// The grid is exactly symmetric about both axes: a cell takes the moments of its mirror image in
// x >= 0, y >= 0, the centroid's signs flipped (on an axis: exactly on it), so mirrored cells share
// their shape's bits and the viscosity is evaluated once per distinct shape (5 x 5: 6 for 25 cells).
inline constexpr std::size_t max_distinct_shapes = 64;
struct TractionGrid {
  int gx = 0, gy = 0;
  double shape_integral = 0;  // sum area * shape (-> 2 pi / 3 as the grid refines)
  std::vector<GridCell> cells;
  std::vector<double> shapes;  // the distinct shapes, in order of first appearance
};

// Column (or row) i of n over [-1, 1] as its mirror image with the larger centre: its bounds ((2 i -
// n) / n: the same bits for i and n - 1 - i) and the sign (+1, -1, 0 on the axis) of its centroid.
struct MirroredSpan {
  double lo, hi, sign;
};
MirroredSpan mirrored_span(int i, int n) {
  const int k = std::max(i, n - 1 - i);
  const double sign = 2 * i + 1 == n ? 0.0 : (k == i ? 1.0 : -1.0);
  return {static_cast<double>(2 * k - n) / n, static_cast<double>(2 * k + 2 - n) / n, sign};
}

std::unique_ptr<TractionGrid> build_grid(int gx, int gy) {
  auto grid = std::make_unique<TractionGrid>();
  grid->gx = gx;
  grid->gy = gy;
  const double cell_area = 4.0 / (static_cast<double>(gx) * gy);
  for (int i = 0; i < gx; ++i) {
    const MirroredSpan sx = mirrored_span(i, gx);
    for (int j = 0; j < gy; ++j) {
      const MirroredSpan sy = mirrored_span(j, gy);
      const Moments mo = disk_rectangle_moments(sx.lo, sx.hi, sy.lo, sy.hi);
      if (!(mo.area > 1e-14 * cell_area)) continue;
      GridCell c{};
      c.area = mo.area;
      c.x = sx.sign == 0 ? 0.0 : sx.sign * (mo.mx / mo.area);
      c.y = sy.sign == 0 ? 0.0 : sy.sign * (mo.my / mo.area);
      c.shape = std::sqrt(std::max(0.0, 1 - c.x * c.x - c.y * c.y));
      grid->shape_integral += c.area * c.shape;
      grid->cells.push_back(c);
    }
  }
  for (GridCell& c : grid->cells) {
    c.load = c.area * c.shape / grid->shape_integral;
    const auto same = std::find_if(grid->shapes.begin(), grid->shapes.end(), [&](double v) { return same_bits(v, c.shape); });
    c.shape_index = static_cast<int>(same - grid->shapes.begin());
    if (same == grid->shapes.end()) grid->shapes.push_back(c.shape);
  }
  return grid;
}

// Grids are built once per (grid_x, grid_y) and thread; a call allocates nothing after that.
const TractionGrid& traction_grid(int gx, int gy) {
  thread_local std::vector<std::unique_ptr<TractionGrid>> cache;
  thread_local const TractionGrid* last = nullptr;
  if (last != nullptr && last->gx == gx && last->gy == gy) return *last;
  for (const auto& g : cache)
    if (g->gx == gx && g->gy == gy) return *(last = g.get());
  cache.push_back(build_grid(gx, gy));
  return *(last = cache.back().get());
}

// tanh(x) / x, finite and smooth through x = 0 (even in x), to about an ulp (as std::tanh(x) / x)
// at a third of its cost: for |x| <= 1 the (8, 8) Pade approximant, the 8th convergent of Lambert's
// continued fraction tanh x = x / (1 + x^2 / (3 + x^2 / (5 + ...))) (truncation < 3e-17 at |x| = 1,
// positive coefficients: no cancellation), above it one exponential, tanh = 1 - 2 / (e^(2|x|) + 1)
// (no cancellation where tanh > 0.76), and 1 / |x| where tanh rounds to 1 (|x| > 19.06).
inline double tanh_over_x(double x) {
  const double y = x * x;
  if (y <= 1) {
    const double p = (((y + 990) * y + 135135) * y + 4729725) * y + 34459425;
    const double q = (((45 * y + 13860) * y + 945945) * y + 16216200) * y + 34459425;
    return p / q;
  }
  const double a = std::abs(x);
  if (a > 19.5) return 1 / a;
  return (1 - 2 / (std::exp(2 * a) + 1)) / a;
}

// Hamrock & Brewe (1983) closed form for the ellipticity, k = a/b with a transverse to rolling
// (< 1 when the ellipse is longer in the rolling direction); used only inside the EHL fits, which
// are themselves fits of about this accuracy.
double hamrock_brewe_ellipticity(double rx, double ry) { return 1.0339 * std::pow(ry / rx, 0.636); }

}  // namespace

// ---- Hertz ---------------------------------------------------------------------------------------

HertzPointContact hertz_point_contact(double kx, double ky, double reduced_modulus) {
  if (!(kx + ky > 0)) throw std::invalid_argument("hertz_point_contact: kx + ky must be > 0");
  if (!(kx > 0 && ky > 0))
    throw std::invalid_argument(
        "hertz_point_contact: both relative curvatures must be > 0 "
        "(a zero or negative one has no elliptical Hertz contact)");
  if (!(reduced_modulus > 0) || !std::isfinite(reduced_modulus) || !std::isfinite(kx + ky))
    throw std::invalid_argument("hertz_point_contact: reduced modulus and curvatures must be finite, E* > 0");
  const double kmin = std::min(kx, ky), kmax = std::max(kx, ky), sum = kx + ky;
  const double m = solve_eccentricity_squared((kmax - kmin) / sum, kmax / kmin);
  const double ellipticity = 1 / std::sqrt(1 - m);
  const double e = std::sqrt(m);
  const double kk = std::comp_ellint_1(e), ee = std::comp_ellint_2(e);
  HertzPointContact h;
  h.ellipticity = ellipticity;
  h.b_coefficient = std::cbrt(3 * ee / (pi * ellipticity * reduced_modulus * sum));
  h.a_coefficient = ellipticity * h.b_coefficient;
  const double approach_coefficient = 3 * kk / (2 * pi * ellipticity * h.b_coefficient * reduced_modulus);
  h.stiffness = std::pow(approach_coefficient, -1.5);
  h.a_along_x = kx < ky;
  return h;
}

HertzTable::HertzTable(const HertzPointContact& constant) { nodes_.push_back(constant); }

void HertzTable::build(const std::vector<double>& kx, const std::vector<double>& ky, double reduced_modulus) {
  const std::size_t n = kx.size();
  if (n < 1 || ky.size() != n) throw std::invalid_argument("HertzTable: needs at least one node");
  if (n > 1 && !(s_max_ > s_min_)) throw std::invalid_argument("HertzTable: needs s_max > s_min");
  nodes_.clear();
  for (std::size_t i = 0; i < n; ++i) nodes_.push_back(hertz_point_contact(kx[i], ky[i], reduced_modulus));
  d_stiffness_.assign(n, 0.0);
  d_a_.assign(n, 0.0);
  d_b_.assign(n, 0.0);
  if (n == 1) return;
  // Derivatives by finite differences of the node values: fourth order (five points, one-sided
  // at the ends) when there are five nodes or more, else second order, else the chord.
  const double h = (s_max_ - s_min_) / static_cast<double>(n - 1);
  auto derivative = [&](auto value, std::vector<double>& out) {
    auto f = [&](std::size_t i) { return value(nodes_[i]); };
    for (std::size_t i = 0; i < n; ++i) {
      double d;
      if (n >= 5) {
        if (i >= 2 && i + 2 < n)
          d = (f(i - 2) - 8 * f(i - 1) + 8 * f(i + 1) - f(i + 2)) / (12 * h);
        else if (i == 0)
          d = (-25 * f(0) + 48 * f(1) - 36 * f(2) + 16 * f(3) - 3 * f(4)) / (12 * h);
        else if (i == 1)
          d = (-3 * f(0) - 10 * f(1) + 18 * f(2) - 6 * f(3) + f(4)) / (12 * h);
        else if (i == n - 1)
          d = (25 * f(n - 1) - 48 * f(n - 2) + 36 * f(n - 3) - 16 * f(n - 4) + 3 * f(n - 5)) / (12 * h);
        else  // i == n - 2
          d = (3 * f(n - 1) + 10 * f(n - 2) - 18 * f(n - 3) + 6 * f(n - 4) - f(n - 5)) / (12 * h);
      } else if (n >= 3) {
        if (i == 0)
          d = (-3 * f(0) + 4 * f(1) - f(2)) / (2 * h);
        else if (i == n - 1)
          d = (3 * f(n - 1) - 4 * f(n - 2) + f(n - 3)) / (2 * h);
        else
          d = (f(i + 1) - f(i - 1)) / (2 * h);
      } else {
        d = (f(1) - f(0)) / h;
      }
      out[i] = d;
    }
  };
  derivative([](const HertzPointContact& c) { return c.stiffness; }, d_stiffness_);
  derivative([](const HertzPointContact& c) { return c.a_coefficient; }, d_a_);
  derivative([](const HertzPointContact& c) { return c.b_coefficient; }, d_b_);
}

HertzPointContact HertzTable::at(double s) const {
  if (nodes_.empty()) return {};
  if (std::isnan(s)) {  // propagate, so the segment's validity check sees it
    HertzPointContact bad = nodes_.front();
    bad.stiffness = bad.a_coefficient = bad.b_coefficient = bad.ellipticity =
        std::numeric_limits<double>::quiet_NaN();
    return bad;
  }
  const std::size_t n = nodes_.size();
  if (n == 1) return nodes_.front();
  s = std::clamp(s, s_min_, s_max_);
  const double h = (s_max_ - s_min_) / static_cast<double>(n - 1);
  const double u = (s - s_min_) / h;
  const std::size_t i = std::min(static_cast<std::size_t>(u), n - 2);
  const double t = u - static_cast<double>(i);
  const double t2 = t * t, t3 = t2 * t;
  const double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + t, h01 = -2 * t3 + 3 * t2, h11 = t3 - t2;
  auto hermite = [&](double f0, double f1, double d0, double d1) {
    return h00 * f0 + h10 * h * d0 + h01 * f1 + h11 * h * d1;
  };
  const HertzPointContact &c0 = nodes_[i], &c1 = nodes_[i + 1];
  HertzPointContact out;
  out.stiffness = hermite(c0.stiffness, c1.stiffness, d_stiffness_[i], d_stiffness_[i + 1]);
  out.a_coefficient = hermite(c0.a_coefficient, c1.a_coefficient, d_a_[i], d_a_[i + 1]);
  out.b_coefficient = hermite(c0.b_coefficient, c1.b_coefficient, d_b_[i], d_b_[i + 1]);
  out.ellipticity = out.a_coefficient / out.b_coefficient;
  out.a_along_x = (t < 0.5 ? c0 : c1).a_along_x;
  return out;
}

// ---- EHL film and rolling resistance -------------------------------------------------------------
// Hamrock & Dowson (1977) central and minimum film fits for fully flooded isothermal point contacts;
// Houpert's hydrodynamic rolling-resistance fit in the form quoted by Harris & Kotzalas, with the
// E' Rx^2 scale (see the header).

namespace {

/// The factors of the EHL fits that depend on the material parameter G alone or on the curvature
/// radii alone, kept for the last arguments seen on this thread: G is a constant of a lubricant and
/// a pair of materials, and a ball-groove contact's Rx changes only with its contact angle (not in
/// a Jacobian's velocity columns, nor between the film and the rolling resistance of one
/// evaluation). A hit returns the bits a fresh evaluation gives (the same calls on the same
/// arguments). The rolling resistance's factors are made when it first asks for them (a contact
/// without rolling resistance never does).
struct EhlFactors {
  double g = std::numeric_limits<double>::quiet_NaN(), g_central = 0, g_minimum = 0, g_rolling = 0;
  double rx = std::numeric_limits<double>::quiet_NaN(), ry = rx, k = 0, central_shape = 0, minimum_shape = 0,
         k_rolling = 0;
  bool has_g_rolling = false, has_k_rolling = false;
};

EhlFactors& ehl_factors(double g, double rx, double ry) {
  thread_local EhlFactors f;
  if (!same_bits(g, f.g)) {
    f.g = g;
    f.g_central = std::pow(g, 0.53), f.g_minimum = std::pow(g, 0.49), f.has_g_rolling = false;
  }
  if (!same_bits(rx, f.rx) || !same_bits(ry, f.ry)) {
    f.rx = rx, f.ry = ry;
    f.k = hamrock_brewe_ellipticity(rx, ry);
    f.central_shape = 1 - 0.61 * std::exp(-0.73 * f.k), f.minimum_shape = 1 - std::exp(-0.68 * f.k);
    f.has_k_rolling = false;
  }
  return f;
}

}  // namespace

FilmThickness hamrock_dowson_film(double entrainment_speed, double load, double rx, double ry,
                                  double reduced_modulus, const PointLubricant& lubricant) {
  FilmThickness film;
  if (!(entrainment_speed > 0) || !(load > 0) || !(lubricant.viscosity > 0)) return film;
  const double e_prime = 2 * reduced_modulus;
  const double u = lubricant.viscosity * entrainment_speed / (e_prime * rx);
  const double g = lubricant.pressure_viscosity * e_prime;
  const double w = load / (e_prime * rx * rx);
  const EhlFactors& f = ehl_factors(g, rx, ry);
  // u^a w^b as exp(a ln u + b ln w) (about 1e-15 relative: the rounding of a ln u, |ln u| ~ 25).
  const double log_u = std::log(u), log_w = std::log(w);
  film.central = 2.69 * std::exp(0.67 * log_u - 0.067 * log_w) * f.g_central * f.central_shape * rx;
  film.minimum = 3.63 * std::exp(0.68 * log_u - 0.073 * log_w) * f.g_minimum * f.minimum_shape * rx;
  return film;
}

namespace {
/// One film starved: H ((m - 1)/(m* - 1))^exponent below m* = 1 + c ((Rx/b)^2 H)^power.
double starved(double film, double rx, double semi_width, double m, double c, double power, double exponent) {
  if (!(film > 0)) return film;
  const double critical = 1 + c * std::pow(rx * film / (semi_width * semi_width), power);  // (Rx/b)^2 h/Rx
  if (m >= critical) return film;
  return m > 1 ? film * std::pow((m - 1) / (critical - 1), exponent) : 0.0;
}
}  // namespace

FilmThickness starved_film(const FilmThickness& flooded, double rx, double semi_width, double inlet_meniscus) {
  if (!(inlet_meniscus > 0) || !(semi_width > 0) || !(rx > 0)) return flooded;
  return {starved(flooded.central, rx, semi_width, inlet_meniscus, 3.06, 0.58, 0.29),
          starved(flooded.minimum, rx, semi_width, inlet_meniscus, 3.34, 0.56, 0.25)};
}

double ehl_rolling_resistance(double entrainment_speed, double load, double rx, double ry,
                              double reduced_modulus, const PointLubricant& lubricant) {
  if (!(entrainment_speed > 0) || !(load > 0) || !(lubricant.viscosity > 0) ||
      !(lubricant.pressure_viscosity > 0))
    return 0;
  const double e_prime = 2 * reduced_modulus;
  const double u = lubricant.viscosity * entrainment_speed / (e_prime * rx);
  const double g = lubricant.pressure_viscosity * e_prime;
  const double w = load / (e_prime * rx * rx);
  EhlFactors& f = ehl_factors(g, rx, ry);
  if (!f.has_g_rolling) f.g_rolling = std::pow(g, 0.022), f.has_g_rolling = true;
  if (!f.has_k_rolling) f.k_rolling = std::pow(f.k, 0.348), f.has_k_rolling = true;
  return 2.86 * e_prime * rx * rx * f.k_rolling * f.g_rolling * std::exp(0.66 * std::log(u) + 0.47 * std::log(w));
}

// ---- traction ------------------------------------------------------------------------------------

double film_weight(double film_thickness, const PointLubricant& lubricant) {
  if (!(film_thickness > 0)) return 0.0;
  if (!(film_thickness < lubricant.boundary_film)) return 1.0;
  const double x = film_thickness / lubricant.boundary_film;
  return x * x * (3 - 2 * x);
}

int traction_block_count(const PointTraction& traction) {
  if (traction.grid_x < 1 || traction.grid_y < 1) return 1;
  const auto cells = traction_grid(traction.grid_x, traction.grid_y).cells.size();
  return static_cast<int>(std::clamp<std::size_t>(cells / traction_block_cells, 1, max_traction_blocks));
}

TractionResult integrate_traction_block(const PointTraction& traction, const PointLubricant& lubricant,
                                        double normal_force, double ax, double ay, double film_thickness,
                                        const ContactSliding& sliding, int block) {
  TractionResult out;
  if (traction.model == TractionModel::none || !(normal_force > 0) || !(ax > 0) || !(ay > 0)) return out;
  if (traction.grid_x < 1 || traction.grid_y < 1)
    throw std::invalid_argument("integrate_traction: grid_x and grid_y must be >= 1");
  const bool limiting =
      traction.model == TractionModel::limiting_shear && film_thickness > 0 && lubricant.viscosity > 0;
  // Below the boundary film the film's shear (weight w) and the curve (1 - w) share the traction.
  const double film_share = limiting ? film_weight(film_thickness, lubricant) : 0.0;
  const bool blended = limiting && film_share < 1;
  if (!limiting && traction.friction_coefficient == 0) return out;

  const TractionGrid& grid = traction_grid(traction.grid_x, traction.grid_y);
  const auto blocks = static_cast<std::size_t>(traction_block_count(traction));
  const auto b = static_cast<std::size_t>(block);
  if (block < 0 || b >= blocks) throw std::invalid_argument("integrate_traction_block: no such block");
  // Block b: cells [n b / blocks, n (b + 1) / blocks) in grid order (rows along x).
  const std::size_t first = grid.cells.size() * b / blocks, last = grid.cells.size() * (b + 1) / blocks;
  const double area_scale = ax * ay;                                                // unit disk -> ellipse
  const double pressure_scale = normal_force / (area_scale * grid.shape_integral);  // ~ p_max
  const double mu_over_scale = traction.friction_coefficient / traction.slip_velocity_scale;
  const double inverse_scale = 1 / traction.slip_velocity_scale;
  const double inverse_h = limiting ? 1 / film_thickness : 0;
  // Where the exponent reaches the cap (most of a loaded contact) the viscosity is one number,
  // evaluated once per block: std::min(exponent, cap) is the cap exactly when cap < exponent.
  const double cap = lubricant.viscosity_exponent_cap;
  double capped_viscosity = std::numeric_limits<double>::quiet_NaN();
  bool has_capped = false;
  auto viscosity_at = [&](double p) {
    const double exponent = lubricant.roelands_index > 0
                                ? roelands_exponent(lubricant.viscosity, lubricant.roelands_index, p)
                                : lubricant.pressure_viscosity * p;
    if (!(cap < exponent)) return lubricant.viscosity * std::exp(std::min(exponent, cap));
    if (!has_capped) capped_viscosity = lubricant.viscosity * std::exp(cap), has_capped = true;
    return capped_viscosity;
  };
  // Per distinct shape (the first max_distinct_shapes, evaluated up front; a cell beyond them
  // evaluates its own): the film's shear rate factor eta / h and the tanh's argument per unit
  // sliding speed eta / (h tau_L), so that a cell takes g = area eta / h tanh_over_x(s eta / (h tau_L)).
  struct ShapeShear {
    double rate, slope;
  };
  auto shape_shear = [&](double shape) {
    const double p = pressure_scale * shape;
    const double tau_limit = lubricant.limiting_shear_coefficient * p;
    if (!(tau_limit > 0)) return ShapeShear{0, 0};
    const double rate = viscosity_at(p) * inverse_h;
    return ShapeShear{rate, rate / tau_limit};
  };
  std::array<ShapeShear, max_distinct_shapes> shear;  // NOLINT: the first `shapes` are set below
  const std::size_t shapes = limiting ? std::min(grid.shapes.size(), max_distinct_shapes) : 0;
  for (std::size_t k = 0; k < shapes; ++k) shear[k] = shape_shear(grid.shapes[k]);
  const double curve_scale = mu_over_scale * normal_force * (1 - film_share);
  double fx = 0, fy = 0, mz = 0, power = 0;
  for (std::size_t i = first; i < last; ++i) {
    const GridCell& c = grid.cells[i];
    const double x = ax * c.x, y = ay * c.y;
    const double sx = sliding.slide_x - sliding.spin * y, sy = sliding.slide_y + sliding.spin * x;
    const double s2 = sx * sx + sy * sy, s = std::sqrt(s2);
    // g = |tau| area / s: the shear force of the cell is -g (sx, sy), finite at s = 0.
    double g;
    if (limiting) {
      const auto k = static_cast<std::size_t>(c.shape_index);
      const ShapeShear sh = k < shapes ? shear[k] : shape_shear(c.shape);
      g = sh.rate * (c.area * area_scale) * tanh_over_x(sh.slope * s);
      if (blended) g = film_share * g + curve_scale * c.load * tanh_over_x(s * inverse_scale);
    } else {
      g = mu_over_scale * normal_force * c.load * tanh_over_x(s * inverse_scale);
    }
    const double cx = -g * sx, cy = -g * sy;
    fx += cx;
    fy += cy;
    mz += x * cy - y * cx;
    power += g * s2;
  }
  out.force_x = fx;
  out.force_y = fy;
  out.spin_moment = mz;
  out.power_loss = power;
  return out;
}

TractionResult sum_traction_blocks(std::span<const TractionResult> blocks) {
  if (blocks.empty()) return {};
  TractionResult sum = blocks[0];
  for (std::size_t b = 1; b < blocks.size(); ++b) {
    sum.force_x += blocks[b].force_x;
    sum.force_y += blocks[b].force_y;
    sum.spin_moment += blocks[b].spin_moment;
    sum.power_loss += blocks[b].power_loss;
  }
  return sum;
}

TractionResult integrate_traction(const PointTraction& traction, const PointLubricant& lubricant,
                                  double normal_force, double ax, double ay, double film_thickness,
                                  const ContactSliding& sliding) {
  const int blocks = traction_block_count(traction);
  if (blocks == 1)
    return integrate_traction_block(traction, lubricant, normal_force, ax, ay, film_thickness, sliding, 0);
  std::array<TractionResult, max_traction_blocks> partial{};
  const int n = std::min(blocks, max_traction_blocks);
  for (int b = 0; b < n; ++b)
    partial[static_cast<std::size_t>(b)] =
        integrate_traction_block(traction, lubricant, normal_force, ax, ay, film_thickness, sliding, b);
  return sum_traction_blocks(std::span<const TractionResult>(partial.data(), static_cast<std::size_t>(n)));
}

}  // namespace raceway::contact
