// The EHD film on the spatial roller model's race slices (contact/segments/roller_slice_segment.hpp).
// An aligned straight roller whose slices all see the same gap is the planar line contact
// (roller_segments.hpp) cut into N pieces: each slice's film is the planar film of a contact as long
// as the slice is wide and as stiff as its share, so the slices' forces summed over the roller give
// the planar contact's normal force, traction (Couette and Poiseuille) and film thickness. Checked on
// both races, apart and overlapping, in pure rolling and with sliding, with and without EHD
// traction. The planar contact point lies midway between the surfaces and the slices' on the race, so
// the entrainment speeds differ by (approach / 2) / race_radius and the slips by the roller's spin
// times that half gap: normal forces within 1e-3, tractions within 1e-3 of themselves and 2.5e-3 of
// the normal force (near pure rolling, where that slip difference is all the slip).
// The slice's forward-difference Jacobian (as the equations form it) is checked against central
// differences, with the film and its traction, as the other lubricated segments are.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "contact/laws/lubricated_line_contact.hpp"
#include "contact/segments/roller_slice_segment.hpp"
#include "contact/segments/segment_jacobian.hpp"

namespace raceway::contact {
namespace {

constexpr double viscosity = 0.04, pressure_viscosity = 2e-8;
constexpr double length = 12e-3, roller_radius = 6e-3, inner_race = 30e-3, outer_race = 42e-3;
constexpr int slices = 24;
const double e_star = reduced_modulus(2.08e11, 0.3, 2.08e11, 0.3);

LineFilm film_of(double film_length, double race_radius, bool outer) {
  LineFilm f;
  f.viscosity = viscosity;
  f.pressure_viscosity = pressure_viscosity;
  f.reduced_modulus = e_star;
  f.reduced_radius = 1.0 / (1.0 / roller_radius + (outer ? -1.0 : 1.0) / race_radius);
  f.length = film_length;
  f.cutoff = 0.02 * roller_radius;
  return f;
}

EhdRaceFilm race_film(const LineFilm& f, double stiffness, bool traction) {
  EhdRaceFilm film;
  film.law = {f, stiffness, 1e-4};
  film.damping_factor = 0.5;
  film.traction = traction;
  film.couette = {0.06, 0.05, 0.05};
  return film;
}

RollerRaceSegment planar_race(bool outer, bool traction) {
  const double race = outer ? outer_race : inner_race;
  RollerRaceSegment s;
  s.race_radius = race;
  s.roller_radius = roller_radius;
  s.internal = outer;
  s.law = make_line_contact_law(e_star, length, 1, 0.0, 0.5, 1e-4);
  s.traction = {0.1, 0.05};
  s.ehd = race_film(film_of(length, race, outer), s.law.stiffness, traction);
  return s;
}

std::vector<RollerSliceSegment> slice_race(bool outer, bool traction) {
  const SlicedLineContact sliced = make_sliced_line_contact(e_star, RollerProfile{.length = length}, slices, 0.5, 1e-4);
  const double race = outer ? outer_race : inner_race;
  std::vector<RollerSliceSegment> out;
  for (int j = 0; j < slices; ++j) {
    RollerSliceSegment s = make_roller_slice_segment(sliced, static_cast<std::size_t>(j), race, roller_radius, outer,
                                                     TractionCurve{0.1, 0.05});
    LineFilm f = film_of(sliced.slice_width, race, outer);
    f.reduced_radius = 0;  // the segment's radii give it
    s.ehd = race_film(f, s.stiffness, traction);
    out.push_back(s);
  }
  return out;
}

/// The roller at azimuth 0.3 on a race (ring turning at `ring_spin`), orbiting at `orbit` and spinning
/// at `spin` about its axis (parallel to the ring's), at `approach` from the race.
struct Setting {
  double approach, ring_spin, orbit, spin, approach_rate;
};

void place(const Setting& s, bool outer, PlanarKinematics& ring, PlanarKinematics& roller, SpatialKinematics& ring3,
           SpatialKinematics& roller3) {
  const double race = outer ? outer_race : inner_race, azimuth = 0.3;
  const double d = outer ? race - roller_radius + s.approach : race + roller_radius - s.approach;
  const double c = std::cos(azimuth), sn = std::sin(azimuth);
  const double rate = (outer ? 1.0 : -1.0) * s.approach_rate;  // d(d)/dt for the approach rate asked
  ring = {0, 0, 0, 0, 0, s.ring_spin};
  roller = {d * c, d * sn, 0, rate * c - s.orbit * d * sn, rate * sn + s.orbit * d * c, s.spin};
  ring3.angular_velocity = Vec3(0, 0, s.ring_spin);
  roller3.position = Vec3(roller.x, roller.y, 0);
  roller3.velocity = Vec3(roller.vx, roller.vy, 0);
  roller3.angular_velocity = Vec3(0, 0, s.spin);
}

TEST(LubricatedSlices, SlicesOfAStraightRollerSumToThePlanarFilm) {
  // Inner race turning at 300 rad/s, the roller rolling (orbit from the rolling condition) or sliding.
  const double w_i = 300.0, rolling_orbit = w_i * inner_race / (2 * (inner_race + roller_radius));
  const double rolling_spin = -(w_i - rolling_orbit) * inner_race / roller_radius + rolling_orbit;
  double worst = 0;
  for (const bool outer : {false, true})
    for (const bool traction : {true, false})
      for (const Setting s : {Setting{-2e-6, w_i, rolling_orbit, rolling_spin, 0.0},
                              Setting{1e-6, w_i, rolling_orbit, rolling_spin, 0.0},
                              Setting{4e-6, w_i, rolling_orbit, 0.97 * rolling_spin, 0.0},
                              Setting{3e-6, 0.0, rolling_orbit, 0.9 * rolling_spin, 2e-4}}) {
        PlanarKinematics ring, roller;
        SpatialKinematics ring3, roller3;
        place(s, outer, ring, roller, ring3, roller3);
        const SegmentResult planar = evaluate(planar_race(outer, traction), ring, roller);
        ASSERT_TRUE(planar.valid);
        ASSERT_GT(planar.diagnostics.normal_force, 5.0);  // a loaded film
        Vec3 force = Vec3::Zero(), moment = Vec3::Zero();
        double normal = 0, film = 0;
        for (const RollerSliceSegment& seg : slice_race(outer, traction)) {
          const SpatialSegmentResult r = evaluate(seg, ring3, roller3);
          ASSERT_TRUE(r.valid);
          force += r.on_b.force;
          moment += r.on_b.moment;
          normal += r.diagnostics.normal_force;
          film += r.diagnostics.film_thickness / slices;
        }
        const double scale = std::hypot(planar.on_b.fx, planar.on_b.fy);
        const double normal_planar = planar.diagnostics.normal_force;
        const double tangential = std::abs(planar.diagnostics.traction_force);
        const double error = std::hypot(force.x() - planar.on_b.fx, force.y() - planar.on_b.fy) / scale;
        worst = std::max(worst, error);
        EXPECT_NEAR(normal, normal_planar, 1e-3 * normal_planar);
        EXPECT_LT(error, 2.5e-3);
        // The traction alone (Couette, Poiseuille or the curve), through the roller's moment: within
        // 1e-3 of it, and 2.5e-3 of the normal force near pure rolling, where the two contact points'
        // slips differ by the roller's spin times half the gap (some 1e-3 m/s: the curve's slope
        // 0.1 / (0.05 m/s) makes that 1.5e-3 N per N).
        EXPECT_NEAR(moment.z() / roller_radius, planar.on_b.mz / roller_radius, 1e-3 * tangential + 2.5e-3 * normal_planar);
        EXPECT_GT(film, 0.05e-6);
        EXPECT_NEAR(std::abs(force.z()), 0.0, 1e-9 * scale);
      }
  std::printf("[ slices ] %d slices against the planar EHD line contact: force within %.2g\n", slices, worst);
}

/// The slice's film thickness is Moes' for its share of the load: the inverse of its own law.
TEST(LubricatedSlices, SliceFilmCarriesItsShareOfTheLoad) {
  const std::vector<RollerSliceSegment> race = slice_race(false, true);
  PlanarKinematics ring, roller;
  SpatialKinematics ring3, roller3;
  place(Setting{2e-6, 300.0, 100.0, -1000.0, 0.0}, false, ring, roller, ring3, roller3);
  const RollerSliceSegment& seg = race[slices / 2];
  const SpatialSegmentResult r = evaluate(seg, ring3, roller3);
  ASSERT_TRUE(r.valid);
  // Entrainment, relative to the contact point, which orbits at 100 rad/s: the ring's surface at
  // (300 - 100) r_i, the roller's at (100 - (-1000)) r (to 1e-5: the approach shortens its lever).
  const double u_ring = (300.0 - 100.0) * inner_race;
  const double u_roller = (100.0 - -1000.0) * roller_radius;
  const double u_m = 0.5 * (u_ring + u_roller);
  LineFilm f = film_of(length / slices, inner_race, false);
  const double h = film_thickness(f, r.diagnostics.normal_force / f.length, u_m);
  EXPECT_NEAR(r.diagnostics.film_thickness, h, 2e-3 * h);
}

// The forward-difference block the equations assemble against central differences of the same
// slice, with the film (apart, touching and overlapping) and with EHD traction.
TEST(LubricatedSlices, JacobianAgainstCentralDifferences) {
  using Shape = JacobianShape<SpatialKinematics>;
  // Forward steps as the spatial segments' conformance suite takes them; the central reference ten
  // times larger. Round-off floor: 1e-12 |F| / step (the film's Newton solve converges to 1e-15 of h).
  SpatialSteps steps{};
  for (int side = 0; side < 2; ++side)
    for (int k = 0; k < 3; ++k) {
      steps[12 * side + k] = 1e-10;
      steps[12 * side + 3 + k] = 1e-9;
      steps[12 * side + 6 + k] = 1e-7;
      steps[12 * side + 9 + k] = 1e-6;
    }
  for (const bool outer : {false, true}) {
    const RollerSliceSegment seg = slice_race(outer, true)[3];
    for (const double approach : {-3e-6, 2e-6, 8e-6}) {
      PlanarKinematics ring, roller;
      SpatialKinematics a, b;
      place(Setting{approach, 300.0, 100.0, -900.0, 0.0}, outer, ring, roller, a, b);
      b.rotation = Eigen::AngleAxisd(2e-4, Vec3(1, 1, 0).normalized()).toRotationMatrix();  // tilted a little
      b.velocity += Vec3(0.01, 0.0, 0.02);
      const SpatialSegmentResult base = evaluate(seg, a, b);
      ASSERT_TRUE(base.valid);
      ASSERT_GT(base.diagnostics.normal_force, 0.0);
      SpatialJacobian forward{};
      ASSERT_TRUE(segment_jacobian(seg, a, b, base, steps, forward));
      for (int j = 0; j < 24; ++j) {
        const double h = 10 * steps[static_cast<std::size_t>(j)];
        const double floor = 1e-12 * base.on_b.force.norm() / steps[static_cast<std::size_t>(j)];
        auto shifted = [&](double d) {
          SpatialKinematics pa = a, pb = b;
          Shape::perturb(j < 12 ? pa : pb, j % 12, d);
          return Shape::rows(evaluate(seg, pa, pb));
        };
        const auto plus = shifted(h), minus = shifted(-h);
        double column = 0, error = 0;
        for (std::size_t i = 0; i < plus.size(); ++i) {
          const double central = (plus[i] - minus[i]) / (2 * h);
          column += std::abs(central);
          error += std::abs(central - forward[i][static_cast<std::size_t>(j)]);
        }
        EXPECT_LE(error, 1e-3 * column + 12 * floor) << "column " << j << " approach " << approach << " outer " << outer;
      }
    }
  }
}

}  // namespace
}  // namespace raceway::contact
