// The ribs of a spatial cylindrical roller bearing carry its axial load (contact/segments/
// roller_flange_segment.hpp in spatial_roller_model.cpp): at rest, preloaded radially (10 um of
// negative clearance), an axial load on the inner ring is carried by the inner ring's rib on the
// far side into the rollers' ends and out through the outer ring's opposite rib. Settled (the
// rollers' friction on the races, a tanh curve, carries nothing without sliding), the ribs' axial
// forces on each ring add up to the load; every roller takes its share (Z equal rollers, no gravity);
// the races' slices carry no axial force. NJ takes an inner-ring load along +z on its single inner
// rib (-z side), NUP also one along -z on its other inner rib. The end play is taken up: the inner
// ring moves by the roller_end_clearance and more.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "io/scene/scene_parser.hpp"
#include "scheduler/executor.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/segment_record.hpp"
#include "solver/bearing/startup.hpp"
#include "solver/numerics/integrator.hpp"

namespace raceway::bearing {
namespace {

std::string scene_text(const std::string& ribs, const std::string& fz) {
  return R"(
[scene]
name = "ribs at rest"
model = "spatial"
end_time = "0.01 s"
output_interval = "1 ms"
[bearing]
type = "cylindrical_roller"
rolling_elements = 13
roller_diameter = "9.2 mm"
roller_length = "10 mm"
pitch_diameter = "45.74 mm"
radial_clearance = "-10 um"
inner_bore_diameter = "30 mm"
outer_outside_diameter = "62 mm"
ribs = ")" + ribs + R"("
corner_radius = "0.5 mm"
roller_end_clearance = "50 um"
[cage]
guidance = "rolling_element"
pocket_clearance = "0.2 mm"
[inner_ring]
motion = "driven"
speed = "0 rpm"
translation = "fixed"
axial = "free"
load = { fz = ")" + fz + R"(" }
[outer_ring]
motion = "fixed"
)";
}

struct AxialForces {
  double inner_ribs = 0, outer_ribs = 0, slices = 0;  ///< N along z, on the rings
  double smallest_share = 1e300, largest_share = 0;    ///< N, one roller's inner-rib force along z
  double inner_ring_z = 0;                             ///< m
};

AxialForces settled(const std::string& ribs, const std::string& fz) {
  const scene::Scene scene = scene::parse_scene(scene_text(ribs, fz), ribs + ".toml");
  const Model m = build_model(scene);
  scheduler::SerialExecutor executor;
  Equations eq(m, executor);
  numerics::Integrator integrator(eq, scene.solver, 0.0, initial_state(m, 0.0).state);
  std::vector<double> z, zdot(static_cast<std::size_t>(m.state_size));
  integrator.advance_to(0.01, z);  // settled by 5 ms
  eq.rhs(0.01, z.data(), zdot.data());
  AxialForces a;
  std::vector<double> share(static_cast<std::size_t>(m.element_count), 0.0);
  const auto& records = eq.segment_records();
  for (std::size_t s = 0; s < m.segments.size(); ++s) {
    const Segment& seg = m.segments[s];
    const double on_ring = records[s * SegmentRecord::size + SegmentRecord::on_a + 2];  // force z on A, the ring
    if (seg.kind == SegmentKind::roller_flange) {
      (seg.body_a == m.inner_ring ? a.inner_ribs : a.outer_ribs) += on_ring;
      if (seg.body_a == m.inner_ring) share[static_cast<std::size_t>(seg.element)] -= on_ring;
    } else if (seg.kind == SegmentKind::roller_inner_slice || seg.kind == SegmentKind::roller_outer_slice) {
      a.slices += std::abs(on_ring);
    }
  }
  for (const double q : share)
    a.smallest_share = std::min(a.smallest_share, std::abs(q)), a.largest_share = std::max(a.largest_share, std::abs(q));
  a.inner_ring_z = z[static_cast<std::size_t>(m.bodies[static_cast<std::size_t>(m.inner_ring)].slot[sz])];
  std::printf("[ ribs ] %s, inner-ring load %s: inner ribs %.4f N, outer ribs %.4f N, slices |%.3g| N, one roller's "
              "inner rib %.4f .. %.4f N, inner ring at z = %.2f um\n",
              ribs.c_str(), fz.c_str(), a.inner_ribs, a.outer_ribs, a.slices, a.smallest_share, a.largest_share,
              1e6 * a.inner_ring_z);
  return a;
}

void expect_carried(const AxialForces& a, double load) {
  EXPECT_NEAR(a.inner_ribs, -load, 1e-3 * std::abs(load));   // the inner ring's rib pushes it back
  EXPECT_NEAR(a.outer_ribs, load, 1e-3 * std::abs(load));    // ... and the outer ring takes the load
  EXPECT_LT(a.slices, 1e-3 * std::abs(load));                 // nothing through the races
  EXPECT_NEAR(a.smallest_share, std::abs(load) / 13, 1e-2 * std::abs(load) / 13);
  EXPECT_NEAR(a.largest_share, std::abs(load) / 13, 1e-2 * std::abs(load) / 13);
  EXPECT_GT(std::abs(a.inner_ring_z), 50e-6);                 // the end play taken up
  EXPECT_LT(std::abs(a.inner_ring_z), 80e-6);                 // ... and a few um of Hertz deflection
  EXPECT_GT(a.inner_ring_z * load, 0.0);                      // along the load
}

TEST(SpatialRollerRibs, NjCarriesAnInnerRingLoadAlongPlusZ) { expect_carried(settled("NJ", "200 N"), 200.0); }

TEST(SpatialRollerRibs, NupCarriesBothDirections) {
  expect_carried(settled("NUP", "200 N"), 200.0);
  expect_carried(settled("NUP", "-300 N"), -300.0);
}

}  // namespace
}  // namespace raceway::bearing
