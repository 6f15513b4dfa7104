// Contact conformance suite: the same physics checks for every contact segment kind, planar and
// spatial (segment_kinds.hpp), each kind over all of its configurations: no force apart, continuity
// at onset, action = reaction, the normal law along the expected normal, Hunt-Crossley damping,
// the energy balance, power loss as dissipation, traction opposing the sliding, frame invariance and
// the validity flag. The Jacobian checks are in test_segment_jacobian.cpp. Each tolerance is chosen
// so that a sign error or a missing term in contact/ breaks it by orders of magnitude.
#include <algorithm>
#include <cmath>
#include <string>

#include "segment_kinds.hpp"

namespace raceway::contact::test {
namespace {

template <class Kind>
class SegmentConformance : public ::testing::Test {};
TYPED_TEST_SUITE(SegmentConformance, AllSegmentKinds, KindName);

// Zero force, moment, energy and loss when apart, whatever the velocities; the approach reported.
TYPED_TEST(SegmentConformance, NoForceWhenApart) {
  using K = TypeParam;
  for_each_configuration<K>({}, [&](const auto& c, const auto& seg) {
    for (const double separation : {1e-12, 1e-9, 1e-6, 5e-5}) {
      for (const double dir : roller::directions) {
        for (const auto& m : K::motions()) {
          const auto p = K::placed(c, seg, -separation, dir, m);
          const auto r = evaluate_at<K>(seg, p);
          EXPECT_TRUE(r.valid);
          EXPECT_EQ(K::wrenches(r).norm(), 0.0) << "separation " << separation;
          EXPECT_EQ(r.diagnostics.normal_force, 0.0);
          EXPECT_EQ(r.diagnostics.traction_force, 0.0);
          EXPECT_EQ(r.diagnostics.elastic_energy, 0.0);
          EXPECT_EQ(r.diagnostics.power_loss, 0.0);
          EXPECT_NEAR(r.diagnostics.approach, -separation, K::approach_tolerance);
        }
      }
    }
    // Bodies rushing towards each other (1 m/s along the normal) but still apart: still nothing.
    auto p = K::placed(c, seg, -1e-9, 0.4, K::motions()[0]);
    K::set_velocity(p.b, -p.normal_on_b);
    EXPECT_EQ(K::wrenches(evaluate_at<K>(seg, p)).norm(), 0.0);
    // Exactly at touch.
    const auto touch = K::placed(c, seg, 0.0, 1.0, K::motions()[1]);
    EXPECT_LT(evaluate_at<K>(seg, touch).diagnostics.normal_force, 1e-9);
  });
}

// Continuity at onset: force and moment vanish with the approach and so does their slope (the
// law's exponent is above 1). A constant term, a damper c * rate, a force before contact or a
// rolling-resistance couple growing like Q^0.47 break these bounds by orders of magnitude.
// Palmgren's law itself gives K (1e-12 m)^(10/9) = 6.3e-5 N for a steel roller pair, so "below
// 1e-6 N" is asked at 1e-14 m, and at 1e-12 m the force is held to the analytic bound and to 1e-3 N.
TYPED_TEST(SegmentConformance, ContinuousAtOnset) {
  using K = TypeParam;
  for_each_configuration<K>({}, [&](const auto& c, const auto& seg) {  // everything on
    const double n_exp = K::exponent(c);
    for (const auto& m : K::motions()) {
      for (const double dir : roller::directions) {
        for (const double below : {-1e-12, -1e-13}) {
          EXPECT_EQ(K::wrenches(evaluate_at<K>(seg, K::placed(c, seg, below, dir, m))).norm(), 0.0);
        }
        for (const double approach : {1e-12, 1e-14}) {
          const auto p = K::placed(c, seg, approach, dir, m);
          const double bound = K::stiffness(c, p) * std::pow(approach, n_exp) *
                               (1 + K::damping_factor * K::speed_bound(p)) * (1 + K::friction) *
                               (1 + K::stiffness_tolerance(c));
          const Wrenches w = K::wrenches(evaluate_at<K>(seg, p));
          EXPECT_LE(w.force_b.norm(), bound) << "approach " << approach;
          // Moments: levers below 0.1 m, couples (spin, rolling resistance) below 0.1 m times Q.
          EXPECT_LE(w.moment_a.norm() + w.moment_b.norm(), 0.4 * bound) << "approach " << approach;
          EXPECT_LT(w.force_b.norm(), approach > 1e-13 ? 1e-3 : 1e-6) << "approach " << approach;
          EXPECT_LT(w.moment_a.norm() + w.moment_b.norm(), 1e-3 * 0.05);
        }
        // Secant slope of the whole wrench (moments over 0.05 m) near onset against one in operation:
        // it falls like approach^(n-1).
        auto slope = [&](double approach) {
          const Wrenches w1 = K::wrenches(evaluate_at<K>(seg, K::placed(c, seg, approach, dir, m)));
          const Wrenches w2 = K::wrenches(evaluate_at<K>(seg, K::placed(c, seg, 2 * approach, dir, m)));
          return ((w2.force_b - w1.force_b).norm() + (w2.moment_b - w1.moment_b).norm() / 0.05 +
                  (w2.moment_a - w1.moment_a).norm() / 0.05) / approach;
        };
        const double at_onset = slope(1e-12), in_operation = slope(1e-5);
        ASSERT_GT(in_operation, 0.0);
        EXPECT_LT(at_onset, 3.0 * std::pow(1e-12 / 1e-5, n_exp - 1) * in_operation);
      }
    }
    // The elastic law alone grows exactly like approach^n.
    const auto elastic = K::make(c, {.damping = false, .traction = false});
    auto force_at = [&](double approach, double dir) {
      return K::wrenches(evaluate_at<K>(elastic, K::placed(c, elastic, approach, dir, K::motions()[1]))).force_b.norm();
    };
    for (const double dir : roller::directions) {
      for (const auto& [from, to, tolerance] : {std::array{1e-8, 1e-6, 1e-7}, std::array{1e-7, 1e-6, 1e-6}}) {
        const double f1 = force_at(from, dir), f2 = force_at(to, dir);
        ASSERT_GT(f1, 0.0);
        EXPECT_NEAR(std::log(f2 / f1) / std::log(to / from), n_exp, tolerance);
      }
    }
  });
}

// Action equals reaction; the total moment about the origin vanishes (configuration far from it).
TYPED_TEST(SegmentConformance, ActionEqualsReaction) {
  using K = TypeParam;
  for_each_configuration<K>({}, [&](const auto& c, const auto& seg) {
    for (const auto& m : K::motions()) {
      for (const double dir : roller::directions) {
        for (const double approach : {1e-7, 3e-6, 2e-5}) {
          const auto p = K::translated(K::placed(c, seg, approach, dir, m, 3e-5), Vec3(0.031, -0.047, 0.022));
          const auto r = evaluate_at<K>(seg, p);
          ASSERT_TRUE(r.valid);
          const Wrenches w = K::wrenches(r);
          const double f = w.force_b.norm();
          ASSERT_GT(f, 0.0);
          EXPECT_LE((w.force_a + w.force_b).norm(), 1e-12 * f);
          const double scale = w.moment_a.norm() + w.moment_b.norm() + K::position(p.a).cross(w.force_a).norm() +
                               K::position(p.b).cross(w.force_b).norm();
          EXPECT_LE(moment_about_origin<K>(w, p).norm(), 1e-12 * scale) << "dir " << dir << " approach " << approach;
        }
      }
    }
  });
}

// The normal law (Palmgren, Hertz or Palmgren stations) along the expected normal, with its elastic
// energy; nothing tangential, nothing lost without damping and traction.
TYPED_TEST(SegmentConformance, NormalLawAlongNormal) {
  using K = TypeParam;
  for_each_configuration<K>({.damping = false, .traction = false}, [&](const auto& c, const auto& seg) {
    const double n_exp = K::exponent(c);
    for (const double approach : {1e-6, 5e-6, 2e-5, 3e-5}) {
      for (const double dir : roller::directions) {
        const auto p = K::placed(c, seg, approach, dir, K::motions()[1], 1e-5);
        const auto r = evaluate_at<K>(seg, p);
        ASSERT_TRUE(r.valid);
        const auto& d = r.diagnostics;
        const double expected = K::stiffness(c, p) * std::pow(approach, n_exp);
        EXPECT_NEAR(d.approach, approach, K::geometry_tolerance * approach);
        EXPECT_NEAR(d.normal_force, expected, K::stiffness_tolerance(c) * expected);
        EXPECT_LE((K::wrenches(r).force_b - d.normal_force * p.normal_on_b).norm(), 1e-10 * expected);
        EXPECT_NEAR(d.elastic_energy, d.normal_force * approach / (n_exp + 1),
                    K::geometry_tolerance * expected * approach);
        EXPECT_EQ(d.traction_force, 0.0);
        EXPECT_EQ(d.power_loss, 0.0);
      }
    }
  });
}

// Hunt-Crossley damping: approaching at rate v multiplies the elastic force by (1 + c v) and
// dissipates c v^2 Q_elastic; separating faster than 1/c leaves no force (a contact cannot pull),
// and the elastic force's work is then the loss.
TYPED_TEST(SegmentConformance, HuntCrossleyDamping) {
  using K = TypeParam;
  for_each_configuration<K>({.damping = true, .traction = false}, [&](const auto& c, const auto& seg) {
    const double damping = K::damping_factor;
    for (const double approach : {1e-6, 8e-6, 1e-5}) {
      for (const double dir : roller::directions) {
        const auto rest = K::placed(c, seg, approach, dir, K::motions()[0], 1e-5);
        const double elastic = evaluate_at<K>(seg, rest).diagnostics.normal_force;
        const double analytic = K::stiffness(c, rest) * std::pow(approach, K::exponent(c));
        EXPECT_NEAR(elastic, analytic, K::stiffness_tolerance(c) * analytic);
        for (const double rate : {0.3, 0.02, -0.5, -0.8, -1.9, -3.0, -20.0}) {  // > 0: approaching
          auto p = rest;
          K::set_velocity(p.b, -rate * p.normal_on_b);  // B moving against the normal force on it
          const auto r = evaluate_at<K>(seg, p);
          const double expected = std::max(0.0, elastic * (1.0 + damping * rate));
          const double tol = K::geometry_tolerance * elastic;
          const auto& d = r.diagnostics;
          EXPECT_NEAR(d.normal_force, expected, tol) << "rate " << rate;
          EXPECT_LE((K::wrenches(r).force_b - expected * p.normal_on_b).norm(), tol) << "rate " << rate;
          EXPECT_GE(d.normal_force, 0.0);
          EXPECT_GE(d.power_loss, 0.0);
          // Power of the damping force on the relative motion: (F - elastic) * rate; dissipated.
          EXPECT_NEAR(d.power_loss, (expected - elastic) * rate, tol * std::abs(rate)) << "rate " << rate;
          if (rate > 0) {
            EXPECT_NEAR(d.power_loss, elastic * damping * rate * rate, tol * rate * rate);
          }
          if (1.0 + damping * rate <= 0) {
            EXPECT_EQ(K::wrenches(r).norm(), 0.0) << "fast separation must give no force";
          }
        }
      }
    }
  });
}

// Energy balance in any motion: the work of the contact on the two bodies goes into the elastic
// energy or is dissipated, loss = -(F.v + M.w over both bodies) - dE/dt, with dE/dt from the
// elastic_energy diagnostic of the configuration advanced rigidly in time (ball/groove: Q_elastic
// times the rate of the approach diagnostic). A wrong sign or a wrong value of the approach rate or
// the slip the segment uses breaks it.
TYPED_TEST(SegmentConformance, EnergyBalance) {
  using K = TypeParam;
  const double dt = K::energy_dt;
  for_each_configuration<K>({}, [&](const auto& c, const auto& seg) {
    for (const auto& m : K::motions()) {
      for (const double dir : roller::directions) {
        for (const double approach : {3e-6, 5e-6, 2e-5}) {
          const auto p = K::placed(c, seg, approach, dir, m, 4e-5);
          const auto r = evaluate_at<K>(seg, p);
          ASSERT_TRUE(r.valid);
          const auto after = evaluate_at<K>(seg, K::advanced(p, dt)).diagnostics;
          const auto before = evaluate_at<K>(seg, K::advanced(p, -dt)).diagnostics;
          double energy_rate = (after.elastic_energy - before.elastic_energy) / (2 * dt);
          if (!K::energy_is_potential) {
            const double elastic_force = (K::exponent(c) + 1) * r.diagnostics.elastic_energy / approach;
            energy_rate = elastic_force * (after.approach - before.approach) / (2 * dt);
          }
          const Power power = power_on_bodies<K>(r, p);
          EXPECT_NEAR(r.diagnostics.power_loss, -power.total - energy_rate,
                      1e-6 * (power.scale + std::abs(energy_rate)) + 1e-12)
              << "dir " << dir << " approach " << approach;
        }
      }
    }
  });
}

// Power: the loss is never negative; with no approach rate (no elastic or damping work) it is
// exactly minus the power of the contact forces and moments on the two bodies, and positive in
// any motion (sliding, spin or rolling resistance dissipates).
TYPED_TEST(SegmentConformance, PowerLossIsDissipation) {
  using K = TypeParam;
  for_each_configuration<K>({}, [&](const auto& c, const auto& seg) {
    const auto all = K::motions();
    for (std::size_t i = 0; i < all.size(); ++i) {
      for (const double dir : roller::directions) {
        for (const double approach : {3e-6, 2e-5}) {
          auto p = K::placed(c, seg, approach, dir, all[i]);
          EXPECT_GE(evaluate_at<K>(seg, p).diagnostics.power_loss, 0.0);
          K::stop_approach(c, p);
          const auto r = evaluate_at<K>(seg, p);
          ASSERT_TRUE(r.valid);
          const Power power = power_on_bodies<K>(r, p);
          EXPECT_GE(r.diagnostics.power_loss, 0.0);
          EXPECT_NEAR(r.diagnostics.power_loss, -power.total, 1e-9 * power.scale + 1e-15)
              << "dir " << dir << " approach " << approach;
          if (i > 0) {
            EXPECT_GT(r.diagnostics.power_loss, 0.0) << "motion " << i;
          }
        }
      }
    }
  });
}

// Traction (friction) opposes the sliding: B slides across A at rest, without rotation; the
// tangential force is mu(s) Q exactly (uniform sliding over the contact) and points against it.
TYPED_TEST(SegmentConformance, TractionOpposesSliding) {
  using K = TypeParam;
  const double speed = 0.15;
  for_each_configuration<K>({}, [&](const auto& c, const auto& seg) {
    for (const double dir : roller::directions) {
      const auto rest = K::placed(c, seg, 2e-5, dir, K::motions()[0]);
      for (const Vec3& t : K::tangents(rest.normal_on_b)) {
        auto p = rest;
        K::set_velocity(p.b, speed * t);
        const auto r = evaluate_at<K>(seg, p);
        ASSERT_TRUE(r.valid);
        const double q = r.diagnostics.normal_force;
        ASSERT_GT(q, 0.0);
        const Vec3 n = p.normal_on_b, f_b = K::wrenches(r).force_b;
        const Vec3 f_t = f_b - f_b.dot(n) * n;
        const double expected = K::friction * std::tanh(speed / K::slip_scale) * q;
        EXPECT_NEAR(f_t.norm(), expected, 1e-9 * expected);
        EXPECT_LE((f_t + f_t.norm() * t).norm(), 1e-9 * expected) << "not against the sliding";
        EXPECT_NEAR(std::abs(r.diagnostics.traction_force), expected, 1e-9 * expected);
        EXPECT_NEAR(std::abs(r.diagnostics.slip_velocity), speed, 1e-12);
        EXPECT_NEAR(r.diagnostics.power_loss, expected * speed, 1e-9 * expected * speed);
      }
    }
  });
}

// Frame invariance: rotating the whole configuration (poses and rates) about the bearing axis
// rotates forces and moments and leaves every scalar diagnostic unchanged. Spatial segments are
// also rotated about an arbitrary axis, which does not carry the bearing's own circumferential
// direction along: that one diagnostic is then not compared.
TYPED_TEST(SegmentConformance, FrameInvariance) {
  using K = TypeParam;
  const auto& fields = K::diagnostic_fields;
  for_each_configuration<K>({.detailed = true}, [&](const auto& c, const auto& seg) {
    for (const auto& m : K::motions()) {
      for (const double dir : roller::directions) {
        for (const double approach : {7e-6, 1.5e-5}) {
          const auto p = K::placed(c, seg, approach, dir, m, 1e-5);
          const auto r0 = evaluate_at<K>(seg, p);
          ASSERT_TRUE(r0.valid);
          const Wrenches w0 = K::wrenches(r0);
          const double f = r0.diagnostics.normal_force;
          ASSERT_GT(f, 0.0);
          const double tol_f = 1e-10 * f;
          const double tol_m = 1e-10 * (K::lever * f + w0.moment_a.norm() + w0.moment_b.norm());
          const double v_scale = 0.01 + K::speed_bound(p);
          for (const FrameRotation& rotation : K::frame_rotations()) {
            const auto r = evaluate_at<K>(seg, K::rotated(p, rotation));
            EXPECT_EQ(r.valid, r0.valid);
            const Mat3 q = rotation.matrix();
            const Wrenches w = K::wrenches(r);
            EXPECT_LE((w.force_a - q * w0.force_a).norm(), tol_f);
            EXPECT_LE((w.force_b - q * w0.force_b).norm(), tol_f);
            EXPECT_LE((w.moment_a - q * w0.moment_a).norm(), tol_m);
            EXPECT_LE((w.moment_b - q * w0.moment_b).norm(), tol_m);
            for (std::size_t i = 0; i < fields.size(); ++i) {
              if (!rotation.about_bearing_axis() && std::string(fields[i].name) == "circumferential_force") continue;
              const double before = r0.diagnostics.*fields[i].member, after = r.diagnostics.*fields[i].member;
              EXPECT_NEAR(after, before, K::diagnostic_tolerance(static_cast<int>(i), before, f, v_scale))
                  << fields[i].name << ", rotation " << rotation.angle;
            }
          }
        }
      }
    }
  });
}

// Validity: beyond the law's limit the result is flagged (a recoverable error); a NaN in an input
// that enters the segment flags it too, and a result still flagged valid does not depend on the NaN.
TYPED_TEST(SegmentConformance, Validity) {
  using K = TypeParam;
  for_each_configuration<K>({}, [&](const auto& c, const auto& seg) {
    const double limit = K::approach_limit(c);
    for (const auto& m : {K::motions()[1], K::motions()[2]}) {
      for (const double dir : {0.5, 0.37, 2.1, -2.6}) {
        for (const double inside : {0.98, 0.99}) {
          EXPECT_TRUE(evaluate_at<K>(seg, K::placed(c, seg, inside * limit, dir, m)).valid);
        }
        for (const double beyond : {1.01, 1.02}) {
          EXPECT_FALSE(evaluate_at<K>(seg, K::placed(c, seg, beyond * limit, dir, m)).valid);
        }
      }
    }
    for (const double approach : {5e-6, 1e-5, -1e-5}) {
      const auto p = K::placed(c, seg, approach, 0.5, K::motions()[1], 1e-5);
      const auto base = evaluate_at<K>(seg, p);
      ASSERT_TRUE(base.valid);
      const Wrenches w0 = K::wrenches(base);
      for (const auto& input : K::nan_inputs()) {
        auto q = p;
        input.apply(q);
        const auto r = evaluate_at<K>(seg, q);
        using Effect = typename std::decay_t<decltype(input)>::Effect;
        if (input.effect == Effect::geometry || (input.effect == Effect::rate && approach > 0)) {
          EXPECT_FALSE(r.valid) << "NaN in " << input.name << ", approach " << approach;
        }
        if (!r.valid && K::invalid_has_no_force) {
          EXPECT_EQ(K::wrenches(r).norm(), 0.0) << "NaN in " << input.name;
        }
        if (r.valid) {  // finite, and as without the NaN
          const Wrenches w = K::wrenches(r);
          EXPECT_EQ(w.force_a, w0.force_a) << "NaN in " << input.name;
          EXPECT_EQ(w.moment_a, w0.moment_a) << "NaN in " << input.name;
          EXPECT_EQ(w.force_b, w0.force_b) << "NaN in " << input.name;
          EXPECT_EQ(w.moment_b, w0.moment_b) << "NaN in " << input.name;
          EXPECT_EQ(r.diagnostics.power_loss, base.diagnostics.power_loss) << "NaN in " << input.name;
        }
      }
    }
  });
}

}  // namespace
}  // namespace raceway::contact::test
