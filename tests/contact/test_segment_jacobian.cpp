// Check 7: the finite-difference Jacobian block of every segment (contact::segment_jacobian, forward
// differences) against a central-difference reference computed here, action = reaction in the block,
// and the normal stiffness against Palmgren's analytic d Q / d delta.
#include <algorithm>
#include <cmath>

#include "segment_cases.hpp"

namespace raceway::contact::test {
namespace {

using Jacobian = std::array<std::array<double, 12>, 6>;
using Steps = std::array<double, 12>;

// Forward steps, as a caller of segment_jacobian would choose them: small against the approach (5 um)
// and the slip scale (0.05 m/s), large against round-off of coordinates of some 3 cm.
constexpr Steps forward_steps = {1e-10, 1e-10, 1e-9, 1e-8, 1e-8, 1e-7,
                                 1e-10, 1e-10, 1e-9, 1e-8, 1e-8, 1e-7};
// Central-difference reference: truncation error (h / scale)^2, well below 1e-6.
constexpr Steps central_steps = {1e-9, 1e-9, 1e-8, 1e-6, 1e-6, 1e-5,
                                 1e-9, 1e-9, 1e-8, 1e-6, 1e-6, 1e-5};
constexpr double lever = 0.02;  // m: moment rows are divided by it to compare them with force rows

void perturb(Placement& p, int j, double h) {
  PlanarKinematics& k = j < 6 ? p.a : p.b;
  double* field[6] = {&k.x, &k.y, &k.theta, &k.vx, &k.vy, &k.omega};
  *field[j % 6] += h;
}

std::array<double, 6> rows(const SegmentResult& r) {
  return {r.on_a.fx, r.on_a.fy, r.on_a.mz, r.on_b.fx, r.on_b.fy, r.on_b.mz};
}

Jacobian central_reference(const AnySegment& seg, const Placement& p) {
  Jacobian jac{};
  for (int j = 0; j < 12; ++j) {
    Placement plus = p, minus = p;
    perturb(plus, j, central_steps[j]);
    perturb(minus, j, -central_steps[j]);
    const auto fp = rows(evaluate_any(seg, plus.a, plus.b));
    const auto fm = rows(evaluate_any(seg, minus.a, minus.b));
    for (int i = 0; i < 6; ++i) jac[i][j] = (fp[i] - fm[i]) / (2 * central_steps[j]);
  }
  return jac;
}

double weighted_column_norm(const Jacobian& jac, int j) {
  double s = 0;
  for (int i = 0; i < 6; ++i) {
    const double v = (i == 2 || i == 5) ? jac[i][j] / lever : jac[i][j];
    s += v * v;
  }
  return std::sqrt(s);
}

class SegmentJacobian : public SegmentTest {};

TEST_P(SegmentJacobian, MatchesCentralDifferences) {
  struct Variant {
    LawOptions options;
    double approach;
  };
  const Variant variants[] = {
      {{}, 5e-6},
      {{}, 2e-5},
      {{.slices = 5, .crown_drop = 2e-6}, 6e-6},  // every slice in contact
  };
  const std::pair<PlanarKinematics, PlanarKinematics> motions[] = {
      {moving(0.004, -0.003, 0.8), moving(-0.006, 0.005, -2.5)},  // slip in the linear traction range
      {moving(0.02, -0.01, 3.0), moving(-0.25, 0.4, -40.0)},      // running, traction saturated
  };
  for (const auto& v : variants) {
    const AnySegment seg = segment(v.options);
    for (const auto& [ma, mb] : motions) {
      for (const double dir : {0.37, 2.1, -2.6}) {
        PlanarKinematics a = ma;
        a.x = 0.2e-3;
        a.y = -0.1e-3;
        const Placement p = place(seg_case(), seg, a, mb, v.approach, dir, 2e-5);
        const SegmentResult base = evaluate_any(seg, p.a, p.b);
        ASSERT_TRUE(base.valid);
        Jacobian jac;
        for (auto& row : jac) row.fill(7.0);  // garbage: every column must be overwritten
        ASSERT_TRUE(jacobian_any(seg, p.a, p.b, base, forward_steps, jac));
        const Jacobian ref = central_reference(seg, p);
        const double f = base.diagnostics.normal_force;
        for (int j = 0; j < 12; ++j) {
          double diff = 0;
          for (int i = 0; i < 6; ++i) {
            const double w = (i == 2 || i == 5) ? 1.0 / lever : 1.0;
            diff += (jac[i][j] - ref[i][j]) * (jac[i][j] - ref[i][j]) * w * w;
          }
          diff = std::sqrt(diff);
          const double ref_norm = weighted_column_norm(ref, j);
          // Relative 1e-4 of the column, plus a round-off floor far below any physical entry.
          const double floor = 1e-13 * f / forward_steps[j];
          EXPECT_LE(diff, 1e-4 * ref_norm + floor)
              << "column " << j << " dir " << dir << " |ref| " << ref_norm;
          // Action = reaction carries to the block: A's force rows are minus B's.
          const double col = weighted_column_norm(jac, j);
          EXPECT_NEAR(jac[0][j], -jac[3][j], 1e-12 * col) << "column " << j;
          EXPECT_NEAR(jac[1][j], -jac[4][j], 1e-12 * col) << "column " << j;
          // Angular momentum about the origin: d/dq_j (M_a + M_b + r_a x F_a + r_b x F_b) = 0, where a
          // position column also moves the lever of the perturbed body (by the step, at the perturbed force).
          double identity = jac[2][j] + jac[5][j] + cross(position(p.a), {jac[0][j], jac[1][j]}) +
                            cross(position(p.b), {jac[3][j], jac[4][j]});
          const int c = j % 6;
          if (c == Component::px || c == Component::py) {
            const bool on_a = j < 6;
            const double h = forward_steps[j];
            const Vec fpert = on_a ? Vec{base.on_a.fx + h * jac[0][j], base.on_a.fy + h * jac[1][j]}
                                   : Vec{base.on_b.fx + h * jac[3][j], base.on_b.fy + h * jac[4][j]};
            const Vec e = c == Component::px ? Vec{1, 0} : Vec{0, 1};
            identity += cross(e, fpert);
          }
          const double m_scale = (std::abs(jac[2][j]) + std::abs(jac[5][j])) + 0.05 * col;
          EXPECT_NEAR(identity, 0.0, 1e-9 * m_scale + 1e2 * floor * lever) << "column " << j;
        }
      }
    }
  }
}

// The analytic normal stiffness: pushing B into A along the normal, dQ/d(delta) = (10/9) K delta^(1/9).
TEST_P(SegmentJacobian, NormalStiffnessIsPalmgrens) {
  const AnySegment seg = segment({.damping = false, .traction = false});
  const double k = expected_stiffness(seg_case());
  for (const double approach : {2e-6, 5e-6, 2e-5}) {
    for (const double dir : {0.37, 2.1, -2.6}) {
      const Placement p = place(seg_case(), seg, moving(0.01, 0, 2), moving(0, 0.03, -7), approach, dir, 2e-5);
      const SegmentResult base = evaluate_any(seg, p.a, p.b);
      Jacobian jac{};
      ASSERT_TRUE(jacobian_any(seg, p.a, p.b, base, forward_steps, jac));
      const Vec n = expected_normal_on_b(seg_case(), p);
      // Moving B by s along -n raises the approach by s.
      const Vec df{-(jac[3][6] * n[0] + jac[3][7] * n[1]), -(jac[4][6] * n[0] + jac[4][7] * n[1])};
      const double stiffness = (10.0 / 9.0) * k * std::pow(approach, 1.0 / 9.0);
      EXPECT_NEAR(dot(df, n), stiffness, 1e-4 * stiffness) << "approach " << approach;
      EXPECT_NEAR(cross(n, df), 0.0, 1e-6 * stiffness) << "the normal does not turn";
    }
  }
}

TEST_P(SegmentJacobian, ZeroStepSkipsColumnAndInvalidIsReported) {
  const AnySegment seg = segment();
  const Placement p = place(seg_case(), seg, moving(0.01, 0, 2), moving(0, 0.03, -7), 5e-6, 0.9, 0);
  const SegmentResult base = evaluate_any(seg, p.a, p.b);
  Steps steps = forward_steps;
  steps[Component::theta] = 0;
  steps[6 + Component::theta] = 0;
  Jacobian jac;
  for (auto& row : jac) row.fill(7.0);
  EXPECT_TRUE(jacobian_any(seg, p.a, p.b, base, steps, jac));
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(jac[i][Component::theta], 0.0);
    EXPECT_EQ(jac[i][6 + Component::theta], 0.0);
  }
  // Just inside the validity limit, a perturbation that crosses it makes the block invalid.
  const Placement edge = place(seg_case(), seg, moving(0, 0, 0), moving(0, 0, 0),
                               seed002::max_approach - 1e-9, 0.9, 0);
  const SegmentResult edge_base = evaluate_any(seg, edge.a, edge.b);
  ASSERT_TRUE(edge_base.valid);
  Steps big{};
  const Vec n = expected_normal_on_b(seg_case(), edge);
  // Step B's position into A along whichever coordinate moves it most.
  const int axis = std::abs(n[0]) > std::abs(n[1]) ? 0 : 1;
  big[6 + axis] = -std::copysign(1e-8 / std::abs(n[axis]), n[axis]);
  EXPECT_FALSE(jacobian_any(seg, edge.a, edge.b, edge_base, big, jac));
}

INSTANTIATE_TEST_SUITE_P(AllSegments, SegmentJacobian, ::testing::ValuesIn(all_segment_cases()),
                         case_name);

}  // namespace
}  // namespace raceway::contact::test
