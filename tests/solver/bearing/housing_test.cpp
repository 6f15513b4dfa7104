// The housing under a ball bearing's outer ring (solver/bearing/housing.hpp) and a race's spall in
// the model (solver/bearing/race_defects.hpp): the Jacobian, assembled through the housing's marker
// and its own terms, against central differences of the right-hand side over every state (a spall
// under a ball among them); the housing's static deflection under the bearing's load; and the step
// limit against a ball's distance to a spall.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "io/scene/scene_parser.hpp"
#include "scheduler/executor.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/housing.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/race_defects.hpp"
#include "solver/bearing/startup.hpp"
#include "solver/numerics/bordered_matrix.hpp"
#include "solver/numerics/integrator.hpp"
#include "tests/support/solver_test_support.hpp"

namespace raceway::bearing {
namespace {

constexpr const char* kScene = R"([scene]
end_time = "20 ms"
output_interval = "1 ms"
[bearing]
designation = "6205"
[inner_ring]
speed = "3000 rpm"
load = { fy = "-375 N" }
[outer_ring]
spall = { angle = "-90 deg", length = "1 mm", width = "2 mm", depth = "0.1 mm", edge = "smooth" }
[housing]
mass = "2 kg"
stiffness = "500 MN/m"
damping = "3000 N s/m"
sensor_interval = "100 us"
)";

/// The scene, without its spall where `spall` is false.
std::string scene_text(bool spall) {
  std::string text = kScene;
  if (!spall) text.erase(text.find("spall = "), text.find('\n', text.find("spall = ")) - text.find("spall = ") + 1);
  return text;
}

/// The scene without its spall and with a second housing mode at the seat (7.1 kHz alone), the sensor
/// off the seat (it reads the second mode at -0.5).
std::string two_mode_scene_text() {
  return scene_text(false) +
         "sensor_participation = [1.0, -0.5]\n"
         "modes = { masses = [\"0.5 kg\"], stiffnesses = [\"1000 MN/m\"], dampings = [\"2000 N s/m\"] }\n";
}

struct HousedBearing {
  explicit HousedBearing(bool spall = true) : HousedBearing(scene_text(spall)) {}
  explicit HousedBearing(const std::string& text) : scene(scene::parse_scene(text, "housing_test")) {
    executor.attach(eq.task_catalogue());
  }
  scene::Scene scene;
  Model model = build_model(scene);
  scheduler::SerialExecutor executor;
  Equations eq{model, executor};
  std::vector<double> start = initial_state(model, 0.0).state;
  std::vector<double> after(double t) {
    std::vector<double> z;
    numerics::Integrator integrator(eq, scene.solver, 0.0, start);
    integrator.advance_to(t, z);
    return z;
  }
};

/// Worst column error of the model Jacobian against central differences (relative to the column,
/// or to its class's largest column where the column is near zero).
double jacobian_error(Equations& eq, const Model& m, double t, const std::vector<double>& z) {
  const Eigen::MatrixXd fd = test::central_difference_jacobian(eq, m, t, z);
  numerics::BorderedMatrix jac(m.border_size, m.element_count, m.block_size);
  EXPECT_EQ(eq.jacobian(t, z.data(), jac), 0);
  const Eigen::MatrixXd dense = jac.to_dense();
  double class_norm[4] = {0, 0, 0, 0};
  for (int j = 0; j < m.state_size; ++j) {
    double& c = class_norm[static_cast<int>(m.state_class[static_cast<std::size_t>(j)])];
    c = std::max(c, fd.col(j).norm());
  }
  double worst = 0;
  int worst_column = 0;
  for (int j = 0; j < m.state_size; ++j) {
    const int c = static_cast<int>(m.state_class[static_cast<std::size_t>(j)]);
    const double diff = (dense.col(j) - fd.col(j)).norm(), ref = fd.col(j).norm();
    const double e = ref > 1e-9 * class_norm[c] ? diff / ref : diff / class_norm[c];
    if (e > worst) worst = e, worst_column = j;
  }
  std::printf("[ housing ] t = %g s: worst column error %.3g (%s)\n", t, worst,
              m.state_name[static_cast<std::size_t>(worst_column)].c_str());
  // The housing's rows depend on the balls through the outer-race contacts: the coupling is there,
  // and right on its own (the columns above are dominated by the housing's own spring).
  const Housing* h = housing_of(m);
  const int balls = m.state_size - m.border_size;
  const Eigen::MatrixXd coupling = fd.block(h->state(2), m.border_size, 2, balls);
  EXPECT_GT(coupling.cwiseAbs().maxCoeff(), 0.0);
  const double coupling_error = (dense.block(h->state(2), m.border_size, 2, balls) - coupling).norm() / coupling.norm();
  std::printf("[ housing ] t = %g s: the housing's rows over the balls' columns: error %.3g\n", t, coupling_error);
  EXPECT_LT(coupling_error, 1e-3);
  return worst;
}

// The tolerance of tests/solver/bearing/spatial_newton_test.cpp (1e-3 of a column's norm: forward
// differences per segment against central differences of the whole right-hand side).
TEST(Housing, JacobianMatchesCentralDifferences) {
  HousedBearing b;
  EXPECT_LT(jacobian_error(b.eq, b.model, 0.0, b.start), 1e-3);
  EXPECT_LT(jacobian_error(b.eq, b.model, 4e-3, b.after(4e-3)), 1e-3);
}

// Settled (a perfect race), the housing carries the bearing's load on its spring: u_y = -(F + the weights the balls
// carry to it) / k, the weights of the inner ring, balls and cage (gravity is on: the 6205's
// first-scene default). Averaged over 2 ms (a housing period is 0.4 ms) after 8 ms (the ring-down
// of its start takes 1 / (zeta omega) = 0.6 ms).
TEST(Housing, StaticDeflectionIsTheLoadOverTheStiffness) {
  HousedBearing b(false);
  const Housing* h = housing_of(b.model);
  ASSERT_NE(h, nullptr);
  numerics::Integrator integrator(b.eq, b.scene.solver, 0.0, b.start);
  std::vector<double> z;
  double sum = 0;
  int n = 0;
  for (double t = 8e-3; t <= 10e-3 + 1e-12; t += 1e-5, ++n) {
    integrator.advance_to(t, z);
    sum += z[static_cast<std::size_t>(h->state(1))];
  }
  double weight = 0;
  for (const Body& body : b.model.bodies)
    if (body.kind != BodyKind::outer_ring) weight += body.mass * 9.80665;
  const double expected = -(375.0 + weight) / 500e6;
  EXPECT_NEAR(sum / n, expected, 0.01 * std::abs(expected));
  EXPECT_NEAR(h->mass(), 2.0 + b.model.bodies[static_cast<std::size_t>(b.model.outer_ring)].mass, 1e-12);
}

// Two modes: the Jacobian through the seat (the sum of the modes) and the modes' coupling through the
// ring's mass riding on the seat.
TEST(HousingModes, JacobianMatchesCentralDifferences) {
  HousedBearing b(two_mode_scene_text());
  ASSERT_EQ(housing_of(b.model)->mode_count(), 2);
  EXPECT_LT(jacobian_error(b.eq, b.model, 0.0, b.start), 1e-3);
  EXPECT_LT(jacobian_error(b.eq, b.model, 4e-3, b.after(4e-3)), 1e-3);
}

// Settled, each mode carries the seat's force on its own spring: the seat sinks by F (1/k_1 + 1/k_2)
// (the compliances add) and the sensor reads F (psi_1/k_1 + psi_2/k_2). Window as in the one-mode test.
TEST(HousingModes, StaticDeflectionAddsTheCompliances) {
  HousedBearing b(two_mode_scene_text());
  const Housing* h = housing_of(b.model);
  numerics::Integrator integrator(b.eq, b.scene.solver, 0.0, b.start);
  std::vector<double> z;
  double seat = 0, sensor = 0;
  int n = 0;
  for (double t = 8e-3; t <= 10e-3 + 1e-12; t += 1e-5, ++n) {
    integrator.advance_to(t, z);
    seat += h->seat(z.data(), 1), sensor += h->sensor(z.data(), 1);
  }
  double weight = 0;
  for (const Body& body : b.model.bodies)
    if (body.kind != BodyKind::outer_ring) weight += body.mass * 9.80665;
  const double force = -(375.0 + weight);
  const double expected_seat = force * (1 / 500e6 + 1 / 1e9), expected_sensor = force * (1 / 500e6 - 0.5 / 1e9);
  EXPECT_NEAR(seat / n, expected_seat, 0.01 * std::abs(expected_seat));
  EXPECT_NEAR(sensor / n, expected_sensor, 0.01 * std::abs(expected_sensor));
  EXPECT_NEAR(h->mass(), 2.0, 1e-12);  // with more than one mode the ring rides on the seat
}

// The undamped frequencies of two modes with the ring on the seat: det(K - w^2 M) = 0 with
// M = [[m1 + mr, mr], [mr, m2 + mr]], K = diag(k1, k2), a quadratic in w^2 solved here by hand.
TEST(HousingModes, FrequenciesSolveTheTwoDegreeOfFreedomProblem) {
  HousedBearing b(two_mode_scene_text());
  const Housing* h = housing_of(b.model);
  const double mr = b.model.bodies[static_cast<std::size_t>(b.model.outer_ring)].mass;
  const double m1 = 2.0, m2 = 0.5, k1 = 500e6, k2 = 1e9;
  const double qa = (m1 + mr) * (m2 + mr) - mr * mr, qb = -(k1 * (m2 + mr) + k2 * (m1 + mr)), qc = k1 * k2;
  const double root = std::sqrt(qb * qb - 4 * qa * qc);
  const double low = std::sqrt((-qb - root) / (2 * qa)) / (2 * std::numbers::pi);
  const double high = std::sqrt((-qb + root) / (2 * qa)) / (2 * std::numbers::pi);
  const std::vector<double> f = h->frequencies();
  ASSERT_EQ(f.size(), 2u);
  EXPECT_NEAR(f[0], low, 1e-9 * low);
  EXPECT_NEAR(f[1], high, 1e-9 * high);
  // One mode: the one-degree-of-freedom frequency with the ring's mass.
  HousedBearing one(false);
  EXPECT_NEAR(housing_of(one.model)->frequencies().front(), std::sqrt(500e6 / (2.0 + mr)) / (2 * std::numbers::pi), 1e-6);
}

// The housing's energy (the modes' and the ring's riding on the seat) changes at the rate the force
// on the ring does work on the seat less the dampers' loss: dE/dt = F . u' - sum_j c_j |q_j'|^2,
// dE/dt by central differences along the rates, at an arbitrary state of the modes.
TEST(HousingModes, EnergyChangesByTheForcesPowerLessTheDampersLoss) {
  HousedBearing b(two_mode_scene_text());
  const Housing* h = housing_of(b.model);
  std::vector<double> z(b.start.size(), 0.0), zdot(b.start.size(), 0.0);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 4; ++i) z[static_cast<std::size_t>(h->state(i, j))] = (i < 2 ? 1e-6 : 0.3) * (1 + i + 3 * j) * (j ? -1 : 1);
  const double forces[2] = {120.0, -450.0};
  h->rates(b.model, 0.0, z.data(), forces, zdot.data());
  const auto energy = [&](double step) {
    std::vector<double> y = z;
    for (std::size_t k = 0; k < y.size(); ++k) y[k] += step * zdot[k];
    double e = 0;
    h->add_energy(b.model, 0.0, y.data(), e);
    return e;
  };
  const double step = 1e-7, rate = (energy(step) - energy(-step)) / (2 * step);
  const double power = forces[0] * h->seat(z.data(), 2) + forces[1] * h->seat(z.data(), 3);
  const double loss = h->power_loss(b.model, 0.0, z.data());
  EXPECT_GT(loss, 0.0);
  EXPECT_NEAR(rate, power - loss, 1e-6 * (std::abs(power) + loss));
}

