// The finite-difference Jacobian block of every contact segment kind (contact::segment_jacobian,
// forward differences) against a central-difference reference computed here with the test's own
// perturbations (segment_kinds.hpp), action = reaction and the balance of angular momentum in the
// block, the columns of coordinates that do not enter, the normal stiffness against the law's
// analytic dQ/d(delta), skipped columns and the validity of perturbed evaluations.
#include <algorithm>
#include <cmath>

#include "segment_kinds.hpp"

namespace raceway::contact::test {
namespace {

template <class Kind>
class SegmentJacobian : public ::testing::Test {};
TYPED_TEST_SUITE(SegmentJacobian, AllSegmentKinds, KindName);

/// Size of a wrench change, moments over the family's lever so that they compare with forces.
template <class Kind>
double weighted_norm(const Wrenches& w) {
  const double l = Kind::jacobian_lever;
  return std::sqrt(w.force_a.squaredNorm() + (w.moment_a / l).squaredNorm() + w.force_b.squaredNorm() +
                   (w.moment_b / l).squaredNorm());
}

Wrenches difference(const Wrenches& x, const Wrenches& y, double scale) {
  return {(x.force_a - y.force_a) * scale, (x.moment_a - y.moment_a) * scale, (x.force_b - y.force_b) * scale,
          (x.moment_b - y.moment_b) * scale};
}

template <class Kind>
typename Kind::Jacobian garbage() {
  typename Kind::Jacobian jac;
  for (auto& row : jac) row.fill(7.0);  // every column must be overwritten
  return jac;
}

TYPED_TEST(SegmentJacobian, MatchesCentralDifferences) {
  using K = TypeParam;
  struct Variant {
    Law law;
    double approach;
  };
  const Variant variants[] = {
      {{}, 5e-6},
      {{}, 2e-5},
      {{.detailed = true}, 6e-6},  // roller: every slice of the crowned law in contact
      {{.damping = false, .traction = false}, 2e-5},
  };
  const auto& forward = K::forward_steps;
  const auto& central = K::central_steps;
  for (const auto& v : variants) {
    for_each_configuration<K>(v.law, [&](const auto& c, const auto& seg) {
      for (const auto& m : {K::motions()[1], K::motions()[2]}) {  // traction saturated; creep
        for (const double dir : roller::directions) {
          const auto p = K::placed(c, seg, v.approach, dir, m);
          const auto base = evaluate_at<K>(seg, p);
          ASSERT_TRUE(base.valid);
          auto jac = garbage<K>();
          ASSERT_TRUE(segment_jacobian(seg, p.a, p.b, base, forward, jac));
          const Wrenches w0 = K::wrenches(base);
          const double f = w0.force_b.norm();
          for (int j = 0; j < 2 * K::components; ++j) {
            auto plus = p, minus = p;
            K::perturb(plus, j, central[j]);
            K::perturb(minus, j, -central[j]);
            const Wrenches ref = difference(K::wrenches(evaluate_at<K>(seg, plus)),
                                            K::wrenches(evaluate_at<K>(seg, minus)), 1.0 / (2 * central[j]));
            const Wrenches got = K::column(jac, j);
            const double floor = K::jacobian_roundoff * f / forward[j];
            EXPECT_LE(weighted_norm<K>(difference(got, ref, 1.0)),
                      K::jacobian_relative * weighted_norm<K>(ref) + floor)
                << "column " << j << " dir " << dir << " |ref| " << weighted_norm<K>(ref);
            // Action = reaction carries to the block: A's force rows are minus B's.
            const double col = weighted_norm<K>(got);
            EXPECT_LE((got.force_a + got.force_b).norm(), 1e-12 * (col + floor)) << "column " << j;
            // Angular momentum about the origin: d/dq_j (M_a + M_b + r_a x F_a + r_b x F_b) = 0, where a
            // position column also moves the lever of the perturbed body (by the step, at the perturbed force).
            Vec3 identity = moment_about_origin<K>(got, p);
            const int axis = K::position_axis(j % K::components);
            if (axis >= 0) {
              const double h = forward[j];
              const Vec3 f_perturbed = j < K::components ? Vec3(w0.force_a + h * got.force_a)
                                                         : Vec3(w0.force_b + h * got.force_b);
              identity += Vec3::Unit(axis).cross(f_perturbed);
            }
            const double m_scale = got.moment_a.norm() + got.moment_b.norm() + 0.05 * col;
            EXPECT_LE(identity.norm(), 1e-9 * m_scale + 1e2 * floor * K::jacobian_lever) << "column " << j;
          }
          if (K::b_orientation_free) {  // B is round: its orientation does not enter
            for (const int o : K::orientation_components) {
              EXPECT_EQ(K::column(jac, K::components + o).norm(), 0.0) << "B orientation column " << o;
            }
          }
        }
      }
    });
  }
}

// The normal stiffness of the elastic law: pushing B into A along the normal by s raises the
// approach by s, dQ/d(delta) = n K delta^(n-1) = n Q / delta, and does not turn the force.
TYPED_TEST(SegmentJacobian, NormalStiffnessIsTheLaws) {
  using K = TypeParam;
  for_each_configuration<K>({.damping = false, .traction = false}, [&](const auto& c, const auto& seg) {
    const double n_exp = K::exponent(c);
    for (const double approach : {2e-6, 5e-6, 2e-5}) {
      for (const double dir : roller::directions) {
        const auto p = K::placed(c, seg, approach, dir, K::motions()[1]);
        const auto base = evaluate_at<K>(seg, p);
        auto jac = garbage<K>();
        ASSERT_TRUE(segment_jacobian(seg, p.a, p.b, base, K::forward_steps, jac));
        const Vec3 n = p.normal_on_b;
        Vec3 df = Vec3::Zero();  // change of the force on B per metre of B moved along -n
        for (int axis = 0; axis < 3; ++axis) {
          for (int c_b = 0; c_b < K::components; ++c_b) {
            if (K::position_axis(c_b) == axis) df -= n[axis] * K::column(jac, K::components + c_b).force_b;
          }
        }
        const double stiffness = n_exp * K::stiffness(c, p) * std::pow(approach, n_exp - 1);
        EXPECT_NEAR(n.dot(df), stiffness, (1e-4 + K::stiffness_tolerance(c)) * stiffness) << "approach " << approach;
        const double secant = n_exp * base.diagnostics.normal_force / approach;
        EXPECT_NEAR(n.dot(df), secant, 1e-4 * secant) << "approach " << approach;
        EXPECT_LE((df - n.dot(df) * n).norm(), 1e-6 * stiffness) << "the normal does not turn";
      }
    }
  });
}

TYPED_TEST(SegmentJacobian, ZeroStepSkipsColumnAndInvalidIsReported) {
  using K = TypeParam;
  for_each_configuration<K>({}, [&](const auto& c, const auto& seg) {
    const auto p = K::placed(c, seg, 5e-6, 0.9, K::motions()[1]);
    const auto base = evaluate_at<K>(seg, p);
    auto steps = K::forward_steps;
    for (const int j : K::skipped_columns) steps[j] = 0.0;
    auto jac = garbage<K>();
    EXPECT_TRUE(segment_jacobian(seg, p.a, p.b, base, steps, jac));
    for (const int j : K::skipped_columns) {
      for (const auto& row : jac) EXPECT_EQ(row[j], 0.0) << "column " << j;
    }
    // Just inside the validity limit, a perturbation that crosses it makes the block invalid.
    const auto edge = K::placed(c, seg, K::approach_limit(c) - 1e-9, 0.9, K::motions()[0]);
    const auto at_edge = evaluate_at<K>(seg, edge);
    ASSERT_TRUE(at_edge.valid);
    typename K::Steps into{};  // B's position steps move it 1 um into A along -n
    for (int c_b = 0; c_b < K::components; ++c_b) {
      const int axis = K::position_axis(c_b);
      if (axis >= 0) into[K::components + c_b] = -1e-6 * edge.normal_on_b[axis];
    }
    EXPECT_FALSE(segment_jacobian(seg, edge.a, edge.b, at_edge, into, jac));
  });
}

}  // namespace
}  // namespace raceway::contact::test
