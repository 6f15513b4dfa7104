// A spatial cylindrical roller bearing at rest, preloaded (10 um of negative clearance), its outer
// ring misaligned by 1 mrad about x, crowned rollers (circular crown of 1 m beyond a 4 mm straight
// middle): the slice loads of the dynamic model, settled, against a quasi-static slice solution
// written here: each roller in its radial plane, its radial place and tilt found by Newton's method
// on the balance of its inner and outer slice forces and of their moments, the approaches from the
// exact geometry of the slice centres (the misaligned ring's frame by its rotation matrix).
//
// Left out of the quasi-static solution, and why they are small: the rollers' axial places (set by
// the ribs, a few um: they move an outer approach by z gamma, some nm), the tilt of the misaligned
// race's normal (its axial component gamma F carries a moment gamma F R, 0.1 % of the slices'), the
// rib forces (under 1 N against slice loads of 60 N). Measured: the largest difference 0.036 % of
// the largest slice load.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "contact/laws/line_contact.hpp"
#include "contact/laws/roller_profile.hpp"
#include "io/scene/scene_parser.hpp"
#include "scheduler/executor.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/startup.hpp"
#include "solver/numerics/integrator.hpp"

namespace raceway::bearing {
namespace {

using contact::Mat3;
using contact::Vec3;

constexpr const char* kScene = R"(
[scene]
name = "misaligned crowned rollers at rest"
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
roller_profile = "circular"
crown_radius = "1 m"
flat_length = "4 mm"
roller_end = "spherical"
[cage]
guidance = "rolling_element"
pocket_clearance = "0.2 mm"
[inner_ring]
motion = "driven"
speed = "0 rpm"
translation = "fixed"
axial = "fixed"
[outer_ring]
motion = "fixed"
tilt = "prescribed"
misalignment = { x = "1 mrad" }
[contact.roller_race]
slices = 20
)";

constexpr double gamma = 1e-3, dm = 45.74e-3, D = 9.2e-3, l = 10e-3, clearance = -10e-6;
constexpr int slices = 20;

/// The quasi-static slice loads of a roller at azimuth psi: inner, then outer, per slice.
struct SliceLoads {
  std::vector<double> inner, outer;
};
SliceLoads quasi_static(double psi, double e_star) {
  const contact::RollerProfile crown{.kind = contact::RollerProfileKind::circular, .length = l, .corner_radius = 0,
                                     .crown_radius = 1.0, .flat_length = 4e-3};
  const double k = contact::palmgren_stiffness(e_star, l) / slices, r = 0.5 * D;
  const double inner_race = 0.5 * (dm - D - 0.5 * clearance), outer_race = 0.5 * (dm + D + 0.5 * clearance);
  std::vector<double> x(slices), drop(slices);
  for (int j = 0; j < slices; ++j) {
    x[j] = -0.5 * l + (j + 0.5) * l / slices;
    drop[j] = contact::profile_drop(crown, x[j]);
  }
  const Vec3 e_r(std::cos(psi), std::sin(psi), 0.0);
  const Mat3 ring = Eigen::AngleAxisd(gamma, Vec3::UnitX()).toRotationMatrix();  // outer ring: Rx(gamma)
  auto loads = [&](double rho, double tilt) {
    SliceLoads s;
    const Vec3 axis = (Vec3::UnitZ() + tilt * e_r).normalized();
    for (int j = 0; j < slices; ++j) {
      const Vec3 centre = rho * e_r + x[j] * axis;
      const Vec3 local = ring.transpose() * centre;
      const double inner = inner_race + r - drop[j] - centre.head<2>().norm();
      const double outer = local.head<2>().norm() - (outer_race - r + drop[j]);
      s.inner.push_back(inner > 0 ? k * std::pow(inner, contact::palmgren_exponent) : 0.0);
      s.outer.push_back(outer > 0 ? k * std::pow(outer, contact::palmgren_exponent) : 0.0);
    }
    return s;
  };
  auto residual = [&](const Eigen::Vector2d& u) {
    const SliceLoads s = loads(u[0], u[1]);
    Eigen::Vector2d f = Eigen::Vector2d::Zero();
    for (int j = 0; j < slices; ++j) f[0] += s.inner[j] - s.outer[j], f[1] += (s.inner[j] - s.outer[j]) * x[j];
    return f;
  };
  Eigen::Vector2d u(0.5 * dm, 0.0);
  for (int it = 0; it < 50; ++it) {
    const Eigen::Vector2d f = residual(u);
    Eigen::Matrix2d jac;
    for (int c = 0; c < 2; ++c) {
      Eigen::Vector2d up = u;
      const double h = c == 0 ? 1e-10 : 1e-8;
      up[c] += h;
      jac.col(c) = (residual(up) - f) / h;
    }
    const Eigen::Vector2d step = jac.fullPivLu().solve(-f);
    u += step;
    if (std::abs(step[0]) < 1e-15 && std::abs(step[1]) < 1e-13) break;
  }
  return loads(u[0], u[1]);
}

TEST(SpatialRollerMisalignment, SliceLoadsAgreeWithAQuasiStaticSliceSolution) {
  const scene::Scene scene = scene::parse_scene(kScene, "misaligned.toml");
  const Model m = build_model(scene);
  scheduler::SerialExecutor executor;
  Equations eq(m, executor);
  numerics::Integrator integrator(eq, scene.solver, 0.0, initial_state(m, 0.0).state);
  std::vector<double> z, zdot(static_cast<std::size_t>(m.state_size));
  integrator.advance_to(10e-3, z);  // settled by 5 ms: the contacts' modes are damped out
  eq.rhs(10e-3, z.data(), zdot.data());
  const auto& steel = scene.material(scene.bearing.roller_material);
  const double e_star = contact::reduced_modulus(steel.youngs_modulus, steel.poisson_ratio, steel.youngs_modulus,
                                                 steel.poisson_ratio);
  double largest = 0, worst = 0;
  std::vector<double> model_inner(static_cast<std::size_t>(m.element_count * slices)), model_outer(model_inner.size());
  for (std::size_t s = 0; s < m.segments.size(); ++s) {
    const Segment& seg = m.segments[s];
    if (seg.kind != SegmentKind::roller_inner_slice && seg.kind != SegmentKind::roller_outer_slice) continue;
    auto& into = seg.kind == SegmentKind::roller_inner_slice ? model_inner : model_outer;
    const auto& law = m.law<contact::RollerSliceSegment>(seg);
    const int j = static_cast<int>(std::lround((law.position + 0.5 * l) * slices / l - 0.5));
    into[static_cast<std::size_t>(seg.element * slices + j)] = eq.diagnostic(s, normal_force_field);
  }
  for (int k = 0; k < m.element_count; ++k) {
    const Body& roller = m.bodies[static_cast<std::size_t>(m.first_element + k)];
    const double psi = std::atan2(z[static_cast<std::size_t>(roller.slot[sy])], z[static_cast<std::size_t>(roller.slot[sx])]);
    const SliceLoads qs = quasi_static(psi, e_star);
    for (int j = 0; j < slices; ++j) {
      const std::size_t i = static_cast<std::size_t>(k * slices + j);
      largest = std::max({largest, qs.inner[static_cast<std::size_t>(j)], qs.outer[static_cast<std::size_t>(j)]});
      worst = std::max({worst, std::abs(model_inner[i] - qs.inner[static_cast<std::size_t>(j)]),
                        std::abs(model_outer[i] - qs.outer[static_cast<std::size_t>(j)])});
    }
  }
  std::printf("[ misalignment ] 1 mrad, crowned rollers: largest slice load %.2f N, largest difference from the "
              "quasi-static slice solution %.3g %% of it\n",
              largest, 100 * worst / largest);
  EXPECT_GT(largest, 30.0);
  EXPECT_LT(worst, 0.02 * largest);
}

// Without the misalignment the same solution gives symmetric slice loads; with it, the tilt loads
// one end: the quasi-static solution itself sees the misalignment (a check that the comparison
// above can fail).
TEST(SpatialRollerMisalignment, TheQuasiStaticSolutionSeesTheMisalignment) {
  const SliceLoads at_minus_90 = quasi_static(-0.5 * std::numbers::pi, 2.25e11 / 2 / (1 - 0.09));
  const SliceLoads at_0 = quasi_static(0.0, 2.25e11 / 2 / (1 - 0.09));
  EXPECT_NEAR(at_0.inner.front(), at_0.inner.back(), 1e-6 * at_0.inner[slices / 2]);
  EXPECT_GT(std::abs(at_minus_90.inner.front() - at_minus_90.inner.back()), 0.2 * at_minus_90.inner[slices / 2]);
}

}  // namespace
}  // namespace raceway::bearing
