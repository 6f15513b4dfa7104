// The lubricated segments of seed 003 (contact/segments/roller_segments.hpp): the roller-race
// contact with its EHD film and the roller-cage bar with its hydrodynamic film. The conformance
// checks of a segment for them: no force beyond the film's reach and a continuous onset there,
// action = reaction with the angular momentum balanced, the normal force the law's, traction
// against the sliding, the squeeze force of a roller hitting a bar against its closed form, and
// the segment's forward-difference Jacobian (as the equations form it) against central differences.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "contact/laws/lubricated_line_contact.hpp"
#include "contact/segments/segment_jacobian.hpp"
#include "roller_cases.hpp"

namespace raceway::contact::test::roller {
namespace {

constexpr double viscosity = 0.02, pressure_viscosity = 2e-8;
constexpr double cutoff = 0.02 * seed002::roller_radius;

SegmentCase case_of(Kind kind, bool internal, int side = +1) {
  for (const SegmentCase& c : all_segment_cases())
    if (c.kind == kind && c.internal == internal && (kind != Kind::bar || c.side == side)) return c;
  throw std::logic_error("no such case");
}

/// The race segment of case c with an EHD film (as solver/bearing/roller_model.cpp builds it).
AnySegment ehd_race(const SegmentCase& c, bool traction) {
  AnySegment any = make_segment(c);
  auto& seg = std::get<RollerRaceSegment>(any);
  EhdRaceFilm film;
  film.law.film = {viscosity, pressure_viscosity,
                   reduced_modulus(c.youngs_a, c.poisson_a, c.youngs_b, c.poisson_b),
                   1.0 / (1.0 / seg.roller_radius + (seg.internal ? -1.0 : 1.0) / seg.race_radius), c.length, cutoff};
  film.law.stiffness = seg.law.stiffness;
  film.law.max_approach = seg.law.max_approach;
  film.damping_factor = seg.law.damping_factor;
  film.traction = traction;
  film.couette = {0.06, 0.05, 0.05};
  seg.ehd = film;
  return any;
}

AnySegment film_bar(const SegmentCase& c) {
  AnySegment any = make_segment(c);
  auto& seg = std::get<CageBarSegment>(any);
  HydrodynamicLineLaw film;
  film.film = {viscosity, 0, reduced_modulus(c.youngs_a, c.poisson_a, c.youngs_b, c.poisson_b), seg.roller_radius,
               c.length, cutoff};
  film.film_floor = 0.2e-6;
  film.dry = seg.law;
  seg.film = film;
  return any;
}

std::vector<std::pair<SegmentCase, AnySegment>> lubricated_segments() {
  std::vector<std::pair<SegmentCase, AnySegment>> out;
  for (const bool internal : {false, true}) {
    const SegmentCase c = case_of(Kind::race, internal);
    out.emplace_back(c, ehd_race(c, true));
    out.emplace_back(c, ehd_race(c, false));
  }
  for (const int side : {+1, -1}) {
    const SegmentCase c = case_of(Kind::bar, false, side);
    out.emplace_back(c, film_bar(c));
  }
  return out;
}

/// Rolling motions: the roller spins at 400 rad/s (a few m/s at its surface) against a slow ring or cage.
std::vector<Motion> rolling_motions() {
  return {{moving(0, 0, 0), moving(0, 0, -400.0)},
          {moving(0.01, -0.02, 50.0), moving(0.3, -0.2, -380.0)},
          {moving(0, 0, 100.0), moving(0, 0, 300.0)}};
}

TEST(LubricatedSegments, NothingBeyondTheFilmAndContinuousOnset) {
  for (const auto& [c, seg] : lubricated_segments()) {
    SCOPED_TRACE(c.name);
    for (const Motion& m : rolling_motions()) {
      for (const double beyond : {1.0001 * cutoff, 2 * cutoff, 5e-4}) {
        const SegmentResult r = evaluate_any(seg, place(c, seg, m.first, m.second, -beyond, 0.4).a,
                                             place(c, seg, m.first, m.second, -beyond, 0.4).b);
        EXPECT_TRUE(r.valid);
        EXPECT_EQ(wrench_norm(r), 0.0) << "gap " << beyond;
      }
      // Inside the reach the force rises from zero with a vanishing slope (C1 window).
      const auto at = [&](double gap) {
        const Placement p = place(c, seg, m.first, m.second, -gap, 0.4);
        return evaluate_any(seg, p.a, p.b).diagnostics.normal_force;
      };
      const double half = at(0.5 * cutoff);
      for (const double below : {1e-8, 1e-9}) EXPECT_LT(at(cutoff - below), 30 * half * std::pow(below / cutoff, 2));
    }
  }
}

TEST(LubricatedSegments, ActionEqualsReactionAndTractionOpposesSliding) {
  for (const auto& [c, seg] : lubricated_segments()) {
    SCOPED_TRACE(c.name);
    for (const Motion& m : rolling_motions())
      for (const double approach : {-20e-6, -1e-6, 0.0, 2e-6, 10e-6})
        for (const double dir : directions) {
          const Placement p = place(c, seg, m.first, m.second, approach, dir);
          const SegmentResult r = evaluate_any(seg, p.a, p.b);
          ASSERT_TRUE(r.valid);
          const double scale = wrench_norm(r) + 1e-12;
          EXPECT_NEAR(r.on_a.fx, -r.on_b.fx, 1e-12 * scale);
          EXPECT_NEAR(r.on_a.fy, -r.on_b.fy, 1e-12 * scale);
          // Angular momentum about the origin: moments plus r x F of both bodies.
          const double total = r.on_a.mz + r.on_b.mz + (p.a.x * r.on_a.fy - p.a.y * r.on_a.fx) +
                               (p.b.x * r.on_b.fy - p.b.y * r.on_b.fx);
          EXPECT_NEAR(total, 0.0, 1e-11 * scale);
          // The normal force pushes B along the test's normal, and the power lost is not negative.
          const double along = r.on_b.fx * p.normal_on_b.x() + r.on_b.fy * p.normal_on_b.y();
          EXPECT_NEAR(along, r.diagnostics.normal_force, 1e-9 * scale);
          EXPECT_GE(r.diagnostics.normal_force, 0.0);
          EXPECT_GE(r.diagnostics.power_loss, -1e-12 * scale);
          // Couette friction, viscous drag or the curve: never along the sliding (the Poiseuille force
          // of EHD traction resists the rolling instead: its segments are left out here).
          const auto* race = std::get_if<RollerRaceSegment>(&seg);
          const bool poiseuille = race && race->ehd && race->ehd->traction;
          if (!poiseuille && std::abs(r.diagnostics.slip_velocity) > 0.1) {
            EXPECT_LE(r.diagnostics.traction_force * r.diagnostics.slip_velocity, 1e-9 * scale) << approach;
          }
        }
  }
}

// A roller hitting a bar at 0.3 m/s, no rolling: the squeeze film's closed form through the segment.
TEST(LubricatedSegments, SqueezeForceOfARollerHittingABar) {
  const SegmentCase c = case_of(Kind::bar, false, +1);
  const AnySegment seg = film_bar(c);
  const double speed = 0.3;
  for (const double gap : {2e-6, 10e-6, 30e-6}) {
    Placement p = place(c, seg, moving(0, 0, 0), moving(0, 0, 0), -gap, 0.7);
    p.b.vx = speed * p.normal_on_b.x() * -1.0;  // towards the bar: against the normal on the roller
    p.b.vy = speed * p.normal_on_b.y() * -1.0;
    const SegmentResult r = evaluate_any(seg, p.a, p.b);
    const double h = 0.5 * (gap + 0.2e-6 + std::hypot(gap - 0.2e-6, 0.2e-6));  // the law's floored film
    const double closed = c.length * 3 * std::sqrt(2.0) * std::numbers::pi * viscosity *
                          std::pow(seed002::roller_radius, 1.5) * speed / std::pow(h, 1.5);
    const double window = gap <= 0.5 * cutoff ? 1.0 : 0.0;  // the gaps here are inside the full film
    ASSERT_EQ(window, 1.0);
    EXPECT_NEAR(r.diagnostics.normal_force, closed, 1e-9 * closed) << "gap " << gap;
    std::printf("[ squeeze ] gap %5.1f um at %.1f m/s: %.4g N\n", gap * 1e6, speed, r.diagnostics.normal_force);
  }
}

// A lubricated bar's gap alone (bar_approach, what the pocket tolerance asks) is its evaluation's
// approach bit for bit, in the film and in dry contact, approaching and receding.
TEST(LubricatedSegments, BarApproachAloneIsTheEvaluatedOne) {
  for (const int side : {+1, -1}) {
    const SegmentCase c = case_of(Kind::bar, false, side);
    const AnySegment seg = film_bar(c);
    const CageBarSegment& law = std::get<CageBarSegment>(seg);
    for (const double approach : {-30e-6, -2e-6, 1e-7, 5e-6})
      for (const double speed : {-0.3, 0.3}) {
        Placement p = place(c, seg, moving(0.01, 0, 40), moving(0, 0, -300), approach, -1.9, 1e-4);
        p.b.vx = speed * p.normal_on_b.x(), p.b.vy = speed * p.normal_on_b.y();
        const double alone = bar_approach(law, p.a, p.b.x, p.b.y);
        EXPECT_EQ(std::bit_cast<std::uint64_t>(alone),
                  std::bit_cast<std::uint64_t>(evaluate(law, p.a, p.b).diagnostics.approach));
      }
  }
}

// The forward-difference block the equations assemble (contact/segments/segment_jacobian.hpp, steps
// as solver/bearing/equations.cpp takes them) against central differences of the same segment.
TEST(LubricatedSegments, JacobianAgainstCentralDifferences) {
  for (const auto& [c, seg] : lubricated_segments()) {
    SCOPED_TRACE(c.name);
    for (const double approach : {-5e-6, 3e-6, 10e-6}) {
      const Motion m = rolling_motions()[1];
      const Placement p = place(c, seg, m.first, m.second, approach, 0.9);
      PlanarJacobian forward{};
      JacobianShape<PlanarKinematics>::Steps steps{};
      for (int side = 0; side < 2; ++side) {
        steps[6 * side + px] = steps[6 * side + py] = 2e-12;
        steps[6 * side + theta] = 1e-10;
        steps[6 * side + vx] = steps[6 * side + vy] = 1e-7;
        steps[6 * side + omega] = 1e-5;
      }
      const SegmentResult base = evaluate_any(seg, p.a, p.b);
      std::visit([&](const auto& s) { segment_jacobian(s, p.a, p.b, base, steps, forward); }, seg);
      for (int j = 0; j < 12; ++j) {
        const double h = 100 * steps[static_cast<std::size_t>(j)];  // central, larger step
        auto shifted = [&](double d) {
          PlanarKinematics a = p.a, b = p.b;
          JacobianShape<PlanarKinematics>::perturb(j < 6 ? a : b, j % 6, d);
          return JacobianShape<PlanarKinematics>::rows(evaluate_any(seg, a, b));
        };
        const auto plus = shifted(h), minus = shifted(-h);
        double column = 0, error = 0;
        for (int i = 0; i < 6; ++i) {
          const double central = (plus[static_cast<std::size_t>(i)] - minus[static_cast<std::size_t>(i)]) / (2 * h);
          column += std::abs(central);
          error += std::abs(central - forward[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)]);
        }
        EXPECT_LE(error, 1e-3 * column + 1e-6) << "column " << j << " approach " << approach;
      }
    }
  }
}

}  // namespace
}  // namespace raceway::contact::test::roller
