// The equation-level test state of the spatial ball-bearing tests: a bearing with every kind of
// contact closed (ball-groove, ball-pocket, cage-land), and helpers that count the closed contacts
// per segment kind. Nothing here computes an expected result.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "scheduler/executor.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/startup.hpp"
#include "tests/support/spatial_scene_builder.hpp"

namespace raceway::test {

/// The combined-load scene (radial (300, -1000) N turned by theta, axial 500 N, 1000 rpm, tanh
/// traction) with an outer-land-guided cage (0.1 mm land clearance), gravity off; its start-up
/// state (ball set turned by theta) and an "engaged" state: the cage pushed 102 um onto its land
/// (2.4 um approach, 295 N), tilted by (0.3, -0.2) mrad and turned 2.7 mrad ahead so that two
/// pockets press on their balls (15 and 5 um, 2 kN and 0.4 kN), with some translational and tilt
/// velocity.
struct EngagedBearing {
  scene::Scene scene;
  bearing::Model model;
  scheduler::SerialExecutor executor;
  bearing::Equations eq;
  std::vector<double> start, engaged;

  static scene::Scene make_scene(double theta,
                                 scene::ElementVelocityFrame frame = scene::ElementVelocityFrame::bearing) {
    BallSceneOptions o;
    o.speed_rpm = 1000;
    const double fx = 300, fy = -1000;
    o.fx = fx * std::cos(theta) - fy * std::sin(theta);
    o.fy = fx * std::sin(theta) + fy * std::cos(theta);
    o.fz = 500;
    o.gravity = false;
    scene::Scene s = deep_groove_scene(o);
    s.cage.guidance = scene::CageGuidance::outer_land;
    s.cage.land_clearance = 0.1e-3;
    s.solver.element_velocity_frame = frame;
    return s;
  }
  explicit EngagedBearing(double theta = 0.0, scene::ElementVelocityFrame frame = scene::ElementVelocityFrame::bearing)
      : scene(make_scene(theta, frame)), model(bearing::build_model(scene)), eq(model, executor) {
    start = initial_state(model, 0.0, theta).state;
    engaged = start;
    const auto& cage = model.bodies[static_cast<std::size_t>(model.cage)];
    auto at = [&](int c) -> double& { return engaged[static_cast<std::size_t>(cage.slot[c])]; };
    const double beta = 0.3 + theta;  // direction of the push onto the land, turned with the problem
    at(bearing::sx) = 0.102e-3 * std::cos(beta), at(bearing::sy) = 0.102e-3 * std::sin(beta), at(bearing::sz) = 20e-6;
    // Cage pose: R = Rz(theta) Rx(3e-4) Ry(-2e-4) Rz(2.7e-3), as Cardan angles.
    const contact::Mat3 r = bearing::cardan_rotation(0, 0, theta) * bearing::cardan_rotation(3e-4, -2e-4, 2.7e-3);
    at(bearing::say) = std::asin(r(0, 2));
    at(bearing::sax) = std::atan2(-r(1, 2), r(2, 2));
    at(bearing::saz) = std::atan2(-r(0, 1), r(0, 0));
    at(bearing::svx) = 0.01 * std::cos(beta + 1.0), at(bearing::svy) = 0.01 * std::sin(beta + 1.0), at(bearing::svz) = -0.003;
    at(bearing::swx) += 0.5, at(bearing::swy) -= 0.3;  // body frame
  }
  EngagedBearing(const EngagedBearing&) = delete;
  EngagedBearing& operator=(const EngagedBearing&) = delete;
};

/// Number of closed contacts of each segment kind in the last rhs().
inline std::vector<int> closed_contacts(const bearing::Model& m, const bearing::Equations& eq) {
  std::vector<int> closed(bearing::segment_kind_count, 0);
  const auto& rec = eq.segment_records();
  for (std::size_t s = 0; s < m.segments.size(); ++s)
    if (rec[s * bearing::SegmentRecord::size + bearing::SegmentRecord::diagnostics + 1] > 0) ++closed[static_cast<std::size_t>(m.segments[s].kind)];
  return closed;
}

/// The segment kinds a ball-bearing model has (ball-groove, ball-pocket, cage-land).
inline std::vector<int> ball_bearing_kinds(const bearing::Model& m) {
  std::vector<int> kinds;
  for (int k = 0; k < bearing::segment_kind_count; ++k)
    if (m.first_segment(static_cast<bearing::SegmentKind>(k))) kinds.push_back(k);
  return kinds;
}

/// The counts of `closed` for the kinds the model has, as "kind n, kind n, ...".
inline std::string describe_closed(const bearing::Model& m, const std::vector<int>& closed) {
  std::string out;
  for (int k : ball_bearing_kinds(m))
    out += std::string(out.empty() ? "" : ", ") + segment_kind_name(static_cast<bearing::SegmentKind>(k)) + " " +
           std::to_string(closed[static_cast<std::size_t>(k)]);
  return out;
}

}  // namespace raceway::test
