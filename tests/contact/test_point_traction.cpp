// Traction integrated over a point contact's ellipse (contact/laws/point_contact.hpp): equilibrium,
// symmetry, energy, limits (Newtonian, limiting shear, the curve), the hand-over from film to curve,
// and grid convergence.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "contact/laws/point_contact.hpp"
#include "contact/laws/viscosity.hpp"

namespace raceway::contact {
namespace {

constexpr double pi = std::numbers::pi;

PointTraction curve_traction(int grid) {
  PointTraction t;
  t.model = TractionModel::curve;
  t.friction_coefficient = 0.1;
  t.slip_velocity_scale = 0.01;
  t.grid_x = t.grid_y = grid;
  return t;
}
PointLubricant oil() {
  PointLubricant lub;
  lub.viscosity = 0.04;
  lub.pressure_viscosity = 2.0e-8;
  lub.limiting_shear_coefficient = 0.08;
  return lub;
}
constexpr double load = 1000, ax = 3e-4, ay = 1.2e-3;  // semi-axes: rolling, transverse

TEST(PointTraction, PureSlideGivesCurveTimesLoad) {
  const PointTraction t = curve_traction(10);
  for (const double slide : {1e-4, 3e-3, 0.01, 0.5}) {
    const ContactSliding s{slide * 0.6, -slide * 0.8, 0};
    const TractionResult r = integrate_traction(t, oil(), load, ax, ay, 0, s);
    const double expected = 0.1 * std::tanh(slide / 0.01) * load;
    EXPECT_NEAR(std::hypot(r.force_x, r.force_y), expected, 1e-3 * expected) << slide;
    // Opposing the slip, exactly antiparallel, and dissipating |F| s.
    EXPECT_NEAR(r.force_x / expected, -0.6, 1e-12);
    EXPECT_NEAR(r.force_y / expected, 0.8, 1e-12);
    EXPECT_NEAR(r.power_loss, expected * slide, 1e-12 * expected * slide);
    EXPECT_NEAR(r.spin_moment, 0, 1e-12 * expected * ay);
  }
}

// Slips on both sides of where tanh(x)/x changes its evaluation (its rational approximant up to
// x = 1, one exponential above, 1/x where tanh rounds to 1 beyond x = 19.5): the curve's
// mu Q tanh(s / s_scale), to round-off, against the library's tanh.
TEST(PointTraction, CurveIsTanhToRoundOff) {
  const PointTraction t = curve_traction(5);
  for (const double slide : {0.0, 1e-9, 1e-6, 2e-5, 1e-4, 3e-3, 0.009999, 0.010001, 0.05, 0.19, 0.2, 0.3}) {
    const double f = -integrate_traction(t, oil(), load, ax, ay, 0, {slide, 0, 0}).force_x;
    const double x = slide / 0.01;
    const double expected = x == 0 ? 0.0 : 0.1 * load * std::tanh(x);
    EXPECT_NEAR(f, expected, 1e-14 * expected) << slide;
  }
}

// The grid is symmetric about both axes (its mirrored cells are the same bits, only the order of
// the cells' sum differs): mirrored sliding gives the mirrored traction to round-off (forces and
// moment change sign, the power stays), for the curve and the film's shear.
TEST(PointTraction, MirroredSlidingGivesMirroredTraction) {
  for (const TractionModel model : {TractionModel::curve, TractionModel::limiting_shear}) {
    for (const int grid : {4, 5, 7}) {
      PointTraction t = curve_traction(grid);
      t.model = model;
      const TractionResult r = integrate_traction(t, oil(), load, ax, ay, 2e-7, {0.003, -0.002, 7});
      const double f = std::hypot(r.force_x, r.force_y), tol = 1e-14 * f, tol_m = tol * ay;
      // Mirrored across both axes (x -> -x, y -> -y): the sliding changes sign, the spin stays.
      const TractionResult m = integrate_traction(t, oil(), load, ax, ay, 2e-7, {-0.003, 0.002, 7});
      EXPECT_NEAR(m.force_x, -r.force_x, tol) << grid;
      EXPECT_NEAR(m.force_y, -r.force_y, tol) << grid;
      EXPECT_NEAR(m.spin_moment, r.spin_moment, tol_m) << grid;
      EXPECT_NEAR(m.power_loss, r.power_loss, 1e-14 * r.power_loss) << grid;
      // Mirrored across the rolling axis (y -> -y): slide_y and the spin change sign.
      const TractionResult y = integrate_traction(t, oil(), load, ax, ay, 2e-7, {0.003, 0.002, -7});
      EXPECT_NEAR(y.force_x, r.force_x, tol) << grid;
      EXPECT_NEAR(y.force_y, -r.force_y, tol) << grid;
      EXPECT_NEAR(y.spin_moment, -r.spin_moment, tol_m) << grid;
      EXPECT_NEAR(y.power_loss, r.power_loss, 1e-14 * r.power_loss) << grid;
    }
  }
}

// The summed pressure times area is the normal load: at full saturation the curve gives mu Q and
// the limiting-shear model Lambda Q, whatever the grid.
TEST(PointTraction, PressureIntegratesToTheNormalLoad) {
  for (const int grid : {1, 2, 3, 5, 10, 17}) {
    PointTraction t = curve_traction(grid);
    const ContactSliding s{50.0, 0, 0};  // s / s_scale = 5000: tanh = 1
    EXPECT_NEAR(-integrate_traction(t, oil(), load, ax, ay, 0, s).force_x, 0.1 * load, 1e-12 * load) << grid;
    t.model = TractionModel::limiting_shear;
    EXPECT_NEAR(-integrate_traction(t, oil(), load, ax, ay, 1e-7, s).force_x, 0.08 * load, 1e-9 * load)
        << grid;
  }
}

TEST(PointTraction, PureSpinHasNoNetForceAndAMomentOpposingIt) {
  for (const TractionModel model : {TractionModel::curve, TractionModel::limiting_shear}) {
    PointTraction t = curve_traction(10);
    t.model = model;
    for (const double spin : {-200.0, -1.0, 0.5, 300.0}) {
      const TractionResult r = integrate_traction(t, oil(), load, ax, ay, 2e-7, {0, 0, spin});
      EXPECT_NEAR(r.force_x, 0, 1e-12 * load);
      EXPECT_NEAR(r.force_y, 0, 1e-12 * load);
      EXPECT_LT(r.spin_moment * spin, 0) << "the moment opposes the spin";
      EXPECT_NEAR(r.power_loss, -r.spin_moment * spin, 1e-12 * r.power_loss);
    }
  }
}

// Energy balance: the power dissipated equals the power the traction takes from the relative
// motion, -(F . slide) - M spin, for any combination of slide and spin.
TEST(PointTraction, PowerLossIsTheWorkOfTheTraction) {
  for (const TractionModel model : {TractionModel::curve, TractionModel::limiting_shear}) {
    PointTraction t = curve_traction(7);
    t.model = model;
    t.grid_y = 9;
    for (const ContactSliding s : {ContactSliding{0.02, 0.001, 0}, ContactSliding{-0.003, 0.004, 40},
                                   ContactSliding{1e-5, -2e-5, -3}, ContactSliding{0, 0, 0}}) {
      const TractionResult r = integrate_traction(t, oil(), load, ax, ay, 2e-7, s);
      const double work = -(r.force_x * s.slide_x + r.force_y * s.slide_y) - r.spin_moment * s.spin;
      EXPECT_GE(r.power_loss, 0.0);
      EXPECT_NEAR(r.power_loss, work, 1e-12 * std::max(r.power_loss, 1e-300));
    }
  }
}

TEST(PointTraction, ContinuousThroughZeroSlip) {
  const PointTraction t = curve_traction(10);
  const TractionResult plus = integrate_traction(t, oil(), load, ax, ay, 0, {1e-9, 0, 0});
  const TractionResult minus = integrate_traction(t, oil(), load, ax, ay, 0, {-1e-9, 0, 0});
  const TractionResult zero = integrate_traction(t, oil(), load, ax, ay, 0, {0, 0, 0});
  // Slope at zero: mu Q / s_scale = 1e4 N s/m; the jump across +-1e-9 m/s is that times 2e-9.
  EXPECT_NEAR(plus.force_x - minus.force_x, -2e-9 * 0.1 * load / 0.01, 1e-9 * 1e-5);
  EXPECT_EQ(zero.force_x, 0.0);
  EXPECT_EQ(zero.power_loss, 0.0);
  // Spin and slide together, slip crossing zero inside the contact: still finite and continuous.
  const TractionResult a = integrate_traction(t, oil(), load, ax, ay, 0, {1e-9, 0, 1e-6});
  const TractionResult b = integrate_traction(t, oil(), load, ax, ay, 0, {-1e-9, 0, 1e-6});
  EXPECT_TRUE(std::isfinite(a.force_x) && std::isfinite(a.spin_moment));
  EXPECT_NEAR(a.force_x, b.force_x, 3e-5);
}

TEST(PointTraction, LimitingShearNewtonianAndSaturated) {
  PointTraction t = curve_traction(10);
  t.model = TractionModel::limiting_shear;
  const double h = 2e-7;
  // Small slip, isoviscous: tau = eta0 s / h everywhere, F = eta0 s / h * (pi ax ay).
  PointLubricant iso = oil();
  iso.pressure_viscosity = 0;
  const double slide = 1e-6;
  const TractionResult newtonian = integrate_traction(t, iso, load, ax, ay, h, {slide, 0, 0});
  const double expected = iso.viscosity * slide / h * pi * ax * ay;
  EXPECT_NEAR(-newtonian.force_x, expected, 1e-9 * expected);
  // Piezoviscous: the same slip shears a stiffer oil.
  const TractionResult piezo = integrate_traction(t, oil(), load, ax, ay, h, {slide, 0, 0});
  EXPECT_GT(-piezo.force_x, 10 * expected);
  // Large slip: saturated at Lambda p, net Lambda Q.
  const TractionResult saturated = integrate_traction(t, oil(), load, ax, ay, h, {30.0, 0, 0});
  EXPECT_NEAR(-saturated.force_x, 0.08 * load, 1e-6 * load);
  // Monotone in slip between the two.
  double previous = 0;
  for (const double s : {1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 1.0}) {
    const double f = -integrate_traction(t, oil(), load, ax, ay, h, {s, 0, 0}).force_x;
    EXPECT_GT(f, previous);
    EXPECT_LE(f, 0.08 * load * (1 + 1e-12));
    previous = f;
  }
}

// Roelands' viscosity (roelands_index > 0) rises with the same initial slope as Barus' but far less at
// the contact's GPa: at small slip its traction lies between the isoviscous and the Barus one, nearer
// the isoviscous at this load; saturated, both reach Lambda Q.
TEST(PointTraction, RoelandsBelowBarus) {
  PointTraction t = curve_traction(10);
  t.model = TractionModel::limiting_shear;
  const double h = 2e-7, slide = 1e-6;
  PointLubricant roelands = oil();
  roelands.roelands_index = roelands_index(roelands.viscosity, roelands.pressure_viscosity);
  PointLubricant iso = oil();
  iso.pressure_viscosity = 0;
  const double f_iso = -integrate_traction(t, iso, load, ax, ay, h, {slide, 0, 0}).force_x;
  const double f_barus = -integrate_traction(t, oil(), load, ax, ay, h, {slide, 0, 0}).force_x;
  const double f_roelands = -integrate_traction(t, roelands, load, ax, ay, h, {slide, 0, 0}).force_x;
  std::printf("[ roelands ] small-slip traction: isoviscous %.4g N, Roelands %.4g N, Barus %.4g N\n", f_iso,
              f_roelands, f_barus);
  EXPECT_GT(f_roelands, 10 * f_iso);
  EXPECT_LT(f_roelands, 0.1 * f_barus);
  const double saturated = -integrate_traction(t, roelands, load, ax, ay, h, {30.0, 0, 0}).force_x;
  EXPECT_NEAR(saturated, 0.08 * load, 1e-6 * load);
}

// Isoviscous Newtonian spin: tau = eta0 omega r / h, so M = -(eta0 omega / h) J with J the polar
// moment of the ellipse, pi ax ay (ax^2 + ay^2) / 4; the midpoint rule over cell centroids
// undercounts each cell's own second moment, O(cell size^2).
TEST(PointTraction, NewtonianSpinMomentIsThePolarMoment) {
  PointTraction t = curve_traction(64);
  t.model = TractionModel::limiting_shear;
  PointLubricant iso = oil();
  iso.pressure_viscosity = 0;
  const double h = 2e-7, spin = 1e-3;
  const double polar = pi * ax * ay * (ax * ax + ay * ay) / 4;
  const double expected = -iso.viscosity * spin / h * polar;
  const TractionResult r = integrate_traction(t, iso, load, ax, ay, h, {0, 0, spin});
  EXPECT_GT(r.spin_moment, expected) << "midpoint rule: below the exact magnitude";
  // Interior cells miss area (dx^2 + dy^2) / 12 each: 3.3e-4 of J here; the rest (boundary cells)
  // is an order smaller.
  const double dx = 2 * ax / 64, dy = 2 * ay / 64;
  const double midpoint = expected * (1 - pi * ax * ay * (dx * dx + dy * dy) / 12 / polar);
  EXPECT_NEAR(r.spin_moment, midpoint, 5e-5 * std::abs(expected));
}

// The Barus exponent is capped at alpha p = 20: an extreme alpha gives a finite, Newtonian shear
// with eta0 e^20 (instead of overflow) wherever alpha p > 20 -- here in every cell.
TEST(PointTraction, ViscosityExponentIsCapped) {
  PointTraction t = curve_traction(8);
  t.model = TractionModel::limiting_shear;
  PointLubricant extreme = oil();
  extreme.pressure_viscosity = 1e-5;  // alpha p ~ 1e4 at Hertz pressures
  const double h = 2e-7, slide = 1e-12;
  const TractionResult r = integrate_traction(t, extreme, load, ax, ay, h, {slide, 0, 0});
  const double expected = extreme.viscosity * std::exp(20.0) * slide / h * pi * ax * ay;
  EXPECT_NEAR(-r.force_x, expected, 1e-6 * expected);
  const TractionResult still = integrate_traction(t, extreme, load, ax, ay, h, {0, 0, 0});
  EXPECT_EQ(still.force_x, 0.0);
  EXPECT_TRUE(std::isfinite(still.power_loss));
}

TEST(PointTraction, FallsBackAndSwitchesOff) {
  PointTraction limiting = curve_traction(6);
  limiting.model = TractionModel::limiting_shear;
  const PointTraction curve = curve_traction(6);
  const ContactSliding s{0.004, 0.001, 20};
  const TractionResult by_curve = integrate_traction(curve, oil(), load, ax, ay, 0, s);
  for (const double h : {0.0, -1e-7}) {
    const TractionResult r = integrate_traction(limiting, oil(), load, ax, ay, h, s);
    EXPECT_EQ(r.force_x, by_curve.force_x);
    EXPECT_EQ(r.spin_moment, by_curve.spin_moment);
  }
  PointLubricant dry = oil();
  dry.viscosity = 0;
  EXPECT_EQ(integrate_traction(limiting, dry, load, ax, ay, 1e-7, s).force_x, by_curve.force_x);
  PointTraction none = curve;
  none.model = TractionModel::none;
  const TractionResult off = integrate_traction(none, oil(), load, ax, ay, 1e-7, s);
  EXPECT_EQ(off.force_x, 0.0);
  EXPECT_EQ(off.force_y, 0.0);
  EXPECT_EQ(off.spin_moment, 0.0);
  EXPECT_EQ(off.power_loss, 0.0);
  EXPECT_EQ(integrate_traction(curve, oil(), 0, ax, ay, 0, s).power_loss, 0.0);
  PointTraction bad = curve;
  bad.grid_x = 0;
  EXPECT_THROW(integrate_traction(bad, oil(), load, ax, ay, 0, s), std::invalid_argument);
}

// As the film vanishes (zero entrainment: standstill, start, stop) the film's shear hands over to
// the friction curve: continuous in h at h -> 0 and at the boundary film, identical to the film law
// above it, and with a small-slip slope that stays bounded (the film's own, eta / h, does not).
TEST(PointTraction, FilmHandsOverToTheCurveAsItVanishes) {
  const PointLubricant lub = oil();
  const double hb = lub.boundary_film;
  EXPECT_EQ(film_weight(0.0, lub), 0.0);
  EXPECT_EQ(film_weight(-1e-9, lub), 0.0);
  EXPECT_EQ(film_weight(hb, lub), 1.0);
  EXPECT_EQ(film_weight(10 * hb, lub), 1.0);
  EXPECT_NEAR(film_weight(0.5 * hb, lub), 0.5, 1e-15);
  // C1 at both ends: the slope of x^2 (3 - 2x) vanishes at x = 0 and x = 1.
  EXPECT_LT(film_weight(1e-6 * hb, lub), 1e-11);
  EXPECT_GT(film_weight((1 - 1e-6) * hb, lub), 1 - 1e-11);

  PointTraction limiting = curve_traction(6);
  limiting.model = TractionModel::limiting_shear;
  const ContactSliding s{0.004, 0.001, 20};
  const TractionResult curve = integrate_traction(curve_traction(6), lub, load, ax, ay, 0, s);
  const TractionResult thin = integrate_traction(limiting, lub, load, ax, ay, 1e-9 * hb, s);
  EXPECT_NEAR(thin.force_x, curve.force_x, 1e-9 * std::abs(curve.force_x));
  EXPECT_NEAR(thin.spin_moment, curve.spin_moment, 1e-9 * std::abs(curve.spin_moment));
  const TractionResult below = integrate_traction(limiting, lub, load, ax, ay, (1 - 1e-9) * hb, s);
  const TractionResult at = integrate_traction(limiting, lub, load, ax, ay, hb, s);
  EXPECT_NEAR(below.force_x, at.force_x, 1e-6 * std::abs(at.force_x));
  // At the boundary film and above: the film law itself, saturating at Lambda Q.
  EXPECT_NEAR(-integrate_traction(limiting, lub, load, ax, ay, hb, {50.0, 0, 0}).force_x, 0.08 * load, 1e-9 * load);

  // Small-slip slope over h in (0, 2 h_b]: at most the curve's mu Q / s_scale plus the film's
  // largest eta / h times w(h) <= 9/8 / h_b, times the contact area.
  const double eta_max = lub.viscosity * std::exp(lub.viscosity_exponent_cap);
  const double bound = 0.1 * load / 0.01 + 1.125 / hb * eta_max * pi * ax * ay;
  const double slip = 1e-12;
  double previous = 0, steepest = 0;
  for (int i = 1; i <= 400; ++i) {
    const double h = 2 * hb * i / 400;
    const double slope = -integrate_traction(limiting, lub, load, ax, ay, h, {slip, 0, 0}).force_x / slip;
    EXPECT_LE(slope, bound) << h;
    if (i > 1) {
      EXPECT_LT(std::abs(slope - previous), 0.05 * bound) << "a jump at h = " << h;
    }
    previous = slope;
    steepest = std::max(steepest, slope);
  }
  EXPECT_GT(steepest, 0.5 * 0.1 * load / 0.01);
}

// Coulomb spin on a circle: M = mu times the integral of p r dA = (3 pi / 16) mu Q a for the Hertz
// pressure p0 sqrt(1 - r^2/a^2), p0 = 3 Q / (2 pi a^2). The grid converges to it.
TEST(PointTraction, GridConvergesForSpin) {
  const double a = 5e-4, mu = 0.1;
  const double exact = 3 * pi / 16 * mu * load * a;
  double previous_error = 1;
  for (const int grid : {4, 8, 16, 32, 64}) {
    PointTraction t = curve_traction(grid);
    t.slip_velocity_scale = 1e-9;  // Coulomb
    const double m = integrate_traction(t, oil(), load, a, a, 0, {0, 0, 100}).spin_moment;
    const double error = std::abs(-m / exact - 1);
    EXPECT_LT(error, previous_error) << grid;
    previous_error = error;
    if (grid == 16) {
      EXPECT_LT(error, 1e-2);
    }
  }
  EXPECT_LT(previous_error, 2e-3);
  // Limiting shear with slide and spin (the net force is a small residue of opposing shears):
  // refining the grid four times at a time approaches a 384 x 384 reference.
  PointTraction t = curve_traction(384);
  t.model = TractionModel::limiting_shear;
  const ContactSliding s{0.002, 0.0, 15};
  const TractionResult fine = integrate_traction(t, oil(), load, ax, ay, 2e-7, s);
  double previous = 1e300;
  for (const int grid : {6, 24, 96}) {
    t.grid_x = t.grid_y = grid;
    const TractionResult r = integrate_traction(t, oil(), load, ax, ay, 2e-7, s);
    const double error = std::abs(r.force_x / fine.force_x - 1) +
                         std::abs(r.spin_moment / fine.spin_moment - 1) +
                         std::abs(r.power_loss / fine.power_loss - 1);
    EXPECT_LT(error, 0.25 * previous) << grid;
    previous = error;
  }
  EXPECT_LT(previous, 5e-3);
}

}  // namespace
}  // namespace raceway::contact