// A ball outside the spall may step to its edge at its speed relative to the race, not further; one
// within it a tenth of its passage.
TEST(Housing, SpallStepLimitReachesTheEdge) {
  HousedBearing b;
  const Model& m = b.model;
  ASSERT_TRUE(has_spall(m));
  const double limit = spall_step_limit(m, 0.0, b.start.data());
  // By hand: every ball's azimuth and its rate about the (fixed) outer ring.
  const double race = 0.5 * b.scene.bearing.outer_race_diameter();
  const double half = 0.5e-3 / race, start = -0.5 * std::numbers::pi - half;
  double expected = 1e300;
  for (int k = 0; k < m.element_count; ++k) {
    const auto ball = m.kinematics(m.first_element + k, 0.0, b.start.data());
    const double azimuth = std::atan2(ball.position.y(), ball.position.x());
    const double rate = (ball.position.x() * ball.velocity.y() - ball.position.y() * ball.velocity.x()) /
                        (ball.position.x() * ball.position.x() + ball.position.y() * ball.position.y());
    ASSERT_GT(rate, 0.0);
    const double within = 2 * half / rate / steps_within_spall;
    double past = std::fmod(azimuth - start, 2 * std::numbers::pi);
    if (past < 0) past += 2 * std::numbers::pi;
    expected = std::min(expected, past < 2 * half ? within : std::max(within, (2 * std::numbers::pi - past) / rate));
  }
  EXPECT_NEAR(limit, expected, 1e-9 * expected);
  EXPECT_GT(limit, 0.0);
}

}  // namespace
}  // namespace raceway::bearing
