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
#include "solver/bearing/element_evaluation.hpp"
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
  explicit Seed002(double perturbation, scene::ElementVelocityFrame frame = scene::ElementVelocityFrame::bearing)
      : scene(with_perturbation(perturbation, frame)), model(build_model(scene)), eq(model, executor),
        start(initial_state(model, 0.0)) {}
  static scene::Scene with_perturbation(double p, scene::ElementVelocityFrame frame) {
    scene::Scene s = test::load_seed002_former_solver();
    s.solver.jacobian_perturbation = p;
    s.solver.element_velocity_frame = frame;
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
// errors at the start (Release): 9.0e-4 (default 1e-7), 7.8e-3 (1e-8), 7.6e-2 (1e-9), 1 (1e-10);
// when this comparison was set up (the dry traction of that time) 8.7e-5, 5.8e-5, 3.5e-4, 5.4e-3.
// The smallest approach is that of the outer contacts carrying the centrifugal force only,
// (F_c / K)^0.9 = 7.3 nm at 40 Hz; the default's position step 1e-10 * 22.9 mm = 2.3 pm gives a
// forward-difference error of K delta^(10/9) of h / (18 delta) = 1.7e-5, and from 1e-8 down
// round-off in the position columns dominates. (A position step relative to the state, 1e-7 *
// 22.9 mm = 2.3 nm, gave 1.8e-2 at the start.)
// So two checks at the start, both against 1e-3:
//  - Assembly*: the best over increments 1e-7 .. 1e-10 (robust to the step rule; a wrong row,
//    column, mass or sign fails at every increment);
//  - DefaultIncrement*: the scene's own setting, as CVODE uses it.
// A short run later the assembly is judged against forward differences (below).
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

TEST(Jacobian, DefaultIncrementMatchesCentralDifferencesAtConsistentStart) {
  Seed002 s(test::load_seed002_former_solver().solver.jacobian_perturbation);
  check_state(s.eq, s.model, 0.0, s.start.state, tolerance, "start, default increment");
}

// The spatial roller bearing (seed 002 in space: race slices, pocket bars, ribs, rollers with tilt
// and skew and their Euler equations):
//  - at the start, against central differences of the whole right-hand side, as above;
//  - 10 ms later against forward differences of the whole right-hand side with the model's own
//    steps (FiniteDifferenceSteps): the differences the model takes segment by segment, so that
//    what remains is the assembly (rows, columns, the wrench-to-rate maps of the rollers' Euler
//    equations and the cage's frame). Central differences are not the reference there: the
//    unloaded rollers' slices sit at their onset, some nm apart by the rollers' microradian tilts,
//    where Palmgren's second derivative (~ delta^(-8/9)) makes them inexact (up to 7 % in single
//    columns). Nor is the forward reference at the start: the loaded rollers' 40 slice forces,
//    summed in the right-hand side, leave round-off of 1e-13 of 300 N, which the 2 pm position step
//    magnifies to 1-2 % of a column (the model differences each slice alone).
// A column is measured against its own norm or a small fraction of its class's largest column,
// whichever is larger (an aligned bearing's axial columns are ~1e-6 of their class's largest).
// Measured: start 9.0e-4 (central), 10 ms 4.0e-7 (forward). (The rollers' tilting moments are small
// in an aligned bearing: their Euler equations are checked on their own, spatial_roller_dynamics_test.)
double spatial_roller_column_error(const Model& m, const Eigen::MatrixXd& model_jac, const Eigen::MatrixXd& ref,
                                   double floor_fraction, std::string& worst_column) {
  // In the integrator's units: entry (i, j) times atol_j / atol_i (the states' physical scales), so
  // that a column's rows of forces and of moments weigh as the error test weighs them (in SI units
  // a wrong moment of inertia hides under a column's force rows).
  const std::vector<double> atol = m.absolute_tolerance();
  Eigen::MatrixXd scaled_ref = ref, scaled_diff = model_jac - ref;
  for (int i = 0; i < m.state_size; ++i)
    for (int j = 0; j < m.state_size; ++j) {
      const double f = atol[static_cast<std::size_t>(j)] / atol[static_cast<std::size_t>(i)];
      scaled_ref(i, j) *= f, scaled_diff(i, j) *= f;
    }
  double largest = 0;
  for (int j = 0; j < m.state_size; ++j) largest = std::max(largest, scaled_ref.col(j).norm());
  double worst = 0;
  for (int j = 0; j < m.state_size; ++j) {
    const double err = scaled_diff.col(j).norm() / std::max(scaled_ref.col(j).norm(), floor_fraction * largest);
    if (err > worst) worst = err, worst_column = m.state_name[static_cast<std::size_t>(j)];
  }
  return worst;
}

/// The Jacobian of the whole right-hand side at (t, z) by forward differences with the model's own
/// steps (FiniteDifferenceSteps): the differences the model takes segment by segment, so that what
/// remains between the two is the assembly.
Eigen::MatrixXd forward_difference_jacobian(Equations& eq, const Model& m, double t, const std::vector<double>& z) {
  const FiniteDifferenceSteps step(m);
  std::vector<double> f(z.size()), fp(z.size()), zp = z;
  EXPECT_EQ(eq.rhs(t, z.data(), f.data()), 0);
  Eigen::MatrixXd forward(m.state_size, m.state_size);
  for (int j = 0; j < m.state_size; ++j) {
    const auto jj = static_cast<std::size_t>(j);
    const double h = step(j, z.data());
    zp[jj] = z[jj] + h;
    EXPECT_EQ(eq.rhs(t, zp.data(), fp.data()), 0);
    zp[jj] = z[jj];
    for (int i = 0; i < m.state_size; ++i)
      forward(i, j) = (fp[static_cast<std::size_t>(i)] - f[static_cast<std::size_t>(i)]) / h;
  }
  return forward;
}

// Seed 002 a short run later (roller-bar contacts closed). Where the rattling rollers are then
// follows the round-off of every step, and some roller sits where a law curves on the scale of the
// central step (the worst column is a roller's spin rate against its position: the traction near
// zero slip): the central differences' own error there moved from 8e-5 to 7e-4 and 1.1e-3 with
// last-bit changes of the block solves, so they cannot judge at 1e-3. The assembly is judged as for
// the spatial model below, against forward differences of the whole right-hand side with the
// model's own steps (a wrong row, column, mass or sign fails); the central differences are printed
// (and the sparsity checked) by check_state. The differences' accuracy is judged at the start.
// The assembled Jacobian's worst column against forward differences of the whole right-hand side
// with the model's own steps, at (t, z); `where` names it.
double forward_difference_error(Seed002& s, double t, const std::vector<double>& z, std::string& where) {
  std::vector<double> f(z.size());
  EXPECT_EQ(s.eq.rhs(t, z.data(), f.data()), 0);
  numerics::BorderedMatrix jac(s.model.border_size, s.model.element_count,
                               (s.model.state_size - s.model.border_size) / s.model.element_count);
  EXPECT_EQ(s.eq.jacobian(t, z.data(), jac), 0);
  return spatial_roller_column_error(s.model, jac.to_dense(), forward_difference_jacobian(s.eq, s.model, t, z), 1e-6,
                                     where);
}

TEST(Jacobian, AssemblyMatchesForwardDifferencesAfterShortRun) {
  Seed002 s(test::load_seed002_former_solver().solver.jacobian_perturbation);
  const auto z = state_after(s, short_run);
  check_state(s.eq, s.model, short_run, z, 0, "t = 20 ms, central differences (not judged)");
  std::string where;
  const double e = forward_difference_error(s, short_run, z, where);
  std::printf("[ jacobian ] t = 20 ms: worst column against forward differences %.3g (%s); closed %s\n", e,
              where.c_str(), closed_contacts(s.model, s.eq).c_str());
  EXPECT_LT(e, 1e-5) << where;
}

// A dry cage bar clear of its roller by more than its columns' steps can close writes zero columns
// without evaluating its law (bar_stays_clear, solver/bearing/element_evaluation.hpp). At the start
// and 20 ms later, every bar so judged has exactly zero differences in every column (the law evaluated
// at each column's step), and both kinds occur: bars judged clear, and bars in contact or within reach.
TEST(Jacobian, ClearCageBarsHaveExactlyZeroColumns) {
  Seed002 s(test::load_seed002_former_solver().solver.jacobian_perturbation);
  const FiniteDifferenceSteps step(s.model);
  int clear = 0, evaluated = 0;
  for (const std::vector<double>& z : {s.start.state, state_after(s, short_run)}) {
    for (const Segment& seg : s.model.segments) {
      if (seg.kind != SegmentKind::cage_bar_front && seg.kind != SegmentKind::cage_bar_rear) continue;
      const auto& law = s.model.law<contact::CageBarSegment>(seg);
      const ElementShape shape = element_shape(s.model, seg);
      const auto at = [&](const std::vector<double>& y) {
        const element_detail::PlanarPair p = element_detail::planar_pair(s.model, seg, short_run, y.data(), nullptr, nullptr);
        return contact::evaluate(law, p.a, p.b);
      };
      const contact::SegmentResult base = at(z);
      if (!element_detail::bar_stays_clear(s.model, step, law, shape, z.data(), base.diagnostics.approach)) {
        ++evaluated;
        continue;
      }
      ++clear;
      for (const SegmentColumn& c : shape.columns) {
        std::vector<double> y = z;
        y[static_cast<std::size_t>(c.state)] += step(c.state, z.data());
        const contact::SegmentResult r = at(y);
        EXPECT_EQ(r.on_a.fx, 0.0) << seg.name;
        EXPECT_EQ(r.on_a.fy, 0.0) << seg.name;
        EXPECT_EQ(r.on_a.mz, 0.0) << seg.name;
        EXPECT_EQ(r.on_b.fx, 0.0) << seg.name;
        EXPECT_EQ(r.on_b.fy, 0.0) << seg.name;
        EXPECT_EQ(r.on_b.mz, 0.0) << seg.name;
      }
    }
  }
  std::printf("[ jacobian ] cage bars judged clear %d, evaluated %d\n", clear, evaluated);
  EXPECT_GT(clear, 0);
  EXPECT_GT(evaluated, 0);
}

// The rollers' velocities in their orbital frame ([solver] element_velocity_frame = "orbital"): the
// rollers' own rows by differences of their rates (the frame's turning terms), the contact forces
// turned into e_r, e_theta. The assembly is judged against forward differences of the whole
// right-hand side with the model's own steps, at the start and 20 ms later (measured 5.6e-6 and
// 1.4e-8). Against central differences at the start the best increment gives 2.2e-3 (the bearing
// frame: 9.0e-4), in a roller's position column: a position step now turns the roller's velocity
// with its frame as well, and the 2.3 pm forward step's error in that column is 2.5 times the
// bearing frame's; so 3e-3 there (a wrong row, sign or mass is off by order 1).
TEST(Jacobian, OrbitalFrameMatchesFiniteDifferences) {
  double best = 1e300;
  for (double r : increments) {
    Seed002 at(r, scene::ElementVelocityFrame::orbital);
    best = std::min(best, check_state(at.eq, at.model, 0.0, at.start.state, 0, "orbital frame, start, increment " + increment_name(r)));
  }
  EXPECT_LT(best, 3e-3);
  Seed002 s(test::load_seed002_former_solver().solver.jacobian_perturbation, scene::ElementVelocityFrame::orbital);
  ASSERT_TRUE(s.model.orbital_velocities);
  const auto later = state_after(s, short_run);
  for (const double t : {0.0, short_run}) {
    const std::vector<double>& z = t == 0.0 ? s.start.state : later;
    std::string where;
    const double e = forward_difference_error(s, t, z, where);
    std::printf("[ jacobian ] orbital frame, t = %g ms: worst column against forward differences %.3g (%s)\n", 1e3 * t,
                e, where.c_str());
    EXPECT_LT(e, 1e-5) << where;
  }
}

TEST(Jacobian, SpatialRollerAssemblyMatchesFiniteDifferences) {
  scene::Scene scene = test::load_seed002_former_solver();
  std::string text = scene.text;
  const std::string planar = "model = \"planar\"";
  text.replace(text.find(planar), planar.size(), "model = \"spatial\"");
  const scene::Scene spatial = scene::parse_scene(text, "seed002 (spatial)");
  const Model m = build_model(spatial);
  scheduler::SerialExecutor executor;
  Equations eq(m, executor);
  const std::vector<double> start = initial_state(m, 0.0).state;
  numerics::Integrator integrator(eq, spatial.solver, 0.0, start);
  {
    const std::vector<double>& z = start;
    std::vector<double> f(static_cast<std::size_t>(m.state_size));
    ASSERT_EQ(eq.rhs(0.0, z.data(), f.data()), 0);
    numerics::BorderedMatrix jac(m.border_size, m.element_count, (m.state_size - m.border_size) / m.element_count);
    ASSERT_EQ(eq.jacobian(0.0, z.data(), jac), 0);
    std::string where;
    const double e = spatial_roller_column_error(m, jac.to_dense(), test::central_difference_jacobian(eq, m, 0.0, z), 1e-4,
                                                 where);
    std::printf("[ jacobian ] spatial roller, start: worst column against central differences %.3g (%s); closed %s\n",
                e, where.c_str(), closed_contacts(m, eq).c_str());
    EXPECT_LT(e, tolerance) << where;
  }
  {
    const double t = 0.01;
    std::vector<double> z, f(static_cast<std::size_t>(m.state_size));
    integrator.advance_to(t, z);
    ASSERT_EQ(eq.rhs(t, z.data(), f.data()), 0);
    const Eigen::MatrixXd forward = forward_difference_jacobian(eq, m, t, z);
    numerics::BorderedMatrix jac(m.border_size, m.element_count, (m.state_size - m.border_size) / m.element_count);
    ASSERT_EQ(eq.jacobian(t, z.data(), jac), 0);
    std::string where;
    const double e = spatial_roller_column_error(m, jac.to_dense(), forward, 1e-6, where);
    std::printf("[ jacobian ] spatial roller, t = 10 ms: worst column against forward differences %.3g (%s); closed "
                "%s\n",
                e, where.c_str(), closed_contacts(m, eq).c_str());
    EXPECT_LT(e, 1e-5) << where;
  }
}

}  // namespace
}  // namespace raceway::bearing
