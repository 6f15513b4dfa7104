// The spatial ball-bearing model's Newton linear algebra: Equations::jacobian against central
// differences of Equations::rhs over all states, with the bordered structure (no ball-ball
// coupling) of the true Jacobian; and the same run with dense and bordered Newton solves.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "solver/bearing/equations.hpp"
#include "solver/bearing/model.hpp"
#include "solver/numerics/bordered_matrix.hpp"
#include "solver/numerics/integrator.hpp"
#include "tests/support/engaged_bearing.hpp"
#include "tests/support/solver_test_support.hpp"

namespace raceway::bearing {
namespace {

using contact::Vec3;
using test::closed_contacts;
using test::describe_closed;
using test::EngagedBearing;
using test::seconds_since;

// ---------------------------------------------------------------------------------------------
// The Jacobian against central differences
// ---------------------------------------------------------------------------------------------

int ball_of(const Model& m, int state) {
  return state < m.border_size ? -1 : (state - m.border_size) / m.block_size;
}

/// Equations::jacobian at (t, z) against central differences of rhs over all states: the
/// worst column error ||J_j - D_j|| / ||D_j|| (a column that is (nearly) zero in D is measured
/// against the largest column of its variable class). Also checks the structure of D: no entry
/// couples two different balls, and every ball is coupled to the border.
double check_jacobian(Equations& eq, const Model& m, double t, const std::vector<double>& z,
                      const char* where) {
  std::vector<double> f(z.size());
  EXPECT_EQ(eq.rhs(t, z.data(), f.data()), 0);
  std::printf("[ jacobian ] %s: closed contacts: %s\n", where, describe_closed(m, closed_contacts(m, eq)).c_str());
  const Eigen::MatrixXd fd = test::central_difference_jacobian(eq, m, t, z);
  for (int i = m.border_size; i < m.state_size; ++i)
    for (int j = m.border_size; j < m.state_size; ++j)
      if (ball_of(m, i) != ball_of(m, j) && fd(i, j) != 0.0) {
        ADD_FAILURE() << where << ": " << m.state_name[static_cast<std::size_t>(i)] << " depends on "
                      << m.state_name[static_cast<std::size_t>(j)];
        return 1e300;
      }
  for (int k = 0; k < m.element_count; ++k) {
    const int first = m.border_size + k * m.block_size;
    EXPECT_GT(fd.block(first, 0, m.block_size, m.border_size).cwiseAbs().maxCoeff(), 0.0)
        << where << ": ball " << k << " is not coupled to the border";
  }
  numerics::BorderedMatrix jac(m.border_size, m.element_count, m.block_size);
  EXPECT_EQ(eq.jacobian(t, z.data(), jac), 0);
  const Eigen::MatrixXd dense = jac.to_dense();
  double class_norm[4] = {0, 0, 0, 0};
  for (int j = 0; j < m.state_size; ++j) {
    double& c = class_norm[static_cast<int>(m.state_class[static_cast<std::size_t>(j)])];
    c = std::max(c, fd.col(j).norm());
  }
  double worst = 0, worst_by_class[4] = {0, 0, 0, 0};
  int worst_column = -1;
  for (int j = 0; j < m.state_size; ++j) {
    const int c = static_cast<int>(m.state_class[static_cast<std::size_t>(j)]);
    const double diff = (dense.col(j) - fd.col(j)).norm(), ref = fd.col(j).norm();
    const double e = ref > 1e-9 * class_norm[c] ? diff / ref : diff / class_norm[c];
    if (e > worst) worst = e, worst_column = j;
    worst_by_class[c] = std::max(worst_by_class[c], e);
  }
  std::printf("[ jacobian ] %s: worst column error %.3g (%s); by class: position %.3g, angle %.3g, velocity %.3g, "
              "angular velocity %.3g\n",
              where, worst, worst_column >= 0 ? m.state_name[static_cast<std::size_t>(worst_column)].c_str() : "-",
              worst_by_class[0], worst_by_class[1], worst_by_class[2], worst_by_class[3]);
  return worst;
}

// Tolerance 1e-3 of the column norm. The model Jacobian is a FORWARD difference per segment (plus
// each body's own terms) with steps 1e-10 r_p = 3.6e-12 m for positions and 1e-7 of the state or of
// its scale (3.8 m/s, 435 rad/s) for rates, so its truncation error is about h / (4 delta) = 1e-7 for
// the Hertz contacts (delta >= 2 um) and h_v / s_scale = 1e-5 for the tanh traction: 1e-3 leaves a
// factor of 100 for contacts nearer their onset or steeper traction. Checked at three states: the
// start-up state, 2 ms later along the run (the balls have found their own spin and orbit) and the
// engaged state with pockets, cage land and a tilted cage.
void expect_jacobian_at_three_states(EngagedBearing& b, const std::string& label) {
  std::vector<double> later;
  {
    numerics::Integrator integrator(b.eq, b.scene.solver, 0.0, b.start);
    integrator.advance_to(2e-3, later);
  }
  EXPECT_LT(check_jacobian(b.eq, b.model, 0.0, b.start, (label + "start").c_str()), 1e-3);
  EXPECT_LT(check_jacobian(b.eq, b.model, 2e-3, later, (label + "t = 2 ms").c_str()), 1e-3);
  EXPECT_LT(check_jacobian(b.eq, b.model, 0.0, b.engaged, (label + "engaged cage").c_str()), 1e-3);
}

TEST(SpatialPhysics, JacobianMatchesFiniteDifferences) {
  EngagedBearing b;
  expect_jacobian_at_three_states(b, "");
}

// The same three states with the balls' in-plane velocities in their orbital frame ([solver]
// element_velocity_frame = "orbital", solver/bearing/orbital_frame.hpp): the positions' rows in
// v_r, v_theta and in the balls' positions (the frame's angle), the frame's turning terms, the
// contact forces turned into e_r, e_theta, and the contacts' dependence on v_r, v_theta.
TEST(SpatialPhysics, JacobianMatchesFiniteDifferencesInOrbitalFrame) {
  EngagedBearing b(0.0, scene::ElementVelocityFrame::orbital);
  expect_jacobian_at_three_states(b, "orbital frame, ");
}

// ---------------------------------------------------------------------------------------------
// Dense and bordered Newton solves
// ---------------------------------------------------------------------------------------------

struct Trajectory {
  std::vector<std::vector<double>> states;  ///< at every output time
  numerics::IntegratorStatistics stats;
};

/// The combined-load run of EngagedBearing from its start-up state, 10 ms, outputs every 0.1 ms;
/// the initial state optionally scaled by (1 + perturbation).
Trajectory integrate(scene::LinearSolverKind kind, double end_time, double perturbation = 0) {
  EngagedBearing b;
  b.scene.solver.linear_solver = kind;
  std::vector<double> z0 = b.start;
  for (double& v : z0) v *= 1 + perturbation;
  numerics::Integrator integrator(b.eq, b.scene.solver, 0.0, z0);
  Trajectory tr;
  const double dt = 1e-4;
  const long samples = std::lround(end_time / dt);
  for (long i = 1; i <= samples; ++i) {
    std::vector<double> z;
    integrator.advance_to(static_cast<double>(i) * dt, z);
    tr.states.push_back(z);
  }
  tr.stats = integrator.statistics();
  return tr;
}

struct TrajectoryDifference {
  double units = 0;  ///< largest |z_p - z_q| / (rtol max(|z_p|, |z_q|) + atol) over states and times
  int state = -1;
  double ring = 0;   ///< m, largest difference of the inner ring's centre
};

TrajectoryDifference difference(const Model& m, double rtol, const Trajectory& p, const Trajectory& q) {
  const auto atol = m.absolute_tolerance();
  const auto& inner = m.bodies[static_cast<std::size_t>(m.inner_ring)];
  TrajectoryDifference d;
  for (std::size_t i = 0; i < p.states.size(); ++i) {
    const auto& a = p.states[i];
    const auto& b = q.states[i];
    for (std::size_t j = 0; j < atol.size(); ++j) {
      const double units = std::abs(a[j] - b[j]) / (rtol * std::max(std::abs(a[j]), std::abs(b[j])) + atol[j]);
      if (units > d.units) d.units = units, d.state = static_cast<int>(j);
    }
    Vec3 dc = Vec3::Zero();
    for (int c = 0; c < 3; ++c) {
      const auto k = static_cast<std::size_t>(inner.slot[c]);
      dc[c] = a[k] - b[k];
    }
    d.ring = std::max(d.ring, dc.norm());
  }
  return d;
}

// The same run (combined load, 1000 rpm, 10 ms, rtol 1e-6) with CVODE's dense linear solver and with
// the bordered-block one: two correct solvers of the same Newton systems. They differ by round-off,
// and CVODE's step-size sequence forks at the first error test that round-off decides, so the
// trajectories cannot agree to a few tolerance units: a third run, bordered from the start state
// scaled by 1 + 1e-15, measures how far round-off alone carries them. Measured (rtol 1e-6 / 1e-8 /
// 1e-10): dense vs bordered 292 / 513 / 111 tolerance units, perturbed vs bordered 283 / 467 / 178,
// always in the velocity of a ball oscillating on its contacts; step counts 1278 vs 1296 (1.4 %),
// 1346 vs 1434 (6.5 %), 1723 vs 1718, the perturbed run 0.7 % / 4 % / 0.3 % off. So:
//  - dense vs bordered within 3 times the round-off baseline (+ 10 units), in tolerance units;
//  - the inner ring's centre (the physical result) within max(1e-9 m, 3 times the baseline)
//    (measured 1.5e-9 m, baseline 1.2e-9 m, of a 190 um displacement; with the rolling start-up,
//    whose balls start without sliding); a wrong linear solve gives a wrong Newton correction, which CVODE's
//    error test catches only at the cost of steps, so
//  - step counts within 5 % and Newton iterations per step within 5 % (a 2 % bound would hold
//    here, 1.4 %, but round-off alone moves the count by up to 4 % at other tolerances).
TEST(SpatialPhysics, DenseAndBorderedAgree) {
  const double end_time = 0.01;
  const auto wall = std::chrono::steady_clock::now();
  const Trajectory dense = integrate(scene::LinearSolverKind::sundials_dense, end_time);
  const Trajectory bordered = integrate(scene::LinearSolverKind::block_elimination, end_time);
  const Trajectory perturbed = integrate(scene::LinearSolverKind::block_elimination, end_time, 1e-15);
  const double seconds = seconds_since(wall);
  EngagedBearing b;
  const double rtol = b.scene.solver.rtol;
  const TrajectoryDifference solvers = difference(b.model, rtol, dense, bordered);
  const TrajectoryDifference baseline = difference(b.model, rtol, perturbed, bordered);
  auto name = [&](int j) { return j >= 0 ? b.model.state_name[static_cast<std::size_t>(j)].c_str() : "-"; };
  auto per_step = [](const numerics::IntegratorStatistics& s) {
    return static_cast<double>(s.newton_iterations) / static_cast<double>(s.steps);
  };
  const double step_ratio = static_cast<double>(bordered.stats.steps) / static_cast<double>(dense.stats.steps);
  std::printf("[ dense/bordered ] steps %ld dense, %ld bordered (ratio %.4f), %ld perturbed; Newton iterations per "
              "step %.4f / %.4f; dense vs bordered %.3g tolerance units (%s), ring %.3g m; round-off baseline %.3g "
              "units (%s), ring %.3g m; %.2f s wall for three runs\n",
              dense.stats.steps, bordered.stats.steps, step_ratio, perturbed.stats.steps, per_step(dense.stats),
              per_step(bordered.stats), solvers.units, name(solvers.state), solvers.ring, baseline.units,
              name(baseline.state), baseline.ring, seconds);
  EXPECT_LT(solvers.units, 3 * baseline.units + 10);
  EXPECT_LT(solvers.ring, std::max(1e-9, 3 * baseline.ring));
  EXPECT_NEAR(step_ratio, 1.0, 0.05);
  EXPECT_NEAR(per_step(bordered.stats) / per_step(dense.stats), 1.0, 0.05);
}

}  // namespace
}  // namespace raceway::bearing
