// The flexible outer ring (solver/bearing/ring_modes.hpp): a thin rim whose inextensional bending
// modes n = 2..N are states.
//  - Static: two opposite radial point loads P (a diametral pinch) on the modal ring, each mode at
//    rest under its generalized force, against the thin-ring result (Roark, docs/references.md) for the shortening of
//    the loaded diameter, (pi/4 - 2/pi) P R^3 / (E I), computed here from the scene; and the modal
//    sum's convergence: its error is the tail sum_{even n > N} 1/(n^2 - 1)^2 of the exact series.
//  - The free frequency of each mode against the classic ring frequency
//    omega_n^2 = E I n^2 (n^2 - 1)^2 / (mu R^4 (n^2 + 1)).
//  - Work conjugacy: the generalized force the contacts put on a mode equals minus the derivative
//    of the contacts' elastic energy with respect to its amplitude (a conservative contact).
//  - Energy balance of a free vibration of the rim pinching the rollers, undamped and frictionless,
//    integrated here by a classic Runge-Kutta method: energy moves between the rim and the rollers
//    and the total stays put.
//  - The Jacobian (the modes' rows and columns through the rim's displacement and the contacts'
//    azimuths) against central differences of the right-hand side.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "scheduler/executor.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/ring_modes.hpp"
#include "solver/bearing/startup.hpp"
#include "solver/numerics/bordered_matrix.hpp"
#include "tests/support/solver_test_support.hpp"

