// The Timoshenko theories of the flexible parts: the cage bars with shear (cage_bridges.hpp) and the
// outer ring's rim as a thick ring, with extension and shear (thick_ring.hpp, ring_modes.hpp).
//  - The rim pinched by two diametral forces P: the sum of the thick ring's harmonics against Roark's
//    thick-ring formula (docs/references.md), (K1 pi/4 - 2 K2^2 / pi) P R^3 / (E I) with
//    K1 = 1 - alpha + beta, K2 = 1 - alpha, alpha = I / (A R^2), beta = E I / (k_s G A R^2); the
//    same pinch on the model's rim (40 modes, the loads projected and the displacement read back as
//    a contact sees them) short of it by the series' tail.
//  - A thin section's harmonics against Love's ring, pi E I (n^2 - 1)^2 / R^3 and V / W = -1/n.
//  - Each harmonic's frequency against the lowest root of its full three-coordinate problem
//    (W, V, Psi with their masses, no condensation): Rayleigh's bound, within 1 %.
//  - The bar: a Timoshenko finite-element model of the clamped-clamped bar (linear elements, the
//    shear at the element's middle), written here: its mean deflection under the uniform pocket
//    force against the bar's stiffness, its first eigenfrequency against the bar's.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "solver/bearing/cage_bridges.hpp"
#include "solver/bearing/ring_modes.hpp"
#include "solver/bearing/thick_ring.hpp"
#include "tests/support/solver_test_support.hpp"

