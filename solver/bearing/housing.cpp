#include "solver/bearing/housing.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <memory>
#include <numbers>

#include "solver/bearing/marker.hpp"

namespace raceway::bearing {

Housing::Housing(std::vector<Mode> modes, double ring_mass, int ring_body, int first_state, int sensor_samples)
    : modes_(std::move(modes)), ring_mass_(ring_mass), ring_body_(ring_body), first_state_(first_state),
      sensor_samples_(sensor_samples) {
  if (modes_.size() == 1) {
    per_force_ = {1.0 / modes_[0].mass};
    return;
  }
  double compliance = 0;  // sum_j 1 / m_j
  for (const Mode& mode : modes_) compliance += 1.0 / mode.mass;
  coupling_ = 1.0 + ring_mass_ * compliance;
  for (const Mode& mode : modes_) per_force_.push_back(1.0 / (mode.mass * coupling_));
}

double Housing::natural_frequency() const { return std::sqrt(stiffness() / mass()) / (2.0 * std::numbers::pi); }
double Housing::damping_ratio() const { return damping() / (2.0 * std::sqrt(stiffness() * mass())); }

std::vector<double> Housing::frequencies() const {
  if (mode_count() == 1) return {natural_frequency()};
  // M q'' + K q = 0 with M = diag(m_j) + m_r 1 1^T (the ring rides on the seat, u = sum_j q_j), K = diag(k_j).
  const auto n = static_cast<Eigen::Index>(mode_count());
  Eigen::MatrixXd mass = Eigen::MatrixXd::Constant(n, n, ring_mass_), stiffness = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    mass(j, j) += modes_[static_cast<std::size_t>(j)].mass;
    stiffness(j, j) = modes_[static_cast<std::size_t>(j)].stiffness;
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(stiffness, mass, Eigen::EigenvaluesOnly);
  std::vector<double> hz;
  for (Eigen::Index j = 0; j < n; ++j) hz.push_back(std::sqrt(modes.eigenvalues()(j)) / (2.0 * std::numbers::pi));
  return hz;
}

double Housing::seat(const double* z, int i) const {
  double u = z[state(i)];  // from the first mode's, not from 0: one mode gives its state's very bits
  for (int j = 1; j < mode_count(); ++j) u += z[state(i, j)];
  return u;
}

double Housing::sensor(const double* z, int i) const {
  double u = modes_[0].sensor * z[state(i)];
  for (int j = 1; j < mode_count(); ++j) u += modes_[static_cast<std::size_t>(j)].sensor * z[state(i, j)];
  return u;
}

void Housing::rates(const Model&, double, const double* z, const double* forces, double* zdot) const {
  const int n = mode_count();
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < n; ++j) zdot[state(i, j)] = z[state(i + 2, j)];
    if (n == 1) {
      zdot[state(i + 2)] = (forces[i] - stiffness() * z[state(i)] - damping() * z[state(i + 2)]) / mass();
      continue;
    }
    // The seat's acceleration, then the force on the seat F_h = F - m_r u'' (header).
    double a = 0;
    for (int j = 0; j < n; ++j) {
      const Mode& mode = modes_[static_cast<std::size_t>(j)];
      a += (forces[i] - mode.stiffness * z[state(i, j)] - mode.damping * z[state(i + 2, j)]) / mode.mass;
    }
    const double seat_force = forces[i] - ring_mass_ * a / coupling_;
    for (int j = 0; j < n; ++j) {
      const Mode& mode = modes_[static_cast<std::size_t>(j)];
      zdot[state(i + 2, j)] = (seat_force - mode.stiffness * z[state(i, j)] - mode.damping * z[state(i + 2, j)]) / mode.mass;
    }
  }
}

void Housing::add_own_jacobian(const Model&, double, numerics::BorderedMatrix& jac) const {
  const int n = mode_count();
  if (n == 1) {  // the one-mode equation's terms as written
    for (int i = 0; i < 2; ++i) {
      jac.add(state(i), state(i + 2), 1.0);
      jac.add(state(i + 2), state(i), -stiffness() / mass());
      if (damping() != 0.0) jac.add(state(i + 2), state(i + 2), -damping() / mass());
    }
    return;
  }
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < n; ++j) {
      jac.add(state(i, j), state(i + 2, j), 1.0);
      // d(v_j') / d(r_k) = (m_r / (m_k coupling) - [j = k]) / m_j, r_k = k_k q_k + c_k v_k.
      for (int k = 0; k < n; ++k) {
        const Mode& mode_k = modes_[static_cast<std::size_t>(k)];
        const double shared = ring_mass_ / (mode_k.mass * coupling_);
        const double per_r = (shared - (j == k ? 1.0 : 0.0)) / modes_[static_cast<std::size_t>(j)].mass;
        jac.add(state(i + 2, j), state(i, k), per_r * mode_k.stiffness);
        if (mode_k.damping != 0.0) jac.add(state(i + 2, j), state(i + 2, k), per_r * mode_k.damping);
      }
    }
}

void Housing::add_energy(const Model&, double, const double* z, double& e) const {
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < mode_count(); ++j) {
      const Mode& mode = modes_[static_cast<std::size_t>(j)];
      const double u = z[state(i, j)], v = z[state(i + 2, j)];
      e += 0.5 * mode.mass * v * v;
      e += 0.5 * mode.stiffness * u * u;
    }
    if (mode_count() > 1) e += 0.5 * ring_mass_ * seat(z, i + 2) * seat(z, i + 2);  // the ring moves with the seat
  }
}

