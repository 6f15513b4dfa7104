// Finite-difference Jacobian of one contact segment, planar or spatial.
//
// The bearing's Jacobian is block diagonal with borders because every segment touches two bodies
// only; each segment's block is formed by perturbing the kinematics of its two bodies, one
// component at a time. One template serves both kinematics types; what differs (the components of
// a body and how one is perturbed, the rows of a result) is said once per type in JacobianShape.
// Pure function; any segment type with an `evaluate(seg, a, b)` overload. No heap allocation.
#pragma once

#include <array>

#include <Eigen/Geometry>

#include "contact/segments/ball_segments.hpp"
#include "contact/segments/roller_segments.hpp"

namespace raceway::contact {

/// Index of a perturbation component of one spatial body (A's twelve columns come first, then B's).
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

/// The shape of a segment's block: `Components` columns per body (A's first, then B's), `Rows`
/// wrench rows, and the result type the rows are read from.
template <class SegmentResultType, int Components, int Rows>
struct JacobianLayout {
  using Result = SegmentResultType;
  using Steps = std::array<double, 2 * Components>;
  using Matrix = std::array<Steps, Rows>;
  static constexpr int components = Components;
};

/// What the finite-difference Jacobian needs of a kinematics type: its layout, how to perturb one
/// component of a body, and the block's rows read from a result.
template <class Kinematics>
struct JacobianShape;

/// Planar block: rows A fx fy mz, B fx fy mz; columns A's six components (Component), then B's.
template <>
struct JacobianShape<PlanarKinematics> : JacobianLayout<SegmentResult, kinematic_components, 6> {
  static void perturb(PlanarKinematics& k, int component, double h) {
    double* field[kinematic_components] = {&k.x, &k.y, &k.theta, &k.vx, &k.vy, &k.omega};
    *field[component] += h;
  }
  static std::array<double, 6> rows(const SegmentResult& r) {
    return {r.on_a.fx, r.on_a.fy, r.on_a.mz, r.on_b.fx, r.on_b.fy, r.on_b.mz};
  }
};

/// Spatial block: rows A force x y z, A moment x y z, B force x y z, B moment x y z (bearing
/// frame, at the bodies' centres, as in SpatialWrench); columns A's twelve components
/// (SpatialComponent), then B's.
template <>
struct JacobianShape<SpatialKinematics> : JacobianLayout<SpatialSegmentResult, spatial_components, 12> {
  static void perturb(SpatialKinematics& k, int component, double h) {
    const int axis = component % 3;
    switch (component / 3) {
      case 0: k.position[axis] += h; break;
      case 1:
        k.rotation = Eigen::AngleAxisd(h, Vec3::Unit(axis)).toRotationMatrix() * k.rotation;
        break;
      case 2: k.velocity[axis] += h; break;
      default: k.angular_velocity[axis] += h; break;
    }
  }
  static std::array<double, 12> rows(const SpatialSegmentResult& r) {
    std::array<double, 12> out{};
    const Vec3* part[4] = {&r.on_a.force, &r.on_a.moment, &r.on_b.force, &r.on_b.moment};
    for (int block = 0; block < 4; ++block)
      for (int i = 0; i < 3; ++i) out[3 * block + i] = (*part[block])[i];
    return out;
  }
};

using PlanarSteps = JacobianShape<PlanarKinematics>::Steps;
using PlanarJacobian = JacobianShape<PlanarKinematics>::Matrix;
using SpatialSteps = JacobianShape<SpatialKinematics>::Steps;
using SpatialJacobian = JacobianShape<SpatialKinematics>::Matrix;

/// d(wrench on A, wrench on B) / d(kinematics of A, kinematics of B) by forward differences around
/// `base` (the unperturbed result, already computed by the caller). Column j is skipped (left zero)
/// when step[j] == 0: a coordinate that is not a state. Returns false if any perturbed evaluation
/// left the law's valid range (the block is still filled).
template <class Segment, class Kinematics>
bool segment_jacobian(const Segment& segment, const Kinematics& a, const Kinematics& b,
                      const typename JacobianShape<Kinematics>::Result& base,
                      const typename JacobianShape<Kinematics>::Steps& step,
                      typename JacobianShape<Kinematics>::Matrix& jac) {
  using Shape = JacobianShape<Kinematics>;
  constexpr int n = Shape::components;
  const auto was = Shape::rows(base);
  bool ok = true;
  for (int j = 0; j < 2 * n; ++j) {
    for (auto& row : jac) row[j] = 0.0;
    const double h = step[j];
    if (h == 0.0) continue;
    Kinematics pa = a, pb = b;
    Shape::perturb(j < n ? pa : pb, j % n, h);
    const typename Shape::Result r = evaluate(segment, pa, pb);
    ok = ok && r.valid;
    const double inv = 1.0 / h;
    const auto now = Shape::rows(r);
    for (std::size_t i = 0; i < now.size(); ++i) jac[i][j] = (now[i] - was[i]) * inv;
  }
  return ok;
}

}  // namespace raceway::contact
