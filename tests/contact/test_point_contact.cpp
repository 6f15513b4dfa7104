// Point-contact laws on their own (contact/laws/point_contact.hpp): the exact Hertz solution against
// independent formulations and closed forms, the Hertz table, the Hamrock-Dowson film and EHL
// rolling resistance (traction over the ellipse: test_point_traction.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <thread>
#include <vector>

#include "contact/laws/line_contact.hpp"
#include "contact/laws/point_contact.hpp"

namespace raceway::contact {
namespace {

constexpr double pi = std::numbers::pi;

// Steel on steel, E = 208 GPa, nu = 0.3.
double steel_e_star() { return reduced_modulus(208e9, 0.3, 208e9, 0.3); }

// The curvature-difference relation, evaluated directly from k (Harris & Kotzalas, ch. 6).
double curvature_difference_of(double k) {
  const double e = std::sqrt(1 - 1 / (k * k));
  const double kk = std::comp_ellint_1(e), ee = std::comp_ellint_2(e);
  return ((k * k + 1) * ee - 2 * kk) / ((k * k - 1) * ee);
}

// An independent route to the contact (Johnson, Contact Mechanics, ch. 3 and sec. 4.2): the
// ratio B/A = ((1/(1-e^2)) E - K) / (K - E) solved by bisection on the eccentricity e, then a from
// the A (smaller-curvature) equation alone, a^3 = 3 P (K - E) / (pi E* e^2 kmin), b = a sqrt(1-e^2)
// and delta = 3 P K / (2 pi a E*). The implementation uses the (A + B) equation and Newton.
struct JohnsonContact {
  double a, b, delta;
};
JohnsonContact johnson_contact(double kmin, double kmax, double e_star, double load) {
  const double target = kmax / kmin;
  auto ratio = [](double e) {
    const double kk = std::comp_ellint_1(e), ee = std::comp_ellint_2(e);
    return (ee / (1 - e * e) - kk) / (kk - ee);
  };
  double lo = 1e-6, hi = 1 - 1e-15;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (ratio(mid) < target ? lo : hi) = mid;
  }
  const double e = 0.5 * (lo + hi);
  const double kk = std::comp_ellint_1(e), ee = std::comp_ellint_2(e);
  JohnsonContact c{};
  c.a = std::cbrt(3 * load * (kk - ee) / (pi * e_star * e * e * kmin));
  c.b = c.a * std::sqrt(1 - e * e);
  c.delta = 3 * load * kk / (2 * pi * c.a * e_star);
  return c;
}

// Deep-groove ball bearing 209 (Harris & Kotzalas, Essential Concepts of Bearing Technology, the
// running example of ch. 2 and 6): ball D = 12.7 mm, pitch diameter 65 mm, groove conformity 0.52,
// contact angle 0. Relative curvatures of the ball-race contact at s = cos(contact angle):
// rolling direction 2/D +- 2 s / (d_m -+ D s) (inner: +, outer: -), transverse 2/D - 1/(f D).
constexpr double ball_d = 12.7e-3, pitch_d = 65e-3, conformity = 0.52;
void inner_race_curvatures(double s, double& kx, double& ky) {
  kx = 2 / ball_d + 2 * s / (pitch_d - ball_d * s);
  ky = 2 / ball_d - 1 / (conformity * ball_d);
}
void outer_race_curvatures(double s, double& kx, double& ky) {
  kx = 2 / ball_d - 2 * s / (pitch_d + ball_d * s);
  ky = 2 / ball_d - 1 / (conformity * ball_d);
}

// Hamrock & Brewe (1983) closed forms, with alpha_r = Ry / Rx >= 1 (Hamrock, Fundamentals of Fluid
// Film Lubrication, ch. 4): k = 1.0339 alpha_r^0.636, E = 1.0003 + 0.5968 / alpha_r,
// K = 1.5277 + 0.6023 ln(alpha_r); delta = K [9 / (2 E R) (Q / (pi k E'))^2]^(1/3), E' = 2 E*.
struct HamrockBrewe {
  double ellipticity, stiffness;
};
HamrockBrewe hamrock_brewe(double kmin, double kmax, double e_star) {
  const double alpha_r = kmax / kmin, r = 1 / (kmin + kmax);
  const double k = 1.0339 * std::pow(alpha_r, 0.636);
  const double ee = 1.0003 + 0.5968 / alpha_r, kk = 1.5277 + 0.6023 * std::log(alpha_r);
  const double delta_unit_load = kk * std::cbrt(9 / (2 * ee * r) * std::pow(1 / (pi * k * 2 * e_star), 2));
  return {k, std::pow(delta_unit_load, -1.5)};
}

// ---- Hertz ---------------------------------------------------------------------------------------

TEST(HertzPointContact, BallOnFlatIsCircular) {
  const double e_star = steel_e_star(), r = 10e-3;
  const HertzPointContact h = hertz_point_contact(1 / r, 1 / r, e_star);
  EXPECT_EQ(h.ellipticity, 1.0);
  const double k_exact = 4.0 / 3.0 * e_star * std::sqrt(r);
  EXPECT_NEAR(h.stiffness, k_exact, 1e-12 * k_exact);
  // a = b = (3 R Q / (4 E*))^(1/3)
  const double c = std::cbrt(3 * r / (4 * e_star));
  EXPECT_NEAR(h.a_coefficient, c, 1e-12 * c);
  EXPECT_NEAR(h.b_coefficient, c, 1e-12 * c);
  EXPECT_FALSE(h.a_along_x);
  // Two equal balls: R = r/2.
  const HertzPointContact two = hertz_point_contact(2 / r, 2 / r, e_star);
  EXPECT_NEAR(two.stiffness, 4.0 / 3.0 * e_star * std::sqrt(r / 2), 1e-12 * k_exact);
}

TEST(HertzPointContact, SolvesTheEllipticIntegralRelation) {
  const double e_star = steel_e_star();
  for (const double ratio :
       {1.0001, 1.001, 1.01, 1.1, 1.2, 1.235, 1.25, 1.5, 2.0, 3.0, 5.0, 10.0, 21.75, 32.31, 50.0, 100.0}) {
    for (const bool x_major : {true, false}) {
      const double kx = x_major ? 100.0 : 100.0 * ratio, ky = x_major ? 100.0 * ratio : 100.0;
      const HertzPointContact h = hertz_point_contact(kx, ky, e_star);
      const double target = (ratio - 1) / (ratio + 1);
      EXPECT_NEAR(curvature_difference_of(h.ellipticity), target, 1e-10) << "ratio " << ratio;
      EXPECT_GT(h.ellipticity, 1.0);
      EXPECT_EQ(h.a_along_x, x_major) << "the longer axis lies along the smaller curvature";
      EXPECT_NEAR(h.a_coefficient / h.b_coefficient, h.ellipticity, 1e-13 * h.ellipticity);
    }
    // Swapping x and y changes nothing but the orientation.
    const HertzPointContact p = hertz_point_contact(100.0, 100.0 * ratio, e_star);
    const HertzPointContact q = hertz_point_contact(100.0 * ratio, 100.0, e_star);
    EXPECT_EQ(p.stiffness, q.stiffness);
    EXPECT_EQ(p.ellipticity, q.ellipticity);
  }
}

TEST(HertzPointContact, MatchesJohnsonsIndependentFormulation) {
  const double e_star = steel_e_star(), load = 1000;
  for (const double ratio : {1.05, 1.3, 2.0, 4.0, 10.0, 32.31, 100.0}) {
    const double kmin = 80.0, kmax = 80.0 * ratio;
    const HertzPointContact h = hertz_point_contact(kmin, kmax, e_star);
    const JohnsonContact j = johnson_contact(kmin, kmax, e_star, load);
    const double q13 = std::cbrt(load);
    // c = sqrt(a b), the equivalent contact radius, and the approach.
    const double c_impl = std::sqrt(h.a_coefficient * h.b_coefficient) * q13;
    EXPECT_NEAR(c_impl, std::sqrt(j.a * j.b), 1e-9 * c_impl) << "ratio " << ratio;
    EXPECT_NEAR(h.a_coefficient * q13, j.a, 1e-9 * j.a);
    const double delta_impl = std::pow(load / h.stiffness, 2.0 / 3.0);
    EXPECT_NEAR(delta_impl, j.delta, 1e-9 * j.delta) << "ratio " << ratio;
  }
}

// The circular limit is approached smoothly: k - 1 ~ 2 eps / 3 and K changes by ~eps/4 for
// ky = kx (1 + eps); no jump where the solver switches from series to direct evaluation.
// The classical table of Hertz's coefficients m, n (Timoshenko & Goodier, Theory of Elasticity,
// sec. 140: a = m [3 pi P (k1 + k2) / (4 (A + B))]^(1/3), b = n [...]^(1/3), k1 + k2 = 1/(pi E*),
// cos(theta) = (B - A) / (A + B)), quoted to three digits; values as recalled from the book (the
// stored corpora do not hold it), which the exact solution reproduces to the table's rounding.
TEST(HertzPointContact, ReproducesTheClassicalCoefficientTable) {
  struct Row {
    double theta_deg, m, n;
  };
  const Row rows[] = {{30, 2.731, 0.493}, {35, 2.397, 0.530}, {40, 2.136, 0.567}, {45, 1.926, 0.604},
                      {50, 1.754, 0.641}, {55, 1.611, 0.678}, {60, 1.486, 0.717}, {65, 1.378, 0.759},
                      {70, 1.284, 0.802}, {75, 1.202, 0.846}, {80, 1.128, 0.893}, {85, 1.061, 0.944},
                      {90, 1.000, 1.000}};
  const double e_star = steel_e_star();
  for (const Row& row : rows) {
    const double c = std::cos(row.theta_deg * pi / 180);
    const double big_a = 1.0, big_b = (1 + c) / (1 - c);  // A, B = half the relative curvatures
    const HertzPointContact h = hertz_point_contact(2 * big_a, 2 * big_b, e_star);
    const double scale = std::cbrt(3 * pi / (4 * pi * e_star * (big_a + big_b)));
    EXPECT_NEAR(h.a_coefficient / scale, row.m, 2.5e-3) << row.theta_deg;
    EXPECT_NEAR(h.b_coefficient / scale, row.n, 2.5e-3) << row.theta_deg;
  }
}

TEST(HertzPointContact, SmoothThroughTheCircleAndTheSeriesSwitch) {
  const double e_star = steel_e_star();
  const HertzPointContact circle = hertz_point_contact(100, 100, e_star);
  for (const double eps : {1e-14, 1e-11, 1e-8, 1e-6}) {
    const HertzPointContact h = hertz_point_contact(100, 100 * (1 + eps), e_star);
    EXPECT_NEAR(h.ellipticity - 1, 2 * eps / 3, 1e-3 * eps + 1e-15) << eps;
    EXPECT_NEAR(h.stiffness / circle.stiffness - 1, -eps / 4, 1e-3 * eps + 1e-15) << eps;
  }
  // Across F(rho) ~ 0.105 (e^2 = 0.25, ratio ~ 1.235) k stays monotone and its third differences
  // stay at round-off: no jump where the solver switches from series to direct evaluation.
  std::vector<double> k;
  for (int i = 0; i <= 400; ++i)
    k.push_back(hertz_point_contact(100, 100 * (1.20 + 1e-4 * i), e_star).ellipticity);
  for (std::size_t i = 1; i + 2 < k.size(); ++i) {
    EXPECT_GT(k[i + 1], k[i]);
    const double third = k[i + 2] - 3 * k[i + 1] + 3 * k[i] - k[i - 1];
    EXPECT_LT(std::abs(third), 3e-13) << "at ratio " << 1.20 + 1e-4 * static_cast<double>(i);
  }
}

TEST(HertzPointContact, RejectsDegenerateInput) {
  EXPECT_THROW(hertz_point_contact(0, 0, 1e11), std::invalid_argument);
  EXPECT_THROW(hertz_point_contact(-100, 50, 1e11), std::invalid_argument);
  EXPECT_THROW(hertz_point_contact(100, 0, 1e11), std::invalid_argument);  // a line contact
  EXPECT_THROW(hertz_point_contact(100, 100, 0), std::invalid_argument);
  EXPECT_THROW(hertz_point_contact(100, std::nan(""), 1e11), std::invalid_argument);
}

// Harris & Kotzalas' 209 bearing. Their worked example gives, for the inner race, curvature sum
// 0.2018 /mm and F(rho) = 0.9399, for the outer race 0.1378 /mm and 0.9121 (values recalled from
// the book; the stored search corpora did not hold it, so these are cross-checked here only through
// the geometry). Hamrock & Brewe's closed forms (k 1.5 % high here, 6 % at Ry/Rx = 100) are 1.6 %
// stiff at the inner race, while the table is within 1e-4 of exact: the segments use the table.
TEST(HertzPointContact, Bearing209AgainstClosedForms) {
  const double e_star = steel_e_star();
  double kx = 0, ky = 0;
  inner_race_curvatures(1.0, kx, ky);
  EXPECT_NEAR((kx + ky) * 1e-3, 0.2018, 1e-4);
  EXPECT_NEAR((kx - ky) / (kx + ky), 0.9399, 2e-4);
  const HertzPointContact inner = hertz_point_contact(kx, ky, e_star);
  EXPECT_FALSE(inner.a_along_x) << "the long axis is transverse to rolling";
  EXPECT_NEAR(inner.ellipticity, 9.2849, 1e-3);  // this implementation, for the record
  const HamrockBrewe hb_inner = hamrock_brewe(ky, kx, e_star);
  EXPECT_NEAR(hb_inner.ellipticity / inner.ellipticity, 1.0, 0.03);
  const double hb_error = hb_inner.stiffness / inner.stiffness - 1;
  EXPECT_GT(hb_error, 0.01) << "Hamrock-Brewe stiffness error " << hb_error;
  EXPECT_LT(hb_error, 0.03);
  // Brewe & Hamrock's earlier k = alpha_r^(2/pi) and Greenwood's asymptote (B/A)^(2/3) bracket it.
  EXPECT_LT(std::pow(kx / ky, 2 / pi), inner.ellipticity);
  EXPECT_GT(std::pow(kx / ky, 2.0 / 3.0), inner.ellipticity);

  outer_race_curvatures(1.0, kx, ky);
  EXPECT_NEAR((kx + ky) * 1e-3, 0.1378, 1e-4);
  EXPECT_NEAR((kx - ky) / (kx + ky), 0.9121, 2e-4);
  const HertzPointContact outer = hertz_point_contact(kx, ky, e_star);
  const HamrockBrewe hb_outer = hamrock_brewe(ky, kx, e_star);
  EXPECT_NEAR(hb_outer.ellipticity / outer.ellipticity, 1.0, 0.03);
  EXPECT_GT(std::abs(hb_outer.stiffness / outer.stiffness - 1), 0.004);

  // The table over the contact angle (s = cos alpha in [0.5, 1]) at the 209's s = 1.
  const HertzTable table(inner_race_curvatures, 0.5, 1.0, 33, e_star);
  EXPECT_NEAR(table.at(1.0).stiffness / inner.stiffness, 1.0, 1e-12);  // a node
  const double s = 0.9137;                                             // between nodes
  inner_race_curvatures(s, kx, ky);
  EXPECT_NEAR(table.at(s).stiffness / hertz_point_contact(kx, ky, e_star).stiffness, 1.0, 1e-4);
}

// ---- Hertz table ---------------------------------------------------------------------------------

TEST(HertzTable, InterpolationErrorOverContactAngle) {
  const double e_star = steel_e_star();
  for (const bool inner : {true, false}) {
    auto curvatures = inner ? inner_race_curvatures : outer_race_curvatures;
    const HertzTable table(curvatures, 0.5, 1.0, 33, e_star);
    EXPECT_EQ(table.s_min(), 0.5);
    EXPECT_EQ(table.s_max(), 1.0);
    double worst_k = 0, worst_a = 0, worst_b = 0;
    for (int i = 0; i <= 2000; ++i) {
      const double s = 0.5 + 0.5 * i / 2000.0;
      double kx = 0, ky = 0;
      curvatures(s, kx, ky);
      const HertzPointContact exact = hertz_point_contact(kx, ky, e_star);
      const HertzPointContact t = table.at(s);
      worst_k = std::max(worst_k, std::abs(t.stiffness / exact.stiffness - 1));
      worst_a = std::max(worst_a, std::abs(t.a_coefficient / exact.a_coefficient - 1));
      worst_b = std::max(worst_b, std::abs(t.b_coefficient / exact.b_coefficient - 1));
      EXPECT_NEAR(t.ellipticity / exact.ellipticity, 1.0, 1e-4);
      EXPECT_EQ(t.a_along_x, exact.a_along_x);
    }
    EXPECT_LT(worst_k, 1e-4) << (inner ? "inner" : "outer");
    EXPECT_LT(worst_a, 1e-4);
    EXPECT_LT(worst_b, 1e-4);
    RecordProperty(inner ? "inner_worst_stiffness_error" : "outer_worst_stiffness_error",
                   std::to_string(worst_k));
    // Clamped outside the range; NaN propagates.
    EXPECT_EQ(table.at(2.0).stiffness, table.at(1.0).stiffness);
    EXPECT_EQ(table.at(-1.0).stiffness, table.at(0.5).stiffness);
    EXPECT_TRUE(std::isnan(table.at(std::nan("")).stiffness));
  }
}

TEST(HertzTable, FewNodesAndConstantTables) {
  const double e_star = steel_e_star();
  const HertzPointContact pocket = hertz_point_contact(50, 50, e_star);
  const HertzTable constant(pocket);
  for (const double s : {-3.0, 0.0, 0.7, 12.0}) {
    EXPECT_EQ(constant.at(s).stiffness, pocket.stiffness);
    EXPECT_EQ(constant.at(s).a_coefficient, pocket.a_coefficient);
  }
  // A contact longer in the rolling direction (kx < ky) keeps a_along_x between the nodes.
  const HertzTable along_x(
      [](double s, double& kx, double& ky) {
        kx = 50 + 20 * s;
        ky = 400;
      },
      0, 1, 9, e_star);
  for (const double s : {0.0, 0.33, 0.5, 0.99}) {
    EXPECT_TRUE(along_x.at(s).a_along_x);
    EXPECT_NEAR(along_x.at(s).stiffness / hertz_point_contact(50 + 20 * s, 400, e_star).stiffness, 1, 1e-6);
  }
  // Two and three nodes still interpolate (less accurately) and hit the nodes exactly.
  for (const int points : {2, 3, 5}) {
    const HertzTable t(inner_race_curvatures, 0.5, 1.0, points, e_star);
    double kx = 0, ky = 0;
    inner_race_curvatures(0.5, kx, ky);
    EXPECT_NEAR(t.at(0.5).stiffness / hertz_point_contact(kx, ky, e_star).stiffness, 1, 1e-14);
    inner_race_curvatures(0.75, kx, ky);
    EXPECT_NEAR(t.at(0.75).stiffness / hertz_point_contact(kx, ky, e_star).stiffness, 1, 2e-2);
  }
}

// ---- film ----------------------------------------------------------------------------------------

struct FilmCase {
  double rx, ry;
  PointLubricant lubricant;
};
FilmCase inner_race_film_case() {
  double kx = 0, ky = 0;
  inner_race_curvatures(1.0, kx, ky);
  PointLubricant lub;
  lub.viscosity = 0.04;
  lub.pressure_viscosity = 2.3e-8;
  lub.limiting_shear_coefficient = 0.08;
  return {1 / kx, 1 / ky, lub};
}

TEST(HamrockDowsonFilm, Scaling) {
  const double e_star = steel_e_star();
  const FilmCase c = inner_race_film_case();
  const FilmThickness base = hamrock_dowson_film(10, 1000, c.rx, c.ry, e_star, c.lubricant);
  ASSERT_GT(base.central, 0);
  EXPECT_GT(base.central, base.minimum);
  EXPECT_LT(base.central, 1.5 * base.minimum);
  const FilmThickness fast = hamrock_dowson_film(20, 1000, c.rx, c.ry, e_star, c.lubricant);
  EXPECT_NEAR(fast.central / base.central, std::pow(2.0, 0.67), 1e-12);
  EXPECT_NEAR(fast.minimum / base.minimum, std::pow(2.0, 0.68), 1e-12);
  PointLubricant thick = c.lubricant;
  thick.viscosity *= 3;
  const FilmThickness viscous = hamrock_dowson_film(10, 1000, c.rx, c.ry, e_star, thick);
  EXPECT_NEAR(viscous.central / base.central, std::pow(3.0, 0.67), 1e-12);
  const FilmThickness loaded = hamrock_dowson_film(10, 4000, c.rx, c.ry, e_star, c.lubricant);
  EXPECT_NEAR(loaded.central / base.central, std::pow(4.0, -0.067), 1e-12);
  EXPECT_NEAR(loaded.minimum / base.minimum, std::pow(4.0, -0.073), 1e-12);
  PointLubricant stiff_oil = c.lubricant;
  stiff_oil.pressure_viscosity *= 2;
  const FilmThickness piezo = hamrock_dowson_film(10, 1000, c.rx, c.ry, e_star, stiff_oil);
  EXPECT_NEAR(piezo.central / base.central, std::pow(2.0, 0.53), 1e-12);
}

// Reference value: the 209 inner race (Rx = 5.109 mm, Ry = 165.1 mm, E = 200 GPa, nu = 0.3) with
// eta0 = 0.04 Pa s, alpha = 2.3e-8 1/Pa (Hamrock's ball-bearing example lubricant), u = 10 m/s,
// Q = 1000 N. No worked example with printed film values could be found in the stored corpora, so
// the reference is Hamrock & Dowson's dimensionless formula evaluated separately (U = 3.5621e-10,
// G = 5054.9, W = 1.7430e-4, k = 9.4286): h_c = 1.0527 um, h_min = 0.8549 um.
TEST(HamrockDowsonFilm, ReferenceValue) {
  const double e_star = reduced_modulus(200e9, 0.3, 200e9, 0.3);
  const FilmCase c = inner_race_film_case();
  const FilmThickness film = hamrock_dowson_film(10, 1000, c.rx, c.ry, e_star, c.lubricant);
  EXPECT_NEAR(film.central, 1.0527e-6, 0.01 * 1.0527e-6);
  EXPECT_NEAR(film.minimum, 0.8549e-6, 0.01 * 0.8549e-6);
}

TEST(HamrockDowsonFilm, ZeroWithoutSpeedLoadOrViscosity) {
  const double e_star = steel_e_star();
  const FilmCase c = inner_race_film_case();
  PointLubricant dry = c.lubricant;
  dry.viscosity = 0;
  for (const FilmThickness f : {hamrock_dowson_film(0, 1000, c.rx, c.ry, e_star, c.lubricant),
                                hamrock_dowson_film(-1, 1000, c.rx, c.ry, e_star, c.lubricant),
                                hamrock_dowson_film(10, 0, c.rx, c.ry, e_star, c.lubricant),
                                hamrock_dowson_film(10, 1000, c.rx, c.ry, e_star, dry)}) {
    EXPECT_EQ(f.central, 0.0);
    EXPECT_EQ(f.minimum, 0.0);
  }
}

// Starvation (Hamrock and Dowson's inlet meniscus), on the 209 reference film above with a contact
// semi-width b = 0.2 mm along rolling: H_c = 1.0527 um / 5.109 mm = 2.0605e-4, (Rx/b)^2 H_c = 0.13447,
// so the critical meniscus m* = 1 + 3.06 * 0.13447^0.58 = 1.9556 (by hand). At and beyond m* the
// flooded film; halfway (m - 1 = (m* - 1)/2) the central film times 0.5^0.29 = 0.8180; continuous at
// m*; zero at m = 1; the minimum film with its own m* and exponent 0.25.
TEST(HamrockDowsonFilm, StarvedBelowTheCriticalMeniscus) {
  const double e_star = reduced_modulus(200e9, 0.3, 200e9, 0.3);
  const FilmCase c = inner_race_film_case();
  const FilmThickness flooded = hamrock_dowson_film(10, 1000, c.rx, c.ry, e_star, c.lubricant);
  const double b = 0.2e-3;
  const double critical = 1 + 3.06 * std::pow(c.rx * flooded.central / (b * b), 0.58);
  EXPECT_NEAR(critical, 1.9556, 2e-3);
  const FilmThickness far = starved_film(flooded, c.rx, b, 10.0);
  EXPECT_EQ(far.central, flooded.central);
  EXPECT_EQ(far.minimum, flooded.minimum);
  const FilmThickness half = starved_film(flooded, c.rx, b, 1 + 0.5 * (critical - 1));
  EXPECT_NEAR(half.central / flooded.central, std::pow(0.5, 0.29), 1e-12);
  EXPECT_NEAR(half.central / flooded.central, 0.8180, 1e-4);
  const double critical_min = 1 + 3.34 * std::pow(c.rx * flooded.minimum / (b * b), 0.56);
  const FilmThickness at = starved_film(flooded, c.rx, b, 1 + 0.25 * (critical_min - 1));
  EXPECT_NEAR(at.minimum / flooded.minimum, std::pow(0.25, 0.25), 1e-12);
  const FilmThickness edge = starved_film(flooded, c.rx, b, critical * (1 - 1e-9));
  EXPECT_NEAR(edge.central / flooded.central, 1.0, 1e-8);
  const FilmThickness dry = starved_film(flooded, c.rx, b, 1.0);
  EXPECT_EQ(dry.central, 0.0);
  EXPECT_EQ(dry.minimum, 0.0);
  const FilmThickness off = starved_film(flooded, c.rx, b, 0.0);  // 0: flooded
  EXPECT_EQ(off.central, flooded.central);
}

// ---- rolling resistance --------------------------------------------------------------------------

TEST(EhlRollingResistance, PositiveScalesAndVanishesWithoutFilm) {
  const double e_star = reduced_modulus(200e9, 0.3, 200e9, 0.3);
  const FilmCase c = inner_race_film_case();
  const double f = ehl_rolling_resistance(10, 1000, c.rx, c.ry, e_star, c.lubricant);
  EXPECT_GT(f, 0);
  // A few 1e-4 of the load at 10 m/s: the order of EHL rolling friction in ball bearings.
  EXPECT_GT(f / 1000, 1e-5);
  EXPECT_LT(f / 1000, 1e-2);
  EXPECT_NEAR(f, 0.42974, 1e-3 * 0.42974);  // the formula evaluated separately
  EXPECT_NEAR(ehl_rolling_resistance(20, 1000, c.rx, c.ry, e_star, c.lubricant) / f, std::pow(2.0, 0.66),
              1e-12);
  EXPECT_NEAR(ehl_rolling_resistance(10, 3000, c.rx, c.ry, e_star, c.lubricant) / f, std::pow(3.0, 0.47),
              1e-12);
  PointLubricant thick = c.lubricant;
  thick.viscosity *= 2;
  EXPECT_NEAR(ehl_rolling_resistance(10, 1000, c.rx, c.ry, e_star, thick) / f, std::pow(2.0, 0.66), 1e-12);
  PointLubricant dry = c.lubricant;
  dry.viscosity = 0;
  EXPECT_EQ(ehl_rolling_resistance(10, 1000, c.rx, c.ry, e_star, dry), 0.0);
  EXPECT_EQ(ehl_rolling_resistance(0, 1000, c.rx, c.ry, e_star, c.lubricant), 0.0);
  EXPECT_EQ(ehl_rolling_resistance(10, 0, c.rx, c.ry, e_star, c.lubricant), 0.0);
}

// The fits keep their factors of G and of the curvature radii for the last arguments seen on the
// thread: what came before must not change a bit. A fresh thread (nothing kept) against this one
// after other lubricants, materials and radii, in both orders of film and rolling resistance.
TEST(EhlFits, SameBitsWhateverWasEvaluatedBefore) {
  const double e_star = reduced_modulus(200e9, 0.3, 200e9, 0.3);
  const FilmCase c = inner_race_film_case();
  struct Values {
    double central, minimum, rolling;
  };
  auto evaluate = [&](double rx, double ry, double e, const PointLubricant& lub) {
    const FilmThickness film = hamrock_dowson_film(7, 800, rx, ry, e, lub);
    return Values{film.central, film.minimum, ehl_rolling_resistance(7, 800, rx, ry, e, lub)};
  };
  PointLubricant other = c.lubricant;
  other.pressure_viscosity *= 1.5;
  Values fresh{}, fresh_other{};
  std::thread([&] {
    fresh = evaluate(c.rx, c.ry, e_star, c.lubricant);
  }).join();
  std::thread([&] {
    fresh_other = evaluate(1.1 * c.rx, c.ry, 0.9 * e_star, other);
  }).join();
  for (int round = 0; round < 2; ++round) {
    const Values a = evaluate(c.rx, c.ry, e_star, c.lubricant);
    const Values b = evaluate(1.1 * c.rx, c.ry, 0.9 * e_star, other);
    EXPECT_EQ(ehl_rolling_resistance(7, 800, c.rx, c.ry, e_star, c.lubricant), fresh.rolling);
    EXPECT_EQ(a.central, fresh.central);
    EXPECT_EQ(a.minimum, fresh.minimum);
    EXPECT_EQ(a.rolling, fresh.rolling);
    EXPECT_EQ(b.central, fresh_other.central);
    EXPECT_EQ(b.minimum, fresh_other.minimum);
    EXPECT_EQ(b.rolling, fresh_other.rolling);
    EXPECT_NE(a.central, b.central);
  }
}

}  // namespace
}  // namespace raceway::contact