double Housing::power_loss(const Model&, double, const double* z) const {  // sum_j c_j |q_j'|^2
  double loss = 0;
  for (int j = 0; j < mode_count(); ++j) {
    const double vx = z[state(2, j)], vy = z[state(3, j)];
    loss += modes_[static_cast<std::size_t>(j)].damping * (vx * vx + vy * vy);
  }
  return loss;
}

void Housing::initial_state(std::vector<double>& z) const {  // at rest, centred
  for (int j = 0; j < mode_count(); ++j)
    for (int i = 0; i < 4; ++i) z[static_cast<std::size_t>(state(i, j))] = 0.0;
}

std::string Housing::describe(const Model&) const {
  std::string text = fmt::format(
      "  {:<12} mass {:.4g} kg{}, {} states [{}..{}): displacement and velocity in x and y per mode, border "
      "states; stiffness {:.4g} N/m, damping {:.4g} N s/m: {:.4g} Hz, damping ratio {:.3g}; its sensor sampled {} "
      "times per output interval\n",
      name(), mass(), mode_count() == 1 ? " (with the outer ring)" : "", 4 * mode_count(), first_state_,
      first_state_ + 4 * mode_count(), stiffness(), damping(), natural_frequency(), damping_ratio(), sensor_samples_);
  for (int j = 1; j < mode_count(); ++j) {
    const Mode& mode = modes_[static_cast<std::size_t>(j)];
    text += fmt::format("  {:<12} further mode {}: modal mass {:.4g} kg, stiffness {:.4g} N/m, damping {:.4g} N s/m "
                        "({:.4g} Hz alone); the outer ring's {:.4g} kg rides on the seat\n",
                        "", j + 1, mode.mass, mode.stiffness, mode.damping,
                        std::sqrt(mode.stiffness / mode.mass) / (2.0 * std::numbers::pi), ring_mass_);
  }
  if (mode_count() > 1) {
    std::string hz;
    for (const double f : frequencies()) hz += fmt::format("{}{:.4g}", hz.empty() ? "" : ", ", f);
    text += fmt::format("  {:<12} undamped frequencies with the ring on the seat: {} Hz\n", "", hz);
  }
  return text;
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
    k.x += housing_->seat(z, 0), k.y += housing_->seat(z, 1);
    k.vx += housing_->seat(z, 2), k.vy += housing_->seat(z, 3);
    return k;
  }
  contact::SpatialKinematics spatial(const Model& m, double t, const double* z) const override {
    contact::SpatialKinematics k = m.kinematics(housing_->ring_body(), t, z);
    k.position.x() += housing_->seat(z, 0), k.position.y() += housing_->seat(z, 1);
    k.velocity.x() += housing_->seat(z, 2), k.velocity.y() += housing_->seat(z, 3);
    return k;
  }
  void columns(const Model&, bool on_a, std::vector<SegmentColumn>& out) const override {
    const Coordinate coordinates[4] = {sx, sy, svx, svy};
    for (int j = 0; j < housing_->mode_count(); ++j)
      for (int i = 0; i < 4; ++i)
        out.push_back({housing_->ring_body(), coordinates[i], housing_->state(i, j), on_a, -1});
  }
  void scatter(const Model&, const Segment&, bool, const double* w, double, const double*, Loads& loads) const override {
    Wrench& ring = loads.body[static_cast<std::size_t>(housing_->ring_body())];  // the ring's force diagnostics
    for (int i = 0; i < 3; ++i) ring.force[i] += w[i], ring.moment[i] += w[3 + i];
    loads.node[static_cast<std::size_t>(housing_->force_offset)] += w[0];
    loads.node[static_cast<std::size_t>(housing_->force_offset + 1)] += w[1];
  }
  void add_rate_derivative(const JacobianAssembly& a, int state, const Wrench& dw) const override {
    for (int j = 0; j < housing_->mode_count(); ++j) {
      const double per_force = housing_->acceleration_per_force(j);
      if (dw.force.x() != 0.0) a.jac.add(housing_->state(2, j), state, dw.force.x() * per_force);
      if (dw.force.y() != 0.0) a.jac.add(housing_->state(3, j), state, dw.force.y() * per_force);
    }
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
  const scene::HousingSpec& h = scene.housing;
  const std::size_t further = h.mode_masses.size();
  const auto participation = [&](std::size_t j) { return h.sensor_participation.empty() ? 1.0 : h.sensor_participation[j]; };
  std::vector<Housing::Mode> modes;
  // One mode: the ring's mass in it (the housing's equation). More: the ring rides on the seat.
  modes.push_back({further == 0 ? h.mass + ring.mass : h.mass, h.stiffness, h.damping, participation(0)});
  for (std::size_t j = 0; j < further; ++j)
    modes.push_back({h.mode_masses[j], h.mode_stiffnesses[j], h.mode_dampings[j], participation(j + 1)});
  const int first = m.state_size;
  for (std::size_t j = 0; j < modes.size(); ++j) {
    const std::string prefix = j == 0 ? "housing." : fmt::format("housing.mode{}.", j + 1);
    add_state(m, VariableClass::position, prefix + "x");
    add_state(m, VariableClass::position, prefix + "y");
    add_state(m, VariableClass::velocity, prefix + "vx");
    add_state(m, VariableClass::velocity, prefix + "vy");
  }
  const int per_output = static_cast<int>(std::lround(scene.scene.output_interval / h.sensor_interval));
  m.add_node(std::make_shared<Housing>(std::move(modes), ring.mass, m.outer_ring, first, per_output));
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
