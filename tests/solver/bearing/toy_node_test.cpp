// A node and a marker that exist only in this test: the kernel's extension points carry a new
// flexible part without an edit to the equations, the model, the dynamics or the output writer.
//
// The toy: the inner raceway is a sleeve on the inner ring's hub, held by an elastic layer. The
// sleeve's offset from the hub's centre and its rate are a node (four border states); the
// inner-race contacts attach to the sleeve (a marker: the hub's kinematics moved by the offset,
// the contact force the sleeve's generalized force, the moment passed to the hub about its
// centre); the layer is a spring element (the ring-mode spring law, force on the sleeve only)
// between the hub's centre and the sleeve's offset. The hub is driven with its centre held.
//  - With the sleeve at rest and centred, every rolling element's and the cage's rates are those
//    of the model without it, bit for bit.
//  - The sleeve's generalized force is the sum of the inner-race contact forces on it.
//  - The Jacobian through the new marker and node against central differences.
//  - A free vibration of the sleeve against the rollers, undamped and frictionless, conserves the
//    total energy (the equations' energy sums the node's kinetic energy and the spring's).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "scheduler/executor.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/startup.hpp"
#include "solver/numerics/bordered_matrix.hpp"
#include "tests/support/solver_test_support.hpp"

namespace raceway::bearing {
namespace {

constexpr double sleeve_mass = 0.05;      // kg
constexpr double layer_stiffness = 2e8;   // N/m

/// The sleeve's offset (x, y) and its rate: four states, two generalized forces.
class ToySleeve final : public Node {
 public:
  explicit ToySleeve(int first) : first_(first) {}
  int state(int i) const { return first_ + i; }
  std::string name() const override { return "toy_sleeve"; }
  int force_count() const override { return 2; }
  void rates(const Model&, double, const double* z, const double* f, double* zdot) const override {
    zdot[state(0)] = z[state(2)];
    zdot[state(1)] = z[state(3)];
    zdot[state(2)] = f[0] / sleeve_mass;
    zdot[state(3)] = f[1] / sleeve_mass;
  }
  void add_own_jacobian(const Model&, double, numerics::BorderedMatrix& jac) const override {
    jac.add(state(0), state(2), 1.0);
    jac.add(state(1), state(3), 1.0);
  }
  void add_energy(const Model&, double, const double* z, double& e) const override {
    e += 0.5 * sleeve_mass * (z[state(2)] * z[state(2)] + z[state(3)] * z[state(3)]);
  }
  void initial_state(std::vector<double>& z) const override {
    for (int i = 0; i < 4; ++i) z[static_cast<std::size_t>(state(i))] = 0.0;
  }
  std::string describe(const Model&) const override { return "  toy_sleeve: the inner raceway on an elastic layer\n"; }
  void add_force_derivative(int col, double dfx, double dfy, numerics::BorderedMatrix& jac) const {
    jac.add(state(2), col, dfx / sleeve_mass);
    jac.add(state(3), col, dfy / sleeve_mass);
  }

 private:
  int first_;
};

/// The inner-race contacts' point on the sleeve.
class SleeveRace final : public MarkerKind {
 public:
  SleeveRace(std::shared_ptr<const ToySleeve> sleeve, int hub) : sleeve_(std::move(sleeve)), hub_(hub) {}
  int body() const override { return hub_; }
  int planning_id() const override { return hub_; }
  contact::PlanarKinematics planar(const Model& m, double t, const double* z, const contact::PlanarKinematics&,
                                   const double*, MarkerPoint& point) const override {
    contact::PlanarKinematics k = m.planar_kinematics(hub_, t, z);
    k.x += z[sleeve_->state(0)], k.y += z[sleeve_->state(1)];
    k.vx += z[sleeve_->state(2)], k.vy += z[sleeve_->state(3)];
    point.offset = {z[sleeve_->state(0)], z[sleeve_->state(1)], 0.0, 0.0};
    return k;
  }
  void to_reference(const MarkerPoint& p, contact::PlanarWrench& w) const override {
    w.mz += p.offset[0] * w.fy - p.offset[1] * w.fx;  // about the hub's centre
  }
  void columns(const Model& m, bool on_a, std::vector<SegmentColumn>& out) const override {
    add_body_columns(m, hub_, on_a, out);
    const Coordinate c[4] = {sx, sy, svx, svy};
    for (int i = 0; i < 4; ++i) out.push_back({-1, c[i], sleeve_->state(i), on_a});
  }
  void scatter(const Model&, const Segment&, bool, const double* w, double, const double*, Loads& loads) const override {
    loads.node[static_cast<std::size_t>(sleeve_->force_offset)] += w[0];
    loads.node[static_cast<std::size_t>(sleeve_->force_offset) + 1] += w[1];
    loads.body[static_cast<std::size_t>(hub_)].moment.z() += w[5];
  }
  void add_rate_derivative(const JacobianAssembly& a, int state, const Wrench& dw) const override {
    sleeve_->add_force_derivative(state, dw.force.x(), dw.force.y(), a.jac);
    Wrench moment;
    moment.moment.z() = dw.moment.z();
    if (a.model.bodies[static_cast<std::size_t>(hub_)].has_states()) a.add_body_rate_derivative(hub_, state, moment);
  }

