// Finite-difference Jacobian of one contact segment (DESIGN.md 4.2).
//
// The bearing's Jacobian is block diagonal with borders because every segment touches two bodies
// only; each segment's block is formed by perturbing the kinematics of its two bodies, one
// component at a time. Pure function; any segment type with an `evaluate(seg, a, b)` overload.
#pragma once

#include <array>

#include "contact/segments/roller_segments.hpp"

namespace raceway::contact {


/// d(wrench on A, wrench on B) / d(kinematics of A, kinematics of B): 6 rows (A fx fy mz, B fx fy
/// mz) by 12 columns. Column j is skipped (left zero) when step[j] == 0: a coordinate that is not a
/// state. Forward differences around `base` (the unperturbed result, already computed by the
/// caller). Returns false if any perturbed evaluation left the law's valid range.
template <class Segment>
bool segment_jacobian(const Segment& segment, const PlanarKinematics& a, const PlanarKinematics& b,
                      const SegmentResult& base, const std::array<double, 12>& step,
                      std::array<std::array<double, 12>, 6>& jac) {
  bool ok = true;
  for (int j = 0; j < 12; ++j) {
    for (auto& row : jac) row[j] = 0.0;
    if (step[j] == 0.0) continue;
    PlanarKinematics pa = a, pb = b;
    PlanarKinematics& target = j < 6 ? pa : pb;
    double* field[6] = {&target.x, &target.y, &target.theta, &target.vx, &target.vy, &target.omega};
    *field[j % 6] += step[j];
    const SegmentResult r = evaluate(segment, pa, pb);
    ok = ok && r.valid;
    const double inv = 1.0 / step[j];
    const double delta[6] = {r.on_a.fx - base.on_a.fx, r.on_a.fy - base.on_a.fy,
                             r.on_a.mz - base.on_a.mz, r.on_b.fx - base.on_b.fx,
                             r.on_b.fy - base.on_b.fy, r.on_b.mz - base.on_b.mz};
    for (int i = 0; i < 6; ++i) jac[i][j] = delta[i] * inv;
  }
  return ok;
}

}  // namespace raceway::contact
