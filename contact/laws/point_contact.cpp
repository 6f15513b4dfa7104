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

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cmath>
#include <limits>
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
/// arguments). The minimum film's and the rolling resistance's factors are made when they are
/// first asked for (a ball-groove contact takes the central film alone; one without rolling
/// resistance never asks for its factors).
struct EhlFactors {
  double g = std::numeric_limits<double>::quiet_NaN(), g_central = 0, g_minimum = 0, g_rolling = 0;
  double rx = std::numeric_limits<double>::quiet_NaN(), ry = rx, k = 0, central_shape = 0, minimum_shape = 0,
         k_rolling = 0;
  bool has_g_minimum = false, has_g_rolling = false, has_k_minimum = false, has_k_rolling = false;
};

EhlFactors& ehl_factors(double g, double rx, double ry) {
  thread_local EhlFactors f;
  if (!same_bits(g, f.g)) {
    f.g = g;
    f.g_central = std::pow(g, 0.53), f.has_g_minimum = false, f.has_g_rolling = false;
  }
  if (!same_bits(rx, f.rx) || !same_bits(ry, f.ry)) {
    f.rx = rx, f.ry = ry;
    f.k = hamrock_brewe_ellipticity(rx, ry);
    f.central_shape = 1 - 0.61 * std::exp(-0.73 * f.k);
    f.has_k_minimum = false, f.has_k_rolling = false;
  }
  return f;
}

/// ln u and ln w of the EHL fits' dimensionless speed and load, kept for the last (u, w) seen on
/// this thread: a contact's film and its rolling resistance are evaluated from the same arguments
/// (the same u and w, bit for bit), so the second takes the first's logarithms.
struct EhlLogs {
  double u = std::numeric_limits<double>::quiet_NaN(), w = u, log_u = 0, log_w = 0;
};
const EhlLogs& ehl_logs(double u, double w) {
  thread_local EhlLogs l;
  if (!same_bits(u, l.u) || !same_bits(w, l.w)) l.u = u, l.w = w, l.log_u = std::log(u), l.log_w = std::log(w);
  return l;
}

}  // namespace

namespace {
/// The fits' films; the minimum film only when `minimum` (its two factors and exponential cost a
/// third of the call, and a ball-groove contact does not read it).
FilmThickness hamrock_dowson(double entrainment_speed, double load, double rx, double ry, double reduced_modulus,
                             const PointLubricant& lubricant, bool minimum) {
  FilmThickness film;
  if (!(entrainment_speed > 0) || !(load > 0) || !(lubricant.viscosity > 0)) return film;
  const double e_prime = 2 * reduced_modulus;
  const double u = lubricant.viscosity * entrainment_speed / (e_prime * rx);
  const double g = lubricant.pressure_viscosity * e_prime;
  const double w = load / (e_prime * rx * rx);
  EhlFactors& f = ehl_factors(g, rx, ry);
  // u^a w^b as exp(a ln u + b ln w) (about 1e-15 relative: the rounding of a ln u, |ln u| ~ 25).
  const EhlLogs& logs = ehl_logs(u, w);
  const double log_u = logs.log_u, log_w = logs.log_w;
  film.central = 2.69 * std::exp(0.67 * log_u - 0.067 * log_w) * f.g_central * f.central_shape * rx;
  if (!minimum) return film;
  if (!f.has_g_minimum) f.g_minimum = std::pow(g, 0.49), f.has_g_minimum = true;
  if (!f.has_k_minimum) f.minimum_shape = 1 - std::exp(-0.68 * f.k), f.has_k_minimum = true;
  film.minimum = 3.63 * std::exp(0.68 * log_u - 0.073 * log_w) * f.g_minimum * f.minimum_shape * rx;
  return film;
}
}  // namespace

FilmThickness hamrock_dowson_film(double entrainment_speed, double load, double rx, double ry,
                                  double reduced_modulus, const PointLubricant& lubricant) {
  return hamrock_dowson(entrainment_speed, load, rx, ry, reduced_modulus, lubricant, true);
}

double hamrock_dowson_central_film(double entrainment_speed, double load, double rx, double ry,
                                   double reduced_modulus, const PointLubricant& lubricant) {
  return hamrock_dowson(entrainment_speed, load, rx, ry, reduced_modulus, lubricant, false).central;
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
  const EhlLogs& logs = ehl_logs(u, w);
  return 2.86 * e_prime * rx * rx * f.k_rolling * f.g_rolling * std::exp(0.66 * logs.log_u + 0.47 * logs.log_w);
}

}  // namespace raceway::contact
