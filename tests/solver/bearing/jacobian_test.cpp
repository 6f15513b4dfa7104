// Equations::jacobian (forward differences of one segment at a time, assembled into the bordered
// matrix) against an independent central-difference Jacobian of Equations::rhs over ALL states, at
// the consistent start state of seed 002 (40 Hz) and at a state a short run later; and the sparsity
// of the true Jacobian: no coupling between different rollers.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "contact/segments/roller_segments.hpp"
#include "scheduler/executor.hpp"
#include "solver/numerics/bordered_matrix.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/numerics/integrator.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/startup.hpp"
#include "tests/support/solver_test_support.hpp"

namespace raceway::bearing {
namespace {

const char* class_name(VariableClass c) {
  switch (c) {
    case VariableClass::position: return "position";
    case VariableClass::angle: return "angle";
    case VariableClass::velocity: return "velocity";
    case VariableClass::angular_velocity: return "angular_velocity";
  }
  return "?";
}

int roller_of(const Model& m, int state) {
  return state < m.border_size ? -1 : (state - m.border_size) / ((m.state_size - m.border_size) / m.element_count);
}

struct ColumnErrors {
  double worst = 0;
  int worst_column = -1;
  double worst_by_class[4] = {0, 0, 0, 0};
};

/// Column-wise relative error ||J_j - D_j|| / ||D_j|| of the model Jacobian against the central
/// differences D. A column that is zero in D (a coordinate no closed contact depends on) is measured
/// against the largest column of its class instead.
ColumnErrors compare(const Model& m, const Eigen::MatrixXd& model_jac, const Eigen::MatrixXd& fd,
                     const std::string& where) {
  ColumnErrors out;
  double class_norm[4] = {0, 0, 0, 0};
  for (int j = 0; j < m.state_size; ++j)
    class_norm[static_cast<int>(m.state_class[j])] =
        std::max(class_norm[static_cast<int>(m.state_class[j])], fd.col(j).norm());
  for (int j = 0; j < m.state_size; ++j) {
    const int c = static_cast<int>(m.state_class[j]);
    const double diff = (model_jac.col(j) - fd.col(j)).norm();
    const double ref = fd.col(j).norm();
    double err;
    if (ref > 1e-9 * class_norm[c]) {
      err = diff / ref;
    } else {
      err = diff / class_norm[c];  // relative to the largest column of the class
      if (diff > 1e-9 * class_norm[c])
        std::printf("[ jacobian ] %s: column %s is zero in the central differences, %.3g in the Jacobian\n",
                    where.c_str(), m.state_name[j].c_str(), diff);
    }
    if (err > out.worst) out.worst = err, out.worst_column = j;
    out.worst_by_class[c] = std::max(out.worst_by_class[c], err);
  }
  std::printf("[ jacobian ] %s: worst column error %.3g (%s); by class: position %.3g, angle %.3g, velocity "
              "%.3g, angular velocity %.3g\n",
              where.c_str(), out.worst, out.worst_column >= 0 ? m.state_name[out.worst_column].c_str() : "-",
              out.worst_by_class[0], out.worst_by_class[1], out.worst_by_class[2], out.worst_by_class[3]);
  return out;
}

/// Which contacts are closed (so that the comparison covers them): counts per segment kind.
std::string closed_contacts(const Model& m, const Equations& eq) {
  int closed[segment_kind_count] = {};
  const auto& rec = eq.segment_records();
  for (std::size_t s = 0; s < m.segments.size(); ++s)
    if (rec[s * SegmentRecord::size + SegmentRecord::diagnostics + 1] > 0) ++closed[static_cast<int>(m.segments[s].kind)];
  std::string out;
  for (int k = 0; k < segment_kind_count; ++k)
    out += std::string(k ? ", " : "") + segment_kind_name(static_cast<SegmentKind>(k)) + " " + std::to_string(closed[k]);
  return out;
}

/// Compares the model Jacobian with central differences at (t, z); checks the sparsity; returns the
/// worst column error (and expects it below `tolerance` unless tolerance <= 0).
double check_state(Equations& eq, const Model& m, double t, const std::vector<double>& z, double tolerance,
                   const std::string& where) {
  std::vector<double> f(z.size());
  EXPECT_EQ(eq.rhs(t, z.data(), f.data()), 0);
  std::printf("[ jacobian ] %s: closed contacts: %s\n", where.c_str(), closed_contacts(m, eq).c_str());
  std::vector<int> carrying;  // rollers in contact with the (free) inner ring
  for (std::size_t s = 0; s < m.segments.size(); ++s)
    if (m.segments[s].kind == SegmentKind::roller_inner_race &&
        eq.segment_records()[s * SegmentRecord::size + SegmentRecord::diagnostics + 1] > 0)
      carrying.push_back(m.segments[s].element);
  EXPECT_FALSE(carrying.empty());
  const Eigen::MatrixXd fd = test::central_difference_jacobian(eq, m, t, z);

  // Sparsity of the true Jacobian: no entry couples two different rollers, exactly.
  for (int i = m.border_size; i < m.state_size; ++i)
    for (int j = m.border_size; j < m.state_size; ++j)
      if (roller_of(m, i) != roller_of(m, j) && fd(i, j) != 0.0) {
        ADD_FAILURE() << where << ": " << m.state_name[i] << " depends on " << m.state_name[j];
        return 1e300;
      }
  // ... while each roller is coupled to the border (the rings carry it): the structure is not empty.
  for (int k : carrying) {
    const int first = m.border_size + k * ((m.state_size - m.border_size) / m.element_count);
    EXPECT_GT(fd.block(first, 0, 5, m.border_size).cwiseAbs().maxCoeff(), 0.0) << "roller " << k;
  }

  const int nb = m.border_size;
  numerics::BorderedMatrix jac(nb, m.element_count, (m.state_size - nb) / m.element_count);
  EXPECT_EQ(eq.jacobian(t, z.data(), jac), 0);
  const Eigen::MatrixXd dense = jac.to_dense();
  const ColumnErrors e = compare(m, dense, fd, where);
  if (tolerance > 0) {
    EXPECT_LT(e.worst, tolerance) << where << ": worst column " << m.state_name[e.worst_column] << " ("
                                  << class_name(m.state_class[e.worst_column]) << ")";
  }
  return e.worst;
}

struct Seed002 {
  scene::Scene scene;
  Model model;
  scheduler::SerialExecutor executor;
  Equations eq;
  StartupReport start;
  explicit Seed002(double perturbation)
      : scene(with_perturbation(perturbation)), model(build_model(scene)), eq(model, executor),
        start(initial_state(model, 0.0)) {}
  static scene::Scene with_perturbation(double p) {
    scene::Scene s = test::load_job_scene("seed002_40hz.toml");
    s.solver.jacobian_perturbation = p;
    return s;
  }
};

std::vector<double> state_after(Seed002& s, double t) {
  numerics::Integrator integrator(s.eq, s.scene.solver, 0.0, s.start.state);
  std::vector<double> z;
  integrator.advance_to(t, z);
  return z;
}

// Tolerance 1e-3 of the column norm. The model Jacobian is a FORWARD difference (contact/segments/
// segment_jacobian.hpp) with the steps of FiniteDifferenceSteps (solver/bearing/equations.cpp):
// positions and angles 1e-3 jacobian_perturbation scale_j, rates jacobian_perturbation
// max(|z_j|, scale_j), scale = atol/rtol (pitch radius for positions, surface speed for velocities);
// its truncation and round-off errors are the floor of this comparison. Measured worst column
// errors (Release; the t = 20 ms states differ a little with the increment, since the Jacobian
// steers CVODE's Newton iterations):
//   jacobian_perturbation  1e-7 (default)  1e-8     1e-9     1e-10
//   start                  8.7e-5          5.8e-5   3.5e-4   5.4e-3
//   t = 20 ms              8.4e-5          2.4e-5   4.3e-4   3.7e-3
// The smallest approach is that of the outer contacts carrying the centrifugal force only,
// (F_c / K)^0.9 = 7.3 nm at 40 Hz; the default's position step 1e-10 * 22.9 mm = 2.3 pm gives a
// forward-difference error of K delta^(10/9) of h / (18 delta) = 1.7e-5, and from 1e-9 down
// round-off in the position columns dominates. (A position step relative to the state, 1e-7 *
// 22.9 mm = 2.3 nm, gave 1.8e-2 at the start and 0.48 at 20 ms.)
// So two checks, both against 1e-3 (17 to 42 times the best the forward differences give):
//  - Assembly*: the best over increments 1e-7 .. 1e-10 (robust to the step rule; a wrong row,
//    column, mass or sign fails at every increment);
//  - DefaultIncrement*: the scene's own setting, as CVODE uses it.
constexpr double tolerance = 1e-3;
constexpr double short_run = 0.02;  // s: 0.8 shaft revolutions, roller-bar contacts closed
const double increments[] = {1e-7, 1e-8, 1e-9, 1e-10};

std::string increment_name(double rel) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", rel);
  return buf;
}

TEST(Jacobian, AssemblyMatchesCentralDifferencesAtConsistentStart) {
  double best = 1e300;
  for (double rel : increments) {
    Seed002 s(rel);
    best = std::min(best, check_state(s.eq, s.model, 0.0, s.start.state, 0, "start, increment " + increment_name(rel)));
  }
  EXPECT_LT(best, tolerance);
}

TEST(Jacobian, AssemblyMatchesCentralDifferencesAfterShortRun) {
  double best = 1e300;
  for (double rel : increments) {
    Seed002 s(rel);
    const auto z = state_after(s, short_run);
    best = std::min(best, check_state(s.eq, s.model, short_run, z, 0, "t = 20 ms, increment " + increment_name(rel)));
  }
  EXPECT_LT(best, tolerance);
}

TEST(Jacobian, DefaultIncrementMatchesCentralDifferencesAtConsistentStart) {
  Seed002 s(test::load_job_scene("seed002_40hz.toml").solver.jacobian_perturbation);
  check_state(s.eq, s.model, 0.0, s.start.state, tolerance, "start, default increment");
}

TEST(Jacobian, DefaultIncrementMatchesCentralDifferencesAfterShortRun) {
  Seed002 s(test::load_job_scene("seed002_40hz.toml").solver.jacobian_perturbation);
  const auto z = state_after(s, short_run);
  check_state(s.eq, s.model, short_run, z, tolerance, "t = 20 ms, default increment");
}

}  // namespace
}  // namespace raceway::bearing
