// Roller profiles and the sliced line contact on their own (contact/laws/roller_profile.hpp,
// sliced_line_contact.hpp): the profiles' drops against their closed forms, the aligned straight
// roller against the unsliced Palmgren law, mirror symmetry under tilt, edge loading against the
// slice formula written here, the derivatives against central differences, continuity at onset and
// the validity flag.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "contact/laws/sliced_line_contact.hpp"

namespace raceway::contact {
namespace {

constexpr double n_exp = 10.0 / 9.0;
const double e_star = reduced_modulus(208e9, 0.3, 208e9, 0.3);

RollerProfile straight(double length, double corner = 0) {
  return {.kind = RollerProfileKind::straight, .length = length, .corner_radius = corner};
}
RollerProfile circular(double length, double corner, double crown_radius, double flat) {
  return {.kind = RollerProfileKind::circular, .length = length, .corner_radius = corner,
          .crown_radius = crown_radius, .flat_length = flat};
}
RollerProfile logarithmic(RollerProfileKind kind, double length, double corner, double load) {
  return {.kind = kind, .length = length, .corner_radius = corner, .design_load = load,
          .reduced_modulus = e_star, .rolling_radius = 4e-3};
}

TEST(RollerProfile, StraightWithRoundedEnds) {
  const RollerProfile p = straight(10e-3, 0.5e-3);
  EXPECT_EQ(profile_drop(p, 0.0), 0.0);
  EXPECT_EQ(profile_drop(p, 4.5e-3), 0.0);
  // 0.4 mm into a 0.5 mm corner: 0.5 - sqrt(0.25 - 0.16) = 0.2 mm.
  EXPECT_NEAR(profile_drop(p, 4.9e-3), 0.2e-3, 1e-15);
  EXPECT_NEAR(profile_drop(p, -4.9e-3), 0.2e-3, 1e-15);
  EXPECT_EQ(profile_drop(straight(10e-3), 4.99e-3), 0.0);
  EXPECT_DOUBLE_EQ(effective_length(p), 9e-3);
}

TEST(RollerProfile, CircularCrown) {
  const RollerProfile full = circular(12e-3, 0.0, 1.0, 0.0);
  for (const double x : {1e-3, 3e-3, 5.9e-3}) {  // R - sqrt(R^2 - x^2) = x^2/2R + x^4/8R^3 + ...
    const double series = x * x / 2 + std::pow(x, 4) / 8 + std::pow(x, 6) / 16;
    EXPECT_NEAR(profile_drop(full, x), series, 1e-12 * series) << x;
  }
  const RollerProfile partial = circular(12e-3, 0.5e-3, 0.5, 6e-3);
  EXPECT_EQ(profile_drop(partial, 2.9e-3), 0.0);
  EXPECT_NEAR(profile_drop(partial, 4e-3), 0.5 - std::sqrt(0.25 - 1e-6), 1e-15);
  // At the corner: crown of the whole crowned half-length (2.5 mm) plus the corner's 0.2 mm.
  EXPECT_NEAR(profile_drop(partial, 5.9e-3), 0.5 - std::sqrt(0.25 - 6.25e-6) + 0.5e-3 - std::sqrt(0.25e-6 - 0.16e-6),
              1e-15);
}

TEST(RollerProfile, LogarithmicCrowns) {
  const double load = 5e3, length = 10e-3;
  const RollerProfile lund = logarithmic(RollerProfileKind::lundberg, length, 0.0, load);
  const RollerProfile jg = logarithmic(RollerProfileKind::johns_gohar, length, 0.0, load);
  const double scale = load / (std::numbers::pi * length * e_star);
  // Lundberg: where 1 - (2x/l)^2 = 1/e the drop is the scale itself.
  const double x_e = 0.5 * length * std::sqrt(1 - std::exp(-1.0));
  EXPECT_NEAR(profile_drop(lund, x_e), scale, 1e-12 * scale);
  EXPECT_EQ(profile_drop(lund, 0.0), 0.0);
  // Johns-Gohar: finite at the end of the effective length, 2 scale ln(a / b).
  const double b = std::sqrt(4 * load * 4e-3 / (std::numbers::pi * length * e_star));
  EXPECT_NEAR(johns_gohar_half_width(jg), b, 1e-15);
  const double x_end = 0.5 * length * (1 - 1e-12);
  EXPECT_NEAR(profile_drop(jg, x_end), 2 * scale * std::log(0.5 * length / b), 1e-6 * scale);
  EXPECT_GT(profile_drop(lund, x_end), 3 * profile_drop(jg, x_end));
  // Near the middle, both are scale (c r^2) with c = 1 and 1 - (b/a)^2.
  const double x = 1e-5, r = 2 * x / length;
  EXPECT_NEAR(profile_drop(lund, x), scale * r * r, 1e-5 * scale * r * r);
  EXPECT_NEAR(profile_drop(jg, x), scale * (1 - std::pow(b / (0.5 * length), 2)) * r * r, 1e-5 * scale * r * r);
  // Even and growing.
  double previous = 0;
  for (int i = 1; i < 50; ++i) {
    const double xi = 0.5 * length * i / 50.0;
    for (const RollerProfile& p : {lund, jg}) EXPECT_EQ(profile_drop(p, xi), profile_drop(p, -xi));
    EXPECT_GT(profile_drop(jg, xi), previous);
    previous = profile_drop(jg, xi);
  }
}

TEST(RollerProfile, BadProfilesAreRejectedWithTheReason) {
  EXPECT_EQ(validate_profile(straight(10e-3, 1e-3)), "");
  EXPECT_NE(validate_profile(straight(0.0)), "");
  EXPECT_NE(validate_profile(straight(10e-3, 5e-3)).find("corner_radius"), std::string::npos);
  EXPECT_NE(validate_profile(circular(10e-3, 0, 2e-3, 0)).find("crown_radius"), std::string::npos);
  EXPECT_NE(validate_profile(circular(10e-3, 1e-3, 1.0, 8e-3)).find("flat_length"), std::string::npos);
  EXPECT_NE(validate_profile(logarithmic(RollerProfileKind::lundberg, 10e-3, 0, 0)).find("design_load"),
            std::string::npos);
  // A design load whose contact is wider than the roller is long.
  EXPECT_NE(validate_profile(logarithmic(RollerProfileKind::johns_gohar, 10e-3, 0, 1e9)).find("half-width"),
            std::string::npos);
  EXPECT_THROW(profile_drop(straight(10e-3), 5e-3), std::invalid_argument);
  EXPECT_THROW(profile_drop(straight(10e-3, 6e-3), 0.0), std::invalid_argument);
  EXPECT_THROW(make_sliced_line_contact(e_star, straight(10e-3), 0, 0, 1e-4), std::invalid_argument);
  ASSERT_NE(find_profile("johns_gohar"), nullptr);
  EXPECT_EQ(find_profile("johns_gohar")->kind, RollerProfileKind::johns_gohar);
  EXPECT_EQ(find_profile("log"), nullptr);
  EXPECT_EQ(known_profile_names(), "straight, circular, lundberg, johns_gohar");
}

// An aligned straight roller, sliced any way, carries the unsliced Palmgren law of its length,
// damping included.
TEST(SlicedLineContact, AlignedStraightRollerIsTheUnslicedLaw) {
  const double length = 14e-3, damping = 0.4;
  const LineContactLaw whole = make_line_contact_law(e_star, length, 1, 0.0, damping, 1e-4);
  for (const int slices : {1, 2, 7, 30, 31}) {
    const SlicedLineContact c = make_sliced_line_contact(e_star, straight(length), slices, damping, 1e-4);
    for (const double approach : {1e-7, 3e-6, 2e-5}) {
      for (const double rate : {0.0, 0.05, -0.3}) {
        const TiltedLineForce f = evaluate_tilted(c, approach, 0.0, rate, 0.0);
        const NormalForce ref = evaluate_normal(whole, approach, rate);
        EXPECT_NEAR(f.force, ref.force, 1e-13 * ref.force) << slices;
        EXPECT_NEAR(f.elastic_energy, ref.elastic_energy, 1e-13 * ref.elastic_energy);
        EXPECT_NEAR(f.damping_power, ref.damping_power, 1e-12 * std::abs(ref.elastic_force * rate) + 1e-300);
        EXPECT_NEAR(f.moment, 0.0, 1e-13 * f.force * length);
      }
    }
  }
  // Rounded ends: the flat length l - 2 r_c carries the law of that length; corner slices start to
  // carry only under a larger approach. The error is that of the slices that straddle the corner.
  const RollerProfile rounded = straight(length, 1e-3);
  const double k_e = palmgren_stiffness(e_star, effective_length(rounded));
  for (const int slices : {14, 140}) {
    const SlicedLineContact c = make_sliced_line_contact(e_star, rounded, slices, 0.0, 1e-4);
    const double f = evaluate_tilted(c, 2e-6, 0.0, 0.0, 0.0).force;
    EXPECT_NEAR(f / (k_e * std::pow(2e-6, n_exp)), 1.0, 2.0 / slices) << slices;
  }
}

// Mirroring the tilt mirrors the slice loads bit for bit; force equal, moment opposite.
TEST(SlicedLineContact, MirrorSymmetricUnderTilt) {
  for (const int slices : {30, 31}) {
    for (const RollerProfile& p : {straight(14e-3, 0.8e-3), circular(14e-3, 0.8e-3, 2.0, 4e-3),
                                   logarithmic(RollerProfileKind::johns_gohar, 14e-3, 0.8e-3, 4e3)}) {
      const SlicedLineContact c = make_sliced_line_contact(e_star, p, slices, 0.3, 1e-4);
      std::vector<double> plus(c.slice_centre.size()), minus(c.slice_centre.size());
      const TiltedLineForce fp = evaluate_tilted(c, 4e-6, 1e-3, 0.01, 0.2, plus);
      const TiltedLineForce fm = evaluate_tilted(c, 4e-6, -1e-3, 0.01, -0.2, minus);
      ASSERT_GT(fp.force, 0.0);
      EXPECT_GT(fp.moment, 0.0);
      for (std::size_t j = 0; j < plus.size(); ++j) EXPECT_EQ(plus[j], minus[plus.size() - 1 - j]);
      EXPECT_NEAR(fp.force, fm.force, 1e-14 * fp.force);
      EXPECT_NEAR(fp.moment, -fm.moment, 1e-14 * fp.force * 14e-3);
      EXPECT_EQ(fp.max_slice_force, fm.max_slice_force);
    }
  }
}

// A tilted straight roller: each slice carries K_j (delta + theta x_j)^(10/9) (this test's own
// formula), so the loaded end carries most; a crown relieves that end.
TEST(SlicedLineContact, EdgeLoadingUnderTilt) {
  const double length = 14e-3, approach = 3e-6, tilt = 0.5e-3;  // the ends move by -+3.5 um
  const int slices = 28;
  const SlicedLineContact c = make_sliced_line_contact(e_star, straight(length), slices, 0.0, 1e-4);
  std::vector<double> loads(slices);
  const TiltedLineForce f = evaluate_tilted(c, approach, tilt, 0.0, 0.0, loads);
  const double k_j = palmgren_stiffness(e_star, length) / slices, w = length / slices;
  double force = 0, moment = 0;
  for (int j = 0; j < slices; ++j) {
    const double x = -0.5 * length + (j + 0.5) * w;
    const double d = approach + tilt * x;
    const double expected = d > 0 ? k_j * std::pow(d, n_exp) : 0.0;
    EXPECT_NEAR(loads[static_cast<std::size_t>(j)], expected, 1e-12 * f.max_slice_force) << j;
    force += expected;
    moment += expected * x;
  }
  EXPECT_NEAR(f.force, force, 1e-12 * force);
  EXPECT_NEAR(f.moment, moment, 1e-12 * std::abs(moment));
  EXPECT_EQ(loads.front(), 0.0);  // the unloaded end lifts off
  EXPECT_EQ(f.max_slice_force, loads.back());
  EXPECT_GT(loads.back(), 1.5 * loads[slices / 2]);
  // The same tilt on a Johns-Gohar roller: a smaller edge load against its middle.
  const SlicedLineContact jg = make_sliced_line_contact(
      e_star, logarithmic(RollerProfileKind::johns_gohar, length, 0.0, 8e3), slices, 0.0, 1e-4);
  std::vector<double> crowned(slices);
  evaluate_tilted(jg, approach, tilt, 0.0, 0.0, crowned);
  EXPECT_LT(crowned.back() / crowned[slices / 2], 0.5 * loads.back() / loads[slices / 2]);
}

// The derivatives against central differences, with slices on both sides of contact.
TEST(SlicedLineContact, DerivativesMatchFiniteDifferences) {
  const SlicedLineContact c =
      make_sliced_line_contact(e_star, circular(14e-3, 0.8e-3, 1.5, 2e-3), 25, 0.5, 1e-4);
  const std::array<double, 4> x0 = {3e-6, 0.4e-3, 0.02, 1.5};
  const std::array<double, 4> h = {1e-10, 1e-8, 1e-5, 1e-3};
  auto at = [&](const std::array<double, 4>& x) { return evaluate_tilted(c, x[0], x[1], x[2], x[3]); };
  const TiltedLineForce base = at(x0);
  ASSERT_GT(base.force, 0.0);
  std::vector<double> loads(25);
  evaluate_tilted(c, x0[0], x0[1], x0[2], x0[3], loads);
  ASSERT_EQ(loads.front(), 0.0) << "the check wants unloaded slices";
  for (std::size_t v = 0; v < 4; ++v) {
    std::array<double, 4> up = x0, down = x0;
    up[v] += h[v];
    down[v] -= h[v];
    const double df = (at(up).force - at(down).force) / (2 * h[v]);
    const double dm = (at(up).moment - at(down).moment) / (2 * h[v]);
    EXPECT_NEAR(base.d_force[v], df, 1e-5 * std::abs(df) + 1e-9 * base.force / h[v]) << v;
    EXPECT_NEAR(base.d_moment[v], dm, 1e-5 * std::abs(dm) + 1e-9 * base.force * 7e-3 / h[v]) << v;
  }
}

// At onset (the first slice just touching) force and slope vanish: the exponent is above 1.
TEST(SlicedLineContact, ContinuousAtOnset) {
  const SlicedLineContact c =
      make_sliced_line_contact(e_star, circular(14e-3, 0.8e-3, 1.5, 2e-3), 25, 0.5, 1e-4);
  const double middle_drop = *std::min_element(c.law.slice_drop.begin(), c.law.slice_drop.end());
  EXPECT_EQ(evaluate_tilted(c, middle_drop, 0.0, 0.1, 0.0).force, 0.0);
  EXPECT_EQ(evaluate_tilted(c, middle_drop - 1e-12, 0.0, 1.0, 0.0).force, 0.0);
  // The flat middle (2 mm) holds the three middle slices (width 0.56 mm): they touch together.
  ASSERT_EQ(std::count(c.law.slice_drop.begin(), c.law.slice_drop.end(), middle_drop), 3);
  const double k_j = 3 * c.law.slice_stiffness[12];
  for (const double d : {1e-12, 1e-14}) {
    const TiltedLineForce f = evaluate_tilted(c, middle_drop + d, 0.0, 0.1, 0.0);
    EXPECT_GT(f.force, 0.0);
    EXPECT_LE(f.force, k_j * std::pow(d, n_exp) * (1 + 0.5 * 0.1) * (1 + 1e-6));
    EXPECT_LE(f.d_force[0], 2 * n_exp * k_j * std::pow(d, n_exp - 1));
  }
}

TEST(SlicedLineContact, ValidityAndBadInput) {
  const SlicedLineContact c = make_sliced_line_contact(e_star, straight(10e-3), 10, 0.5, 1e-5);
  EXPECT_TRUE(evaluate_tilted(c, 0.9e-5, 0.0, 0.0, 0.0).valid);
  // The middle is within the limit, a tilted end is not.
  EXPECT_FALSE(evaluate_tilted(c, 0.9e-5, 1e-3, 0.0, 0.0).valid);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int v = 0; v < 4; ++v) {
    std::array<double, 4> x = {1e-6, 0, 0, 0};
    x[static_cast<std::size_t>(v)] = nan;
    const TiltedLineForce f = evaluate_tilted(c, x[0], x[1], x[2], x[3]);
    EXPECT_FALSE(f.valid);
    EXPECT_EQ(f.force, 0.0);
  }
  // A fast separation: no tension, the elastic work dissipated.
  const TiltedLineForce apart = evaluate_tilted(c, 1e-6, 0.0, -10.0, 0.0);
  EXPECT_EQ(apart.force, 0.0);
  EXPECT_NEAR(apart.damping_power, apart.elastic_force * 10.0, 1e-12 * apart.elastic_force * 10.0);
}

}  // namespace
}  // namespace raceway::contact
