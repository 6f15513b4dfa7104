// Finite-difference Jacobian of one spatial contact segment (DESIGN.md 4.2), the spatial
// counterpart of segment_jacobian.hpp.
//
// Every segment touches two bodies only, so the bearing's Jacobian is block diagonal with borders;
// a segment's block is formed by perturbing the kinematics of its two bodies one component at a
// time. Pure function; any segment type with an `evaluate(seg, a, b)` overload returning a
// SpatialSegmentResult. No heap allocation.
#pragma once

#include <array>

#include <Eigen/Geometry>

#include "contact/segments/ball_segments.hpp"

namespace raceway::contact {

/// Index of a perturbation component of one body (A's twelve columns come first, then B's).
/// Rotations are small rotations about the bearing-frame axes applied on the left
/// (rotation <- R(dphi) * rotation, R from Eigen::AngleAxisd): a rotation of the body about its
/// centre, whatever its current orientation.
enum SpatialComponent : int {
  position_x = 0, position_y, position_z,
  rotation_x, rotation_y, rotation_z,
  velocity_x, velocity_y, velocity_z,
  angular_velocity_x, angular_velocity_y, angular_velocity_z
};
inline constexpr int spatial_components = 12;

/// Rows: A force x y z, A moment x y z, B force x y z, B moment x y z (bearing frame, at the
/// bodies' centres, as in SpatialWrench).
using SpatialJacobian = std::array<std::array<double, 2 * spatial_components>, 12>;
using SpatialSteps = std::array<double, 2 * spatial_components>;

/// d(wrench on A (6), wrench on B (6)) / d(perturbation of A (12), B (12)) by forward differences
/// around `base` (the unperturbed result, already computed by the caller). Column j is skipped
/// (left zero) when step[j] == 0: a coordinate that is not a state. Returns false if any perturbed
/// evaluation left the law's valid range (the block is still filled).
template <class Segment>
bool spatial_segment_jacobian(const Segment& segment, const SpatialKinematics& a,
                              const SpatialKinematics& b, const SpatialSegmentResult& base,
                              const SpatialSteps& step, SpatialJacobian& jac) {
  bool ok = true;
  for (int j = 0; j < 2 * spatial_components; ++j) {
    for (auto& row : jac) row[j] = 0.0;
    const double h = step[j];
    if (h == 0.0) continue;
    SpatialKinematics pa = a, pb = b;
    SpatialKinematics& target = j < spatial_components ? pa : pb;
    const int c = j % spatial_components;
    const int axis = c % 3;
    switch (c / 3) {
      case 0: target.position[axis] += h; break;
      case 1:
        target.rotation = Eigen::AngleAxisd(h, Vec3::Unit(axis)).toRotationMatrix() * target.rotation;
        break;
      case 2: target.velocity[axis] += h; break;
      default: target.angular_velocity[axis] += h; break;
    }
    const SpatialSegmentResult r = evaluate(segment, pa, pb);
    ok = ok && r.valid;
    const double inv = 1.0 / h;
    const Vec3* now[4] = {&r.on_a.force, &r.on_a.moment, &r.on_b.force, &r.on_b.moment};
    const Vec3* was[4] = {&base.on_a.force, &base.on_a.moment, &base.on_b.force, &base.on_b.moment};
    for (int block = 0; block < 4; ++block) {
      for (int i = 0; i < 3; ++i) jac[3 * block + i][j] = ((*now[block])[i] - (*was[block])[i]) * inv;
    }
  }
  return ok;
}

}  // namespace raceway::contact