 private:
  std::shared_ptr<const ToySleeve> sleeve_;
  int hub_;
};

/// The sleeve's offset as a marker (the layer spring's B).
class SleeveOffset final : public MarkerKind {
 public:
  explicit SleeveOffset(std::shared_ptr<const ToySleeve> sleeve) : sleeve_(std::move(sleeve)) {}
  int body() const override { return -1; }
  int planning_id() const override { return -1; }
  contact::PlanarKinematics planar(const Model&, double, const double* z, const contact::PlanarKinematics&,
                                   const double*, MarkerPoint&) const override {
    return {z[sleeve_->state(0)], z[sleeve_->state(1)], 0.0, z[sleeve_->state(2)], z[sleeve_->state(3)], 0.0};
  }
  void columns(const Model&, bool on_a, std::vector<SegmentColumn>& out) const override {
    const Coordinate c[4] = {sx, sy, svx, svy};
    for (int i = 0; i < 4; ++i) out.push_back({-1, c[i], sleeve_->state(i), on_a});
  }
  void scatter(const Model&, const Segment&, bool, const double* w, double, const double*, Loads& loads) const override {
    loads.node[static_cast<std::size_t>(sleeve_->force_offset)] += w[0];
    loads.node[static_cast<std::size_t>(sleeve_->force_offset) + 1] += w[1];
  }
  void add_rate_derivative(const JacobianAssembly& a, int state, const Wrench& dw) const override {
    sleeve_->add_force_derivative(state, dw.force.x(), dw.force.y(), a.jac);
  }