namespace raceway::bearing {
namespace {

/// Seed 003's bearing without the carrier, its outer ring a modal rim, dry race contacts.
/// Love's thin ring unless `theory` says otherwise.
scene::Scene rim_scene(int modes, bool conservative, scene::BeamTheory theory = scene::BeamTheory::euler_bernoulli) {
  scene::Scene s = test::load_job_scene("seed003_no_carrier.toml");
  s.outer_ring.flexibility = scene::RingFlexibility::ring_modes;
  s.outer_ring.rim_theory = theory;
  s.outer_ring.modes = modes;
  s.outer_ring.rim_damping_ratio = conservative ? 0.0 : 0.02;
  s.roller_race.normal.id = contact::LawId::palmgren;
  s.roller_cage.normal.id = contact::LawId::palmgren;
  if (conservative) {
    s.outer_ring.load.fy = scene::TimeFunction::constant(0.0);
    for (scene::ContactSpec* c : {&s.roller_race, &s.roller_cage, &s.cage_land}) {
      c->damping.id = contact::LawId::no_damping, c->damping.factor = 0;
      c->traction.id = contact::LawId::no_traction, c->traction.friction_coefficient = 0;
    }
  } else {
    s.roller_race.traction.id = contact::LawId::tanh_traction;
    s.roller_race.traction.slip_velocity_scale = 0.5;  // smooth at the test's slips
  }
  return s;
}

/// A rim scene's model and equations.
struct RimBearing {
  RimBearing(int modes, bool conservative, scene::BeamTheory theory = scene::BeamTheory::euler_bernoulli)
      : scene(rim_scene(modes, conservative, theory)), m(build_model(scene)), eq(m, ex) {}
  scene::Scene scene;
  Model m;
  scheduler::SerialExecutor ex;
  Equations eq;
};

/// The rim's section from the scene, independently of the builder.
struct Section {
  double radius, bending_stiffness, mass_per_length;
};
Section section_of(const scene::Scene& s, const Model& m) {
  const double race = 0.5 * s.bearing.outer_race_diameter();
  const double thickness = 0.5 * s.bearing.outer_outside_diameter - race;
  const double width = s.bearing.roller_length;
  const double radius = race + 0.5 * thickness;
  const double e = s.material(s.bearing.ring_material).youngs_modulus;
  return {radius, e * width * thickness * thickness * thickness / 12.0,
          m.bodies[static_cast<std::size_t>(m.outer_ring)].mass / (2 * test::pi * radius)};
}

double modal_stiffness(const Model& m, int n) {
  for (const Segment& seg : m.segments)
    if (seg.kind == SegmentKind::outer_ring_mode && seg.name == "outer_ring_mode[" + std::to_string(n) + "]")
      return m.law<RingModeSpring>(seg).stiffness;
  ADD_FAILURE() << "no mode " << n;
  return 0;
}

/// Mode index k's states (amplitudes a, b, rates) and modal mass.
struct Mode {
  std::size_t a, b, va, vb;
  double mass;
};
Mode mode(const Model& m, int k) {
  const RingModes& modes = *ring_modes_of(m);
  auto at = [&](int i) { return static_cast<std::size_t>(modes.state(k, i)); };
  return {at(0), at(1), at(2), at(3), modes.rim().mass[static_cast<std::size_t>(k)]};
}
int mode_count(const Model& m) { return ring_modes_of(m) ? ring_modes_of(m)->count() : 0; }
/// Mode index k's n and stiffness; the index of mode n.
int order(const Model& m, int k) { return ring_modes_of(m)->rim().order[static_cast<std::size_t>(k)]; }
double stiffness_of_mode(const Model& m, int k) { return modal_stiffness(m, order(m, k)); }
int mode_index(const Model& m, int n) {
  for (int k = 0; k < mode_count(m); ++k)
    if (order(m, k) == n) return k;
  ADD_FAILURE() << "no mode " << n;
  return 0;
}
/// The tests of the modes' coupling run for the thin ring and the thick one (n = 0, 1 as well).
constexpr scene::BeamTheory both_theories[] = {scene::BeamTheory::euler_bernoulli, scene::BeamTheory::timoshenko};
const char* theory_name(scene::BeamTheory t) { return t == scene::BeamTheory::timoshenko ? "thick" : "thin"; }

/// At rest: every velocity zero, the rim round.
std::vector<double> rest_state(const Model& m) {
  std::vector<double> z = initial_state(m, 0.0).state;
  for (std::size_t i = 0; i < z.size(); ++i)
    if (m.state_class[i] == VariableClass::velocity || m.state_class[i] == VariableClass::angular_velocity) z[i] = 0;
  return z;
}

double& state(std::vector<double>& z, const Body& b, Coordinate c) { return z[static_cast<std::size_t>(b.slot[c])]; }

TEST(RingModes, DiametralPinchMatchesTheThinRingAndConverges) {
  const double load = 1000.0;
  double previous_error = 1;
  for (int modes : {4, 8, 16, 40}) {
    const scene::Scene scene = rim_scene(modes, true);
    const Model m = build_model(scene);
    ASSERT_EQ(mode_count(m), modes - 1);
    const Section sec = section_of(scene, m);
    // The loads' generalized forces by the model's projection: inward at theta = 0 and pi.
    std::vector<double> q(2 * static_cast<std::size_t>(mode_count(m)), 0.0);
    RimPoint at0, at_pi;
    at_pi.cos_theta = -1;
    const double inward0[2] = {-load, 0.0}, inward_pi[2] = {load, 0.0};
    add_modal_forces(*ring_modes_of(m), at0, inward0, q.data());
    add_modal_forces(*ring_modes_of(m), at_pi, inward_pi, q.data());
    // Each mode at rest: k_n a_n = Q_n.
    std::vector<double> z(static_cast<std::size_t>(m.state_size), 0.0);
    for (int k = 0; k < mode_count(m); ++k) {
      const Mode md = mode(m, k);
      z[md.a] = q[2 * static_cast<std::size_t>(k)] / stiffness_of_mode(m, k);
      z[md.b] = q[2 * static_cast<std::size_t>(k) + 1] / stiffness_of_mode(m, k);
    }
    // The rim's radial displacement at both loads, as a contact there sees it.
    contact::PlanarKinematics centre;
    auto radial = [&](double x) {
      contact::PlanarKinematics roller;
      roller.x = x;
      const RimPoint p = rim_point(*ring_modes_of(m), centre, roller, z.data());
      return p.u[0] * p.cos_theta + p.u[1] * p.sin_theta;
    };
    const double shortening = -(radial(0.05) + radial(-0.05));
    const double exact = (test::pi / 4 - 2 / test::pi) * load * sec.radius * sec.radius * sec.radius /
                         sec.bending_stiffness;
    double tail = 0;  // of sum_{even n >= 2} 1 / (n^2 - 1)^2 = (pi^2 - 8) / 16
    for (double n = modes % 2 ? modes + 1 : modes + 2; n < 2e5; n += 2) tail += 1.0 / ((n * n - 1) * (n * n - 1));
    const double predicted = tail / ((test::pi * test::pi - 8) / 16);
    const double error = (exact - shortening) / exact;
    std::printf("[ rim ] diametral pinch %g N, modes 2..%d: shortening %.6f um, thin ring %.6f um, error %.3g "
                "(series tail %.3g)\n",
                load, modes, 1e6 * shortening, 1e6 * exact, error, predicted);
    EXPECT_GT(error, 0.0);  // the modal sum approaches from below
    EXPECT_NEAR(error, predicted, 1e-9);
    EXPECT_LT(error, previous_error / 5);  // towards (2N / N)^3 = 8 per doubling
    previous_error = error;
  }
  EXPECT_LT(previous_error, 3e-5);  // 40 modes
}

TEST(RingModes, FrequenciesMatchTheClassicRing) {
  RimBearing rb(8, true);
  const scene::Scene& scene = rb.scene;
  const Model& m = rb.m;
  Equations& eq = rb.eq;
  const Section sec = section_of(scene, m);
  for (int n = 2; n <= 8; ++n) {
    std::vector<double> z = rest_state(m), zdot(z.size());  // the rollers clear of the outer race
    const Mode md = mode(m, n - 2);
    const double amplitude = 0.2e-6;
    z[md.b] = amplitude;
    ASSERT_EQ(eq.rhs(0.0, z.data(), zdot.data()), 0);
    const double omega = std::sqrt(-zdot[md.vb] / amplitude);
    const double nn = n * n;
    const double exact = std::sqrt(sec.bending_stiffness * nn * (nn - 1) * (nn - 1) /
                                   (sec.mass_per_length * std::pow(sec.radius, 4) * (nn + 1)));
    std::printf("[ rim ] mode %d: %.2f Hz, thin ring %.2f Hz\n", n, omega / (2 * test::pi), exact / (2 * test::pi));
    EXPECT_NEAR(omega, exact, 1e-9 * exact);
  }
}

/// At rest with the outer ring centred on the inner ring.
std::vector<double> centred_rest_state(const Model& m) {
  std::vector<double> z = rest_state(m);
  const Body& ring = m.bodies[static_cast<std::size_t>(m.outer_ring)];
  state(z, ring, sx) = state(z, ring, sy) = 0;
  return z;
}

/// A pinched rim: the outer ring centred, roller 0 pressed into the race, the modes deflected.
std::vector<double> pinched_state(const Model& m) {
  std::vector<double> z = centred_rest_state(m);
  const Body& roller = m.bodies[static_cast<std::size_t>(m.first_element)];
  const double r = m.outer_race_radius - m.element_radius + 12e-6;  // 12 um into the round race
  const double theta = std::atan2(state(z, roller, sy), state(z, roller, sx));
  state(z, roller, sx) = r * std::cos(theta), state(z, roller, sy) = r * std::sin(theta);
  for (int k = 0; k < mode_count(m); ++k) {
    const Mode md = mode(m, k);
    z[md.a] = 1.5e-6 / (k + 1), z[md.b] = -0.8e-6 / (k + 1);
  }
  return z;
}

TEST(RingModes, GeneralizedForceIsTheWorkConjugate) {
  for (const scene::BeamTheory theory : both_theories) {
    SCOPED_TRACE(theory_name(theory));
    RimBearing rb(6, true, theory);
    const Model& m = rb.m;
    Equations& eq = rb.eq;
    std::vector<double> z = pinched_state(m), zdot(z.size());
    constexpr int energy_field = contact::field_index(contact::line_diagnostic_fields, "elastic_energy");
    auto race_energy = [&](const std::vector<double>& zz) {
      std::vector<double> f(zz.size());
      EXPECT_EQ(eq.rhs(0.0, zz.data(), f.data()), 0);
      double e = 0;
      for (std::size_t s = 0; s < m.segments.size(); ++s)
        if (m.segments[s].kind == SegmentKind::roller_outer_race) e += eq.diagnostic(s, energy_field);
      return e;
    };
    ASSERT_GT(race_energy(z), 1e-3);  // roller 0 is loaded (some kN)
    std::vector<std::pair<double, double>> forces;  // generalized, -dU/da
    for (int k = 0; k < mode_count(m); ++k) {
      const Mode md = mode(m, k);
      for (Coordinate c : {sx, sy}) {
        ASSERT_EQ(eq.rhs(0.0, z.data(), zdot.data()), 0);
        // The contacts' generalized force: the mode's acceleration times its mass, less its spring.
        const std::size_t amplitude = c == sx ? md.a : md.b;
        const double rate = zdot[c == sx ? md.va : md.vb];
        const double generalized = md.mass * rate + stiffness_of_mode(m, k) * z[amplitude];
        const double h = 1e-9, a = z[amplitude];
        std::vector<double> zp = z;
        zp[amplitude] = a + h;
        const double ep = race_energy(zp);
        zp[amplitude] = a - h;
        const double em = race_energy(zp);
        const double conjugate = -(ep - em) / (2 * h);
        std::printf("[ rim ] mode %d %s: generalized force %.6f N, -dU/da %.6f N\n", order(m, k),
                    c == sx ? "cos" : "sin", generalized, conjugate);
        forces.emplace_back(generalized, conjugate);
      }
    }
    double largest = 0;
    for (const auto& [g, c] : forces) largest = std::max(largest, std::abs(c));
    ASSERT_GT(largest, 1000.0);
    for (const auto& [g, c] : forces) EXPECT_NEAR(g, c, 1e-7 * largest);
  }
}

TEST(RingModes, FreeVibrationConservesEnergy) {
  for (const scene::BeamTheory theory : both_theories) {
    SCOPED_TRACE(theory_name(theory));
    RimBearing rb(6, true, theory);
    const Model& m = rb.m;
    Equations& eq = rb.eq;
    std::vector<double> z = centred_rest_state(m);
    // Pinch the rim inward at the azimuth of roller 0 and its opposite (mode 2 alone).
    const Body& roller = m.bodies[static_cast<std::size_t>(m.first_element)];
    const double theta = std::atan2(state(z, roller, sy), state(z, roller, sx));
    const Mode mode2 = mode(m, mode_index(m, 2));
    z[mode2.a] = -20e-6 * std::cos(2 * theta), z[mode2.b] = -20e-6 * std::sin(2 * theta);
    const std::size_t n = z.size();
    std::vector<double> k1(n);
    auto f = [&](double t, const std::vector<double>& y, std::vector<double>& out) {
      ASSERT_EQ(eq.rhs(t, y.data(), out.data()), 0);
    };
    auto mode_energy = [&](const std::vector<double>& y) {
      double e = 0;
      for (int k = 0; k < mode_count(m); ++k) {
        const Mode md = mode(m, k);
        const double a = y[md.a], bb = y[md.b], va = y[md.va], vb = y[md.vb];
        e += 0.5 * stiffness_of_mode(m, k) * (a * a + bb * bb) + 0.5 * md.mass * (va * va + vb * vb);
      }
      return e;
    };
    f(0.0, z, k1);
    const double e0 = eq.energy(0.0, z.data()), rim0 = mode_energy(z);
    double largest_drift = 0, exchanged = 0;
    const double dt = 5e-8;
    double t = 0;
    for (int step = 0; step < 10000; ++step) {  // 0.5 ms: half a period of mode 2
      test::runge_kutta_step(f, t, dt, z);
      t += dt;
      if (step % 100 == 99) {
        f(t, z, k1);
        largest_drift = std::max(largest_drift, std::abs(eq.energy(t, z.data()) - e0));
        exchanged = std::max(exchanged, std::abs(mode_energy(z) - rim0));
      }
    }
    std::printf("[ rim ] free vibration over %.2f ms: energy %.6g J, largest drift %.3g J; the rim's energy %.4g J "
                "changed by up to %.4g J (exchanged with the rollers)\n",
                1e3 * t, e0, largest_drift, rim0, exchanged);
    ASSERT_GT(exchanged, 1e-3 * rim0);  // the rim and the rollers exchange energy
    EXPECT_LT(largest_drift, 1e-3 * exchanged);
  }
}

TEST(RingModes, JacobianMatchesCentralDifferences) {
  for (const scene::BeamTheory theory : both_theories) {
    SCOPED_TRACE(theory_name(theory));
    RimBearing rb(5, false, theory);
    const Model& m = rb.m;
    const Body& roller = m.bodies[static_cast<std::size_t>(m.first_element)];
    std::vector<double> z = pinched_state(m);
    Equations& eq = rb.eq;
    state(z, roller, svx) = 0.02, state(z, roller, svy) = -0.03, state(z, roller, swz) = 5.0;  // sliding, approaching
    for (int k = 0; k < mode_count(m); ++k) {
      const Mode md = mode(m, k);
      z[md.va] = 0.004 / (k + 1), z[md.vb] = 0.003;
    }
    numerics::BorderedMatrix jac(m.border_size, m.element_count, m.block_size);
    ASSERT_EQ(eq.jacobian(0.0, z.data(), jac), 0);
    const Eigen::MatrixXd model = jac.to_dense();
    const Eigen::MatrixXd fd = test::central_difference_jacobian(eq, m, 0.0, z);
    // The border (ring, modes, cage) and roller 0's block, which presses on the rim.
    const int n = roller.offset + roller.size;
    const double scale = fd.topLeftCorner(n, n).cwiseAbs().maxCoeff();
    Eigen::Index worst_row = 0, worst_col = 0;
    const double error = (model - fd).topLeftCorner(n, n).cwiseAbs().maxCoeff(&worst_row, &worst_col);
    std::printf("[ rim ] Jacobian: largest entry %.4g, largest error %.3g at d %s / d %s (%.6g against %.6g)\n", scale,
                error, m.state_name[static_cast<std::size_t>(worst_row)].c_str(),
                m.state_name[static_cast<std::size_t>(worst_col)].c_str(), model(worst_row, worst_col),
                fd(worst_row, worst_col));
    // The blocks that carry the rim, each against its own scale: the modes' rows from the roller's
    // states (its force and its azimuth) and from the modes' (through the contact); the roller's and
    // the ring's rows from the modes' states (through the rim's displacement at the contact).
    const Body& ring = m.bodies[static_cast<std::size_t>(m.outer_ring)];
    const int modes_begin = static_cast<int>(mode(m, 0).a), modes_size = 4 * mode_count(m);
    struct Block {
      const char* name;
      int row, rows, col, cols;
    };
    for (const Block& b : {Block{"modes / roller", modes_begin, modes_size, roller.offset, roller.size},
                           Block{"modes / modes", modes_begin, modes_size, modes_begin, modes_size},
                           Block{"roller / modes", roller.offset, roller.size, modes_begin, modes_size},
                           Block{"ring / modes", ring.offset, ring.size, modes_begin, modes_size}}) {
      const Eigen::MatrixXd f = fd.block(b.row, b.col, b.rows, b.cols);
      const Eigen::MatrixXd d = model.block(b.row, b.col, b.rows, b.cols) - f;
      const double block_scale = f.cwiseAbs().maxCoeff(), block_error = d.cwiseAbs().maxCoeff();
      std::printf("[ rim ] %s: largest entry %.4g, largest error %.3g\n", b.name, block_scale, block_error);
      EXPECT_GT(block_scale, 1e3) << b.name;
      EXPECT_LT(block_error, 1e-5 * block_scale) << b.name;
    }
    EXPECT_LT(error, 1e-5 * scale);
  }
}

}  // namespace
}  // namespace raceway::bearing
