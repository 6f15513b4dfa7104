// The line-contact law on its own (contact/laws/line_contact.hpp): Palmgren's classical constant, the
// sliced law, Hunt-Crossley damping and validity. The segment-level versions of these checks run for
// every segment kind in test_segment_conformance.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "contact/laws/line_contact.hpp"

namespace raceway::contact {
namespace {

constexpr double n_exp = 10.0 / 9.0;

TEST(LineContactLaw, ReducedModulus) {
  // 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2; steel on steel, 207 GPa, 0.3: E* = 207e9 / (2 * 0.91).
  EXPECT_NEAR(reduced_modulus(207e9, 0.3, 207e9, 0.3), 207e9 / 1.82, 1e-12 * 207e9);
  const double steel_brass = 1.0 / ((1 - 0.09) / 208e9 + (1 - 0.34 * 0.34) / 100e9);
  EXPECT_NEAR(reduced_modulus(208e9, 0.3, 100e9, 0.34), steel_brass, 1e-12 * steel_brass);
  EXPECT_NEAR(reduced_modulus(100e9, 0.34, 208e9, 0.3), steel_brass, 1e-12 * steel_brass);
}

// 4. Palmgren: K = 0.70866 E* l^(8/9) reproduces Palmgren's steel constant
// Q = 8.06e4 delta^(10/9) l^(8/9) [N, mm] (Harris & Kotzalas eq. 6.40) within 0.1 %.
TEST(LineContactLaw, PalmgrenClassicalConstant) {
  EXPECT_DOUBLE_EQ(palmgren_exponent, 10.0 / 9.0);
  const double e_star = reduced_modulus(207e9, 0.3, 207e9, 0.3);
  const double length = 10e-3;
  const double k = palmgren_stiffness(e_star, length);
  EXPECT_NEAR(k, 0.70866 * e_star * std::pow(length, 8.0 / 9.0), 1e-12 * k);
  // 8.06e4 * (10 mm)^(8/9) N/mm^(10/9); delta in mm is 1000 delta in m.
  const double classical_n_per_mm = 8.06e4 * std::pow(10.0, 8.0 / 9.0);
  const double classical_si = classical_n_per_mm * std::pow(1000.0, n_exp);
  EXPECT_NEAR(k / classical_si, 1.0, 1e-3) << "K = " << k << ", Palmgren " << classical_si;
  // The magnitude, as a sanity anchor: 1.35e9 N/m^(10/9) for a 10 mm steel roller.
  EXPECT_NEAR(k, 1.3445e9, 1e-3 * 1.3445e9);
}

TEST(LineContactLaw, SlicedLawSumsToWholeLength) {
  const double e_star = reduced_modulus(208e9, 0.3, 208e9, 0.3);
  const LineContactLaw law = make_line_contact_law(e_star, 10e-3, 12, 4e-6, 0.5, 5e-5);
  ASSERT_EQ(law.slice_stiffness.size(), 12u);
  ASSERT_EQ(law.slice_drop.size(), 12u);
  const double sum = std::accumulate(law.slice_stiffness.begin(), law.slice_stiffness.end(), 0.0);
  EXPECT_NEAR(sum, law.stiffness, 1e-14 * law.stiffness);
  EXPECT_NEAR(law.stiffness, palmgren_stiffness(e_star, 10e-3), 1e-14 * law.stiffness);
  for (std::size_t j = 0; j < 12; ++j) {
    EXPECT_GE(law.slice_drop[j], 0.0);
    EXPECT_LT(law.slice_drop[j], 4e-6);
    EXPECT_NEAR(law.slice_drop[j], law.slice_drop[11 - j], 1e-12 * 4e-6) << "symmetric crown";
  }
  // Outermost slice centre at 11/12 of the half length: drop 4 um * (11/12)^2.
  EXPECT_NEAR(law.slice_drop[0], 4e-6 * (11.0 / 12.0) * (11.0 / 12.0), 1e-18);
  EXPECT_THROW(make_line_contact_law(e_star, 10e-3, 0, 0, 0, 1e-4), std::invalid_argument);
}

TEST(LineContactLaw, NormalForceAndEnergy) {
  const double e_star = reduced_modulus(208e9, 0.3, 208e9, 0.3);
  const LineContactLaw law = make_line_contact_law(e_star, 10e-3, 1, 0, 0.5, 5e-5);
  for (const double apart : {-1e-3, -1e-9, 0.0}) {
    const NormalForce f = evaluate_normal(law, apart, 3.0);
    EXPECT_TRUE(f.valid);
    EXPECT_EQ(f.force, 0.0);
    EXPECT_EQ(f.elastic_force, 0.0);
    EXPECT_EQ(f.elastic_energy, 0.0);
    EXPECT_EQ(f.damping_power, 0.0);
  }
  const double delta = 4e-6;
  const double q = law.stiffness * std::pow(delta, n_exp);
  const NormalForce still = evaluate_normal(law, delta, 0.0);
  EXPECT_NEAR(still.force, q, 1e-14 * q);
  EXPECT_NEAR(still.elastic_force, q, 1e-14 * q);
  EXPECT_NEAR(still.elastic_energy, q * delta * 9.0 / 19.0, 1e-14 * q * delta);
  EXPECT_EQ(still.damping_power, 0.0);
  // Hunt-Crossley: elastic (1 + c rate), clipped at zero, dissipative.
  for (const double rate : {0.4, -0.4, -2.0, -5.0}) {
    const NormalForce f = evaluate_normal(law, delta, rate);
    const double expected = std::max(0.0, q * (1 + 0.5 * rate));
    EXPECT_NEAR(f.force, expected, 1e-14 * q) << "rate " << rate;
    EXPECT_NEAR(f.elastic_force, q, 1e-14 * q);
    EXPECT_GE(f.damping_power, 0.0);
    EXPECT_NEAR(f.damping_power, (expected - q) * rate, 1e-14 * q * std::abs(rate));
  }
}

TEST(LineContactLaw, Validity) {
  const LineContactLaw law = make_line_contact_law(1e11, 10e-3, 3, 1e-6, 0.5, 5e-5);
  EXPECT_TRUE(evaluate_normal(law, 4.9e-5, 0.1).valid);
  EXPECT_FALSE(evaluate_normal(law, 5.1e-5, 0.1).valid);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(evaluate_normal(law, nan, 0.0).valid);
  EXPECT_FALSE(evaluate_normal(law, 1e-6, nan).valid);
  EXPECT_FALSE(evaluate_normal(law, inf, 0.0).valid);
  EXPECT_FALSE(evaluate_normal(law, 1e-6, -inf).valid);
}

TEST(TractionCurve, ShapeAndSlope) {
  TractionCurve curve;
  curve.friction_coefficient = 0.1;
  curve.slip_velocity_scale = 0.05;
  EXPECT_EQ(curve.coefficient(0.0), 0.0);
  EXPECT_NEAR(curve.coefficient(0.05), 0.1 * std::tanh(1.0), 1e-15);
  EXPECT_NEAR(curve.coefficient(-0.05), -0.1 * std::tanh(1.0), 1e-15);
  const double h = 1e-8;
  EXPECT_NEAR((curve.coefficient(h) - curve.coefficient(0.0)) / h, 0.1 / 0.05, 1e-6);
  curve.friction_coefficient = 0;
  EXPECT_EQ(curve.coefficient(1.0), 0.0);
}

}  // namespace
}  // namespace raceway::contact