 private:
  std::shared_ptr<const ToySleeve> sleeve_;
};

std::shared_ptr<const ToySleeve> sleeve_of(const Model& m) {
  for (const auto& n : m.nodes)
    if (auto s = std::dynamic_pointer_cast<const ToySleeve>(n)) return s;
  return nullptr;
}

// The toy bearing type: the roller builder's steps, the sleeve added with the rings' states and
// its elements after the roller builder's.
void toy_rings(Model& m, const scene::Scene& scene) {
  roller_model_builder().rings(m, scene);
  const int first = add_state(m, VariableClass::position, "toy_sleeve.x");
  add_state(m, VariableClass::position, "toy_sleeve.y");
  add_state(m, VariableClass::velocity, "toy_sleeve.vx");
  add_state(m, VariableClass::velocity, "toy_sleeve.vy");
  m.add_node(std::make_shared<ToySleeve>(first));
}

void toy_segments(Model& m, const scene::Scene& scene) {
  roller_model_builder().segments(m, scene);
  const auto sleeve = sleeve_of(m);
  const int race = m.add_marker(std::shared_ptr<const MarkerKind>(std::make_shared<SleeveRace>(sleeve, m.inner_ring)));
  for (Segment& seg : m.segments)
    if (seg.kind == SegmentKind::roller_inner_race) seg.marker_a = race;
  m.laws.push_back(RingModeSpring{layer_stiffness, 0.0});
  Segment layer{SegmentKind::outer_ring_mode, m.inner_ring, m.inner_ring, static_cast<int>(m.laws.size()) - 1, -1,
                "toy_sleeve/layer"};
  layer.marker_b = m.add_marker(std::shared_ptr<const MarkerKind>(std::make_shared<SleeveOffset>(sleeve)));
  m.segments.push_back(layer);
}

const ModelBuilder& toy_builder() {
  const ModelBuilder& roller = roller_model_builder();
  static const ModelBuilder builder{roller.check, roller.geometry, toy_rings, roller.cage, roller.rolling_elements,
                                    toy_segments, roller.describe};
  return builder;
}

/// Seed 002's bearing with its inner ring's centre held (the sleeve carries the contacts), dry,
/// undamped and frictionless where `conservative`.
scene::Scene toy_scene(bool conservative) {
  scene::Scene s = test::load_seed002_former_solver();
  s.inner_ring.translation_free = false;
  s.inner_ring.load.fy = scene::TimeFunction::constant(0.0);
  s.gravity = false;
  s.roller_race.traction.slip_velocity_scale = 0.5;  // smooth at the test's slips (a difference straddles no kink)
  if (conservative)
    for (scene::ContactSpec* c : {&s.roller_race, &s.roller_cage, &s.cage_land}) {
      c->damping.id = contact::LawId::no_damping, c->damping.factor = 0;
      c->traction.id = contact::LawId::no_traction, c->traction.friction_coefficient = 0;
    }
  return s;
}

TEST(ToyNode, AtRestTheRigidModelsRatesBitForBit) {
  const scene::Scene scene = toy_scene(false);
  const Model rigid = build_model(scene);
  const Model toy = build_model(scene, toy_builder());
  ASSERT_EQ(toy.state_size, rigid.state_size + 4);
  ASSERT_EQ(toy.nodes.size(), 1u);
  scheduler::SerialExecutor ex_rigid, ex_toy;
  Equations eq_rigid(rigid, ex_rigid), eq_toy(toy, ex_toy);
  const std::vector<double> z_rigid = initial_state(rigid, 0.0).state;
  const std::vector<double> z_toy = initial_state(toy, 0.0).state;
  std::vector<double> f_rigid(z_rigid.size()), f_toy(z_toy.size());
  ASSERT_EQ(eq_rigid.rhs(0.0, z_rigid.data(), f_rigid.data()), 0);
  ASSERT_EQ(eq_toy.rhs(0.0, z_toy.data(), f_toy.data()), 0);
  // The sleeve's four states sit in the border after the rings': everything after them is shifted.
  const int shift = 4, first_toy = sleeve_of(toy)->state(0);
  for (int i = 0; i < rigid.state_size; ++i) {
    const int j = i < first_toy ? i : i + shift;
    ASSERT_EQ(rigid.state_name[static_cast<std::size_t>(i)], toy.state_name[static_cast<std::size_t>(j)]);
    EXPECT_EQ(f_rigid[static_cast<std::size_t>(i)], f_toy[static_cast<std::size_t>(j)]) << rigid.state_name[static_cast<std::size_t>(i)];
  }
  EXPECT_NE(toy.describe().find("toy_sleeve"), std::string::npos);
}

/// The sleeve pushed towards roller 0 (it presses the rollers there).
std::vector<double> pushed_state(const Model& m, double push) {
  std::vector<double> z = initial_state(m, 0.0).state;
  const Body& roller = m.bodies[static_cast<std::size_t>(m.first_element)];
  const double theta = std::atan2(z[static_cast<std::size_t>(roller.slot[sy])], z[static_cast<std::size_t>(roller.slot[sx])]);
  const auto sleeve = sleeve_of(m);
  z[static_cast<std::size_t>(sleeve->state(0))] = push * std::cos(theta);
  z[static_cast<std::size_t>(sleeve->state(1))] = push * std::sin(theta);
  return z;
}

TEST(ToyNode, GeneralizedForceIsTheSumOfTheContactForces) {
  const scene::Scene scene = toy_scene(false);
  const Model m = build_model(scene, toy_builder());
  scheduler::SerialExecutor ex;
  Equations eq(m, ex);
  std::vector<double> z = pushed_state(m, 10e-6), zdot(z.size());
  ASSERT_EQ(eq.rhs(0.0, z.data(), zdot.data()), 0);
  double fx = 0, fy = 0, contact_fx = 0, contact_fy = 0;  // on the sleeve: all, and the contacts' alone
  for (std::size_t s = 0; s < m.segments.size(); ++s) {
    const double* rec = eq.segment_records().data() + s * SegmentRecord::size;
    if (m.segments[s].kind == SegmentKind::roller_inner_race) {
      contact_fx += rec[SegmentRecord::on_a], contact_fy += rec[SegmentRecord::on_a + 1];
      fx += rec[SegmentRecord::on_a], fy += rec[SegmentRecord::on_a + 1];
    } else if (m.segments[s].name == "toy_sleeve/layer") {
      fx += rec[SegmentRecord::on_b], fy += rec[SegmentRecord::on_b + 1];
    }
  }
  const auto sleeve = sleeve_of(m);
  const double ax = zdot[static_cast<std::size_t>(sleeve->state(2))], ay = zdot[static_cast<std::size_t>(sleeve->state(3))];
  std::printf("[ toy ] sleeve: generalized force (%.6g, %.6g) N; contacts (%.6g, %.6g) N and the layer\n",
              sleeve_mass * ax, sleeve_mass * ay, contact_fx, contact_fy);
  ASSERT_GT(std::hypot(contact_fx, contact_fy), 100.0);  // the rollers push back
  EXPECT_NEAR(sleeve_mass * ax, fx, 1e-9 * std::hypot(fx, fy));
  EXPECT_NEAR(sleeve_mass * ay, fy, 1e-9 * std::hypot(fx, fy));
}

TEST(ToyNode, JacobianMatchesCentralDifferences) {
  const scene::Scene scene = toy_scene(false);
  const Model m = build_model(scene, toy_builder());
  scheduler::SerialExecutor ex;
  Equations eq(m, ex);
  std::vector<double> z = pushed_state(m, 8e-6);
  const auto sleeve = sleeve_of(m);
  z[static_cast<std::size_t>(sleeve->state(2))] = 0.01, z[static_cast<std::size_t>(sleeve->state(3))] = -0.02;
  numerics::BorderedMatrix jac(m.border_size, m.element_count, m.block_size);
  ASSERT_EQ(eq.jacobian(0.0, z.data(), jac), 0);
  const Eigen::MatrixXd model = jac.to_dense();
  const Eigen::MatrixXd fd = test::central_difference_jacobian(eq, m, 0.0, z);
  const int sleeve_begin = sleeve->state(0);
  const Body& roller = m.bodies[static_cast<std::size_t>(m.first_element)];
  struct Block {
    const char* name;
    int row, rows, col, cols;
  };
  for (const Block& b : {Block{"sleeve / roller 0", sleeve_begin, 4, roller.offset, roller.size},
                         Block{"roller 0 / sleeve", roller.offset, roller.size, sleeve_begin, 4},
                         Block{"sleeve / sleeve", sleeve_begin, 4, sleeve_begin, 4}}) {
    const Eigen::MatrixXd f = fd.block(b.row, b.col, b.rows, b.cols);
    const Eigen::MatrixXd d = model.block(b.row, b.col, b.rows, b.cols) - f;
    const double scale = f.cwiseAbs().maxCoeff(), error = d.cwiseAbs().maxCoeff();
    std::printf("[ toy ] %s: largest entry %.4g, largest error %.3g\n", b.name, scale, error);
    // The model's columns are forward differences with the scene's steps: on seed 002's small
    // approaches their truncation error is up to about 1e-4 (jacobian_test.cpp measures it); a
    // wrong row, column, mass or sign is an error of order one.
    EXPECT_GT(scale, 1.0) << b.name;
    EXPECT_LT(error, 1e-3 * scale) << b.name;
  }
}

TEST(ToyNode, FreeVibrationConservesEnergy) {
  const scene::Scene scene = toy_scene(true);
  const Model m = build_model(scene, toy_builder());
  scheduler::SerialExecutor ex;
  Equations eq(m, ex);
  std::vector<double> z = pushed_state(m, 15e-6);
  for (std::size_t i = 0; i < z.size(); ++i)  // at rest: the rollers and the cage still, the sleeve released
    if (m.state_class[i] == VariableClass::velocity || m.state_class[i] == VariableClass::angular_velocity) z[i] = 0;
  const std::size_t n = z.size();
  std::vector<double> k1(n);
  auto f = [&](double t, const std::vector<double>& y, std::vector<double>& out) {
    ASSERT_EQ(eq.rhs(t, y.data(), out.data()), 0);
  };
  const auto sleeve = sleeve_of(m);
  auto sleeve_energy = [&](const std::vector<double>& y) {
    const double x = y[static_cast<std::size_t>(sleeve->state(0))], yy = y[static_cast<std::size_t>(sleeve->state(1))];
    const double vx = y[static_cast<std::size_t>(sleeve->state(2))], vy = y[static_cast<std::size_t>(sleeve->state(3))];
    return 0.5 * layer_stiffness * (x * x + yy * yy) + 0.5 * sleeve_mass * (vx * vx + vy * vy);
  };
  f(0.0, z, k1);
  const double e0 = eq.energy(0.0, z.data()), sleeve0 = sleeve_energy(z);
  double drift = 0, exchanged = 0, t = 0;
  const double dt = 2e-8;
  for (int step = 0; step < 5000; ++step) {  // 0.1 ms: several periods of the sleeve (about 10 kHz)
    test::runge_kutta_step(f, t, dt, z);
    t += dt;
    if (step % 50 == 49) {
      f(t, z, k1);
      drift = std::max(drift, std::abs(eq.energy(t, z.data()) - e0));
      exchanged = std::max(exchanged, std::abs(sleeve_energy(z) - sleeve0));
    }
  }
  std::printf("[ toy ] free vibration over %.3f ms: energy %.6g J, largest drift %.3g J, sleeve's energy %.4g J "
              "exchanged up to %.4g J\n",
              1e3 * t, e0, drift, sleeve0, exchanged);
  ASSERT_GT(exchanged, 1e-2 * sleeve0);
  EXPECT_LT(drift, 1e-3 * exchanged);
}

}  // namespace
}  // namespace raceway::bearing
