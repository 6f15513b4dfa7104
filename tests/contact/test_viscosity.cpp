// Viscosity against temperature and pressure (contact/laws/viscosity.hpp): Walther's equation against
// a published ASTM D341 worked example, Vogel's through its three points, Roelands' law against its
// definition (Barus' initial slope, below Barus at high pressure).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "contact/laws/viscosity.hpp"

namespace raceway::contact {
namespace {

// ASTM D341 worked example (a viscosity-temperature calculator after D341, its constants printed to
// four decimals): an ISO VG 32 oil, 32 mm^2/s at 40 degC and 5.4 mm^2/s at 100 degC (313 and 373 K as
// the example takes them): A = 9.5259, B = 3.7449, 8.5 mm^2/s at 80 degC (353 K).
TEST(Viscosity, WaltherAstmD341Example) {
  const WaltherConstants w = walther_constants(32e-6, 313.0, 5.4e-6, 373.0);
  EXPECT_NEAR(w.a, 9.5259, 5e-5);
  EXPECT_NEAR(w.b, 3.7449, 5e-5);
  const double nu80 = walther_viscosity(w, 353.0);
  std::printf("[ walther ] ISO VG 32: %.4g mm^2/s at 80 degC (published 8.5)\n", 1e6 * nu80);
  EXPECT_NEAR(1e6 * nu80, 8.5, 0.05);
  // Through its two points, and falling with temperature.
  EXPECT_NEAR(walther_viscosity(w, 313.0), 32e-6, 1e-12);
  EXPECT_NEAR(walther_viscosity(w, 373.0), 5.4e-6, 1e-12);
  EXPECT_GT(walther_viscosity(w, 330.0), walther_viscosity(w, 331.0));
}

TEST(Viscosity, VogelThroughItsPoints) {
  // An oil's dynamic viscosities at 20, 60 and 100 degC.
  const double t[3] = {293.15, 333.15, 373.15}, eta[3] = {0.29, 0.035, 0.0085};
  const VogelConstants v = vogel_constants(eta[0], t[0], eta[1], t[1], eta[2], t[2]);
  std::printf("[ vogel ] a %.4g Pa s, b %.4g K, c %.4g K\n", v.a, v.b, v.c);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(vogel_viscosity(v, t[i]), eta[i], 1e-12 * eta[i]);
  EXPECT_LT(v.c, t[0]);
  EXPECT_GT(v.b, 0.0);
}

// Roelands: ln(eta/eta0) = ln(eta0/eta_inf) ((1 + p/p_r)^Z - 1); Z from alpha gives Barus' initial
// slope; for a mineral oil (eta0 = 0.04 Pa s, alpha = 2e-8 1/Pa) Z = 0.61, in the 0.5-0.7 of mineral
// oils, and at 1 GPa the viscosity is orders of magnitude below Barus'.
TEST(Viscosity, RoelandsAgainstBarus) {
  const double eta0 = 0.04, alpha = 2e-8;
  const double z = roelands_index(eta0, alpha);
  EXPECT_NEAR(z, alpha * 1.96e8 / std::log(eta0 / 6.31e-5), 1e-15);
  EXPECT_NEAR(z, 0.6076, 1e-4);
  EXPECT_EQ(roelands_exponent(eta0, z, 0.0), 0.0);
  const double dp = 1e3;
  EXPECT_NEAR(roelands_exponent(eta0, z, dp) / dp, alpha, 1e-5 * alpha);  // (Z - 1) dp / 2 p_r: 1e-6
  const double p = 1e9;
  std::printf("[ roelands ] ln(eta/eta0) at 1 GPa: Roelands %.4g, Barus %.4g\n", roelands_exponent(eta0, z, p),
              barus_exponent(alpha, p));
  EXPECT_LT(roelands_exponent(eta0, z, p), barus_exponent(alpha, p) - 3.0);
  // By hand: 6.4519 ((1 + 1e9 / 1.96e8)^0.60757 - 1) = 6.4519 (6.10204^0.60757 - 1) = 6.4519 x 2.00077 = 12.909.
  EXPECT_NEAR(roelands_exponent(eta0, z, p), 12.909, 0.001);
}

}  // namespace
}  // namespace raceway::contact