namespace raceway::bearing {
namespace {

constexpr double pi = test::pi;

/// Seed 003's planet rim: steel, 13 x 14 mm at 63.5 mm, its 3.04 kg spread round it.
ThickRingSection seed003_rim() { return rectangular_ring(63.5e-3, 13e-3, 14e-3, 2.1e11, 0.3, 3.04 / (2 * pi * 63.5e-3)); }

/// Roark's shortening of the loaded diameter of a thick ring pinched by P.
double roark_pinch(const ThickRingSection& r, double load) {
  const double ei = r.youngs_modulus * r.area_moment, radius2 = r.radius * r.radius;
  const double alpha = r.area_moment / (r.area * radius2);
  const double beta = ei / (r.shear_coefficient * r.shear_modulus * r.area * radius2);
  const double k1 = 1 - alpha + beta, k2 = 1 - alpha;
  return (k1 * pi / 4 - 2 * k2 * k2 / pi) * load * r.radius * radius2 / ei;
}

/// The harmonics' shortening, sum over even n from `first` to `last` of 4 P / k_n (each of the two
/// loads puts -2 P on a_n, and w(0) + w(pi) = 2 a_n).
double harmonic_pinch(const ThickRingSection& r, double load, int first, int last) {
  double sum = 0;
  for (int n = last; n >= first; n -= 2) sum += 4 * load / thick_ring_harmonic(r, n).stiffness;  // small first
  return sum;
}

TEST(ThickRing, DiametralPinchMatchesRoark) {
  const ThickRingSection rim = seed003_rim();
  const double load = 1000.0, exact = roark_pinch(rim, load);
  const double series = harmonic_pinch(rim, load, 0, 400000);
  const double ei = rim.youngs_modulus * rim.area_moment;
  const double thin = (pi / 4 - 2 / pi) * load * std::pow(rim.radius, 3) / ei;
  std::printf("[ thick ring ] pinch by %.0f N: harmonics %.9g um, Roark %.9g um (thin ring %.6g um)\n", load,
              1e6 * series, 1e6 * exact, 1e6 * thin);
  EXPECT_GT(exact / thin - 1, 5e-3);  // extension and shear matter here
  EXPECT_NEAR(series, exact, 1e-6 * exact);
}

// The model's rim (the scene's section, 40 modes): the pinch's projection, the modes at rest and
// the displacement read back, short of Roark by the series beyond n = 40.
TEST(ThickRing, ModelRimPinchFallsShortByTheTail) {
  scene::Scene s = test::load_job_scene("seed003_no_carrier.toml");
  s.outer_ring.flexibility = scene::RingFlexibility::ring_modes;
  s.outer_ring.rim_theory = scene::BeamTheory::timoshenko;
  s.outer_ring.modes = 40;
  const Model m = build_model(s);
  const RingModes& modes = *ring_modes_of(m);
  const RimRing& rim = modes.rim();
  ASSERT_EQ(modes.count(), 41);  // n = 0..40
  const double load = 1000.0;
  std::vector<double> q(2 * static_cast<std::size_t>(modes.count()), 0.0);
  RimPoint at0, at_pi;
  at_pi.cos_theta = -1;
  const double inward0[2] = {-load, 0.0}, inward_pi[2] = {load, 0.0};
  add_modal_forces(modes, at0, inward0, q.data());
  add_modal_forces(modes, at_pi, inward_pi, q.data());
  std::vector<double> z(static_cast<std::size_t>(m.state_size), 0.0);
  for (int k = 0; k < modes.count(); ++k)
    for (int i = 0; i < 2; ++i)
      z[static_cast<std::size_t>(modes.state(k, i))] =
          q[static_cast<std::size_t>(2 * k + i)] / rim.stiffness[static_cast<std::size_t>(k)];
  auto radial = [&](double x) {
    contact::PlanarKinematics centre, roller;
    roller.x = x;
    const RimPoint p = rim_point(modes, centre, roller, z.data());
    return p.u[0] * p.cos_theta + p.u[1] * p.sin_theta;
  };
  const double shortening = -(radial(0.05) + radial(-0.05));
  const scene::Material& steel = s.material(s.bearing.ring_material);
  const ThickRingSection section = rectangular_ring(rim.radius, rim.thickness, rim.width, steel.youngs_modulus,
                                                    steel.poisson_ratio, rim.mass_per_length);
  const double exact = roark_pinch(section, load), tail = harmonic_pinch(section, load, 42, 400000);
  std::printf("[ thick ring ] model rim, 40 modes: %.9g um, Roark %.9g um, tail beyond 40 %.4g um\n", 1e6 * shortening,
              1e6 * exact, 1e6 * tail);
  EXPECT_NEAR(shortening + tail, exact, 1e-6 * exact);
}

TEST(ThickRing, ThinSectionIsLovesRing) {
  const ThickRingSection thin = rectangular_ring(0.1, 1e-4, 1e-2, 2e11, 0.3, 1.0);
  const double ei = thin.youngs_modulus * thin.area_moment;
  for (int n = 2; n <= 8; ++n) {
    const RingHarmonic h = thick_ring_harmonic(thin, n);
    const double nn = n * n, love = pi * ei * (nn - 1) * (nn - 1) / std::pow(thin.radius, 3);
    EXPECT_NEAR(h.stiffness, love, 1e-4 * love) << n;  // shear and extension: ~ n^2 (t / R)^2 = 6e-5 at n = 8
    EXPECT_NEAR(h.tangential, -1.0 / n, 1e-6) << n;
    EXPECT_NEAR(h.mass, pi * thin.radius * (1 + 1 / nn), 1e-5 * h.mass) << n;
  }
}

/// The full problem of harmonic n >= 1 (strain rows as in thick_ring.hpp, written out here).
Eigen::Matrix3d full_stiffness(const ThickRingSection& r, int n) {
  const double R = r.radius, alpha = r.area_moment / (r.area * R * R);
  Eigen::Vector3d eps(1 / R, n / R, 0), kappa(-1 / (R * R), -n / (R * R), n / R), gamma(-n / R, -1 / R, 1);
  return pi * R *
         (r.youngs_modulus * r.area * eps * eps.transpose() +
          r.youngs_modulus * r.area_moment / (1 - alpha) * kappa * kappa.transpose() +
          r.shear_coefficient * r.shear_modulus * r.area * gamma * gamma.transpose());
}

TEST(ThickRing, FrequencyBoundsTheFullHarmonic) {
  const ThickRingSection rim = seed003_rim();
  for (int n = 2; n <= 8; ++n) {
    const RingHarmonic h = thick_ring_harmonic(rim, n);
    const Eigen::Vector3d masses(rim.mass_per_length, rim.mass_per_length, rim.rotary_per_length);
    const Eigen::Matrix3d mass = pi * rim.radius * masses.asDiagonal().toDenseMatrix();
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix3d> solver(full_stiffness(rim, n), mass);
    const double exact = std::sqrt(solver.eigenvalues()(0)), rayleigh = std::sqrt(h.stiffness / h.mass);
    std::printf("[ thick ring ] n = %d: %.2f Hz (full harmonic %.2f Hz)\n", n, rayleigh / (2 * pi), exact / (2 * pi));
    EXPECT_GE(rayleigh, exact * (1 - 1e-12));
    EXPECT_LT(rayleigh, 1.01 * exact);
  }
}

/// A clamped-clamped Timoshenko bar by finite elements: stiffness and mass over (w, psi) per node.
struct BarModel {
  Eigen::MatrixXd k, m;
  Eigen::VectorXd unit_load;  ///< a uniform load of total 1 N
  double element = 0;
};
BarModel bar_model(const BridgeBeam& b, double density, int elements) {
  const int nodes = elements + 1, n = 2 * (nodes - 2);  // the two ends clamped
  BarModel out{Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n), Eigen::VectorXd::Zero(n), b.span / elements};
  const double h = out.element, area = b.thickness * b.height;
  const double ei = b.youngs_modulus * b.area_moment, shear = b.shear_coefficient * b.shear_modulus * area;
  const Eigen::Vector4d curvature(0, -1 / h, 0, 1 / h), gamma(-1 / h, -0.5, 1 / h, -0.5);  // at the middle
  Eigen::Matrix4d ke = h * (ei * curvature * curvature.transpose() + shear * gamma * gamma.transpose());
  Eigen::Matrix4d me = Eigen::Matrix4d::Zero();
  for (int d = 0; d < 2; ++d) {
    const double rho = density * (d == 0 ? area : b.area_moment) * h / 6;
    me(d, d) = me(d + 2, d + 2) = 2 * rho, me(d, d + 2) = me(d + 2, d) = rho;
  }
  for (int e = 0; e < elements; ++e) {
    auto dof = [&](int local) {
      const int node = e + local / 2;
      return node == 0 || node == nodes - 1 ? -1 : 2 * (node - 1) + local % 2;
    };
    for (int i = 0; i < 4; ++i) {
      if (dof(i) < 0) continue;
      if (i % 2 == 0) out.unit_load(dof(i)) += 0.5 * h / b.span;
      for (int j = 0; j < 4; ++j)
        if (dof(j) >= 0) out.k(dof(i), dof(j)) += ke(i, j), out.m(dof(i), dof(j)) += me(i, j);
    }
  }
  return out;
}

TEST(TimoshenkoBar, StiffnessAndFrequencyMatchTheFiniteElementBar) {
  scene::Scene s = test::load_job_scene("seed003_flexible_bridges.toml");
  s.cage.bridge_damping_ratio = 0;
  s.cage.bridge_height = 7.4e-3;  // the scene's bars: the cage's radial section
  const BridgeBeam bar = bridge_beam(s, 0.0);
  s.cage.bridge_theory = scene::BeamTheory::euler_bernoulli;
  const BridgeBeam slender = bridge_beam(s, 0.0);
  const double density = s.material(s.cage.material).density;
  ASSERT_GT(bar.shear_coefficient, 0.8);

  const BarModel fe = bar_model(bar, density, 400);
  const Eigen::VectorXd w = fe.k.ldlt().solve(fe.unit_load);
  const double mean = w.dot(fe.unit_load);  // the load's work: sum of nodal w h / L = the mean deflection
  const double fe_stiffness = 1.0 / mean;

  const BarModel coarse = bar_model(bar, density, 150);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(coarse.k, coarse.m);
  const double fe_omega = std::sqrt(solver.eigenvalues()(0));
  const double omega = std::sqrt(bar.stiffness / bar.modal_mass);
  const double slender_omega = std::sqrt(slender.stiffness / slender.modal_mass);
  std::printf("[ bar ] %.3g x %.3g mm over %.3g mm, k_s %.4f: k %.5g N/m (finite elements %.5g; slender %.5g, "
              "ratio %.4f); first mode %.2f kHz (finite elements %.2f; slender %.2f)\n",
              1e3 * bar.thickness, 1e3 * bar.height, 1e3 * bar.span, bar.shear_coefficient, bar.stiffness,
              fe_stiffness, slender.stiffness, bar.stiffness / slender.stiffness, omega / (2e3 * pi),
              fe_omega / (2e3 * pi), slender_omega / (2e3 * pi));
  EXPECT_NEAR(bar.stiffness, fe_stiffness, 1e-4 * fe_stiffness);
  EXPECT_GT(omega, fe_omega * (1 - 1e-4));  // Rayleigh's bound
  EXPECT_LT(omega, 1.01 * fe_omega);
  EXPECT_LT(bar.stiffness, 0.7 * slender.stiffness);  // the stubby bar's shear is no detail
}

}  // namespace
}  // namespace raceway::bearing
