#include "solver/bearing/housing.hpp"

#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "solver/bearing/marker.hpp"

namespace raceway::bearing {

Housing::Housing(double mass, double stiffness, double damping, int ring_body, int first_state, int sensor_samples)
    : mass_(mass), stiffness_(stiffness), damping_(damping), ring_body_(ring_body), first_state_(first_state),
      sensor_samples_(sensor_samples) {}

double Housing::natural_frequency() const { return std::sqrt(stiffness_ / mass_) / (2.0 * std::numbers::pi); }
double Housing::damping_ratio() const { return damping_ / (2.0 * std::sqrt(stiffness_ * mass_)); }

void Housing::rates(const Model&, double, const double* z, const double* forces, double* zdot) const {
  for (int i = 0; i < 2; ++i) {
    zdot[state(i)] = z[state(i + 2)];
    zdot[state(i + 2)] = (forces[i] - stiffness_ * z[state(i)] - damping_ * z[state(i + 2)]) / mass_;
  }
}

void Housing::add_own_jacobian(const Model&, double, numerics::BorderedMatrix& jac) const {
  for (int i = 0; i < 2; ++i) {
    jac.add(state(i), state(i + 2), 1.0);
    jac.add(state(i + 2), state(i), -stiffness_ / mass_);
    if (damping_ != 0.0) jac.add(state(i + 2), state(i + 2), -damping_ / mass_);
  }
}

void Housing::add_energy(const Model&, double, const double* z, double& e) const {
  for (int i = 0; i < 2; ++i) {
    const double u = z[state(i)], v = z[state(i + 2)];
    e += 0.5 * mass_ * v * v;
    e += 0.5 * stiffness_ * u * u;
  }
}

double Housing::power_loss(const Model&, double, const double* z) const {
  return damping_ * (z[state(2)] * z[state(2)] + z[state(3)] * z[state(3)]);
}

void Housing::initial_state(std::vector<double>& z) const {  // at rest, centred
  for (int i = 0; i < 4; ++i) z[static_cast<std::size_t>(state(i))] = 0.0;
}

std::string Housing::describe(const Model&) const {
  return fmt::format("  {:<12} mass {:.4g} kg (with the outer ring), 4 states [{}..{}): displacement and velocity in x "
                     "and y, border states; stiffness {:.4g} N/m, damping {:.4g} N s/m: {:.4g} Hz, damping ratio {:.3g}; "
                     "its sensor sampled {} times per output interval\n",
                     name(), mass_, first_state_, first_state_ + 4, stiffness_, damping_, natural_frequency(),
                     damping_ratio(), sensor_samples_);
}

namespace {

/// An element's attachment on the outer ring in its housing: the ring's kinematics moved by the
/// housing's displacement and velocity; the force on it drives the housing.
class HousingMarker final : public MarkerKind {
 public:
  HousingMarker(std::shared_ptr<const Housing> housing, int planning_id)
      : housing_(std::move(housing)), planning_id_(planning_id) {}
  int body() const override { return housing_->ring_body(); }
  int planning_id() const override { return planning_id_; }  // the housing node's: its states couple them

  contact::PlanarKinematics planar(const Model& m, double t, const double* z, const contact::PlanarKinematics&,
                                   const double*, MarkerPoint&) const override {
    contact::PlanarKinematics k = m.planar_kinematics(housing_->ring_body(), t, z);
    k.x += z[housing_->state(0)], k.y += z[housing_->state(1)];
    k.vx += z[housing_->state(2)], k.vy += z[housing_->state(3)];
    return k;
  }
  contact::SpatialKinematics spatial(const Model& m, double t, const double* z) const override {
    contact::SpatialKinematics k = m.kinematics(housing_->ring_body(), t, z);
    k.position.x() += z[housing_->state(0)], k.position.y() += z[housing_->state(1)];
    k.velocity.x() += z[housing_->state(2)], k.velocity.y() += z[housing_->state(3)];
    return k;
  }
  void columns(const Model&, bool on_a, std::vector<SegmentColumn>& out) const override {
    const Coordinate coordinates[4] = {sx, sy, svx, svy};
    for (int i = 0; i < 4; ++i) out.push_back({housing_->ring_body(), coordinates[i], housing_->state(i), on_a, -1});
  }
  void scatter(const Model&, const Segment&, bool, const double* w, double, const double*, Loads& loads) const override {
    Wrench& ring = loads.body[static_cast<std::size_t>(housing_->ring_body())];  // the ring's force diagnostics
    for (int i = 0; i < 3; ++i) ring.force[i] += w[i], ring.moment[i] += w[3 + i];
    loads.node[static_cast<std::size_t>(housing_->force_offset)] += w[0];
    loads.node[static_cast<std::size_t>(housing_->force_offset + 1)] += w[1];
  }
  void add_rate_derivative(const JacobianAssembly& a, int state, const Wrench& dw) const override {
    const double inv_mass = 1.0 / housing_->mass();
    if (dw.force.x() != 0.0) a.jac.add(housing_->state(2), state, dw.force.x() * inv_mass);
    if (dw.force.y() != 0.0) a.jac.add(housing_->state(3), state, dw.force.y() * inv_mass);
  }

 private:
  std::shared_ptr<const Housing> housing_;
  int planning_id_;
};

std::shared_ptr<const Housing> shared_housing(const Model& m, int* index = nullptr) {
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    if (auto h = std::dynamic_pointer_cast<const Housing>(m.nodes[i])) {
      if (index) *index = static_cast<int>(i);
      return h;
    }
  return nullptr;
}

}  // namespace

void add_housing(Model& m, const scene::Scene& scene) {
  if (!scene.housing.present) return;
  const Body& ring = m.bodies[static_cast<std::size_t>(m.outer_ring)];
  const int first = m.state_size;
  add_state(m, VariableClass::position, "housing.x");
  add_state(m, VariableClass::position, "housing.y");
  add_state(m, VariableClass::velocity, "housing.vx");
  add_state(m, VariableClass::velocity, "housing.vy");
  const scene::HousingSpec& h = scene.housing;
  const int per_output = static_cast<int>(std::lround(scene.scene.output_interval / h.sensor_interval));
  m.add_node(std::make_shared<Housing>(h.mass + ring.mass, h.stiffness, h.damping, m.outer_ring, first, per_output));
}

void attach_outer_ring_to_housing(Model& m) {
  int node = -1;
  auto housing = shared_housing(m, &node);
  if (!housing) return;
  const int marker = m.add_marker(
      std::shared_ptr<const MarkerKind>(std::make_shared<HousingMarker>(housing, m.node_planning_id(node))));
  for (Segment& seg : m.segments) {
    if (seg.body_a == m.outer_ring) seg.marker_a = marker;
    if (seg.body_b == m.outer_ring) seg.marker_b = marker;
  }
}

const Housing* housing_of(const Model& m) { return shared_housing(m).get(); }

}  // namespace raceway::bearing
