#include "solver/bearing/cage_bridges.hpp"

#include "solver/bearing/carrier_frame.hpp"
#include "solver/bearing/equations.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace raceway::bearing {

namespace {

/// A Timoshenko bar's stiffness for its mean deflection and its modal mass over the bar's mass.
struct TimoshenkoBar {
  double stiffness = 0, mass_ratio = 0;
};

// The static shape per unit pocket force, w = B xi^2 (1 - xi)^2 + S xi (1 - xi) (xi = x / L) with
// B = L^3 / (24 E I), S = L / (2 kappa G A): its mean u = B / 30 + S / 6, the mean of its square
// B^2 / 630 + B S / 70 + S^2 / 30 (Beta integrals), and the mean square of the sections' rotation
// L w_b' = 2 B xi (1 - xi) (1 - 2 xi), 4 B^2 / 210, weighted by the section's (t / L)^2 / 12.
TimoshenkoBar timoshenko_bar(const BridgeBeam& b) {
  const double length3 = b.span * b.span * b.span;
  const double bend = length3 / (24.0 * b.youngs_modulus * b.area_moment);
  const double shear = b.span / (2.0 * b.shear_coefficient * b.shear_modulus * b.thickness * b.height);
  const double mean = bend / 30.0 + shear / 6.0;
  const double slender = b.thickness * b.thickness / (12.0 * b.span * b.span);
  const double square = bend * bend / 630.0 + bend * shear / 70.0 + shear * shear / 30.0 +
                        slender * 4.0 * bend * bend / 210.0;
  return {1.0 / mean, square / (mean * mean)};
}

}  // namespace

BridgeBeam bridge_beam(const scene::Scene& scene, double cage_height) {
  const auto& g = scene.bearing;
  const auto& cs = scene.cage;
  const auto& material = scene.material(cs.material);
  BridgeBeam b;
  const double chord = g.pitch_diameter * std::sin(std::numbers::pi / g.rolling_elements);
  b.thickness = cs.bridge_thickness > 0 ? cs.bridge_thickness : chord - g.roller_diameter - cs.pocket_clearance;
  b.height = cs.bridge_height > 0 ? cs.bridge_height : cage_height;
  b.span = cs.bar_width > 0 ? cs.bar_width : g.roller_length;
  if (!(b.thickness > 0))
    throw std::runtime_error(fmt::format(
        "cage.bridge_thickness: the pockets leave no bridge (d_m sin(pi / Z) - D - pocket_clearance = {:.4g} mm); "
        "give bridge_thickness",
        1e3 * b.thickness));
  b.youngs_modulus = material.youngs_modulus;
  b.area_moment = b.height * b.thickness * b.thickness * b.thickness / 12.0;
  b.mass = material.density * b.thickness * b.height * b.span;
  if (cs.bridge_theory == scene::BeamTheory::euler_bernoulli) {
    b.stiffness = cs.bridge_stiffness > 0 ? cs.bridge_stiffness
                                          : 720.0 * b.youngs_modulus * b.area_moment / (b.span * b.span * b.span);
    b.modal_mass = 10.0 / 7.0 * b.mass;
  } else {
    const double nu = material.poisson_ratio;
    b.shear_modulus = b.youngs_modulus / (2.0 * (1.0 + nu));
    b.shear_coefficient = 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu);
    const TimoshenkoBar bar = timoshenko_bar(b);
    b.stiffness = cs.bridge_stiffness > 0 ? cs.bridge_stiffness : bar.stiffness;
    b.modal_mass = bar.mass_ratio * b.mass;
  }
  b.damping = 2.0 * cs.bridge_damping_ratio * std::sqrt(b.stiffness * b.modal_mass);
  return b;
}

namespace {
constexpr double pi = std::numbers::pi;
}

CageBridge::CageBridge(int index, int count, int cage, int angle_state, const BridgeBeam& beam, double pitch_radius,
                       double angle_tolerance)
    : index_(index),
      count_(count),
      cage_(cage),
      angle_(angle_state),
      rate_(angle_state + 1),
      mass_(beam.modal_mass),
      inertia_(beam.modal_mass * pitch_radius * pitch_radius),
      angle_tolerance_(angle_tolerance),
      rate_tolerance_(angle_tolerance * std::sqrt(beam.stiffness * pitch_radius * pitch_radius / inertia_)) {}

std::string CageBridge::name() const { return fmt::format("cage_bridge[{}]", index_); }

// The moment on it bends it; the force on it went to the cage, which carries it (its marker). Its
// states are its angle and rate relative to the cage, so its acceleration is its absolute one,
// I w' = M (+ the frame's Euler moment), less the cage's, which the cage's rates hold already
// (rigid bodies' rates come before the nodes').
void CageBridge::rates(const Model& m, double t, const double* z, const double* forces, double* zdot) const {
  double mz = forces[0];
  if (const auto frame = carrier_frame(m.params().carrier, t)) mz += frame->moment(inertia_);
  const int carrier_rate = m.bodies[static_cast<std::size_t>(cage_)].slot[swz];
  zdot[angle_] = z[rate_];
  zdot[rate_] = mz / inertia_ - zdot[carrier_rate];
}

void CageBridge::add_moment_derivative(int state, double dm, numerics::BorderedMatrix& jac) const {
  const double rate = dm * (1.0 / inertia_);
  if (rate != 0.0) jac.add(rate_, state, rate);
}

void CageBridge::add_own_jacobian(const Model&, double, numerics::BorderedMatrix& jac) const { jac.add(angle_, rate_, 1.0); }

void CageBridge::add_energy(const Model& m, double, const double* z, double& e) const {
  const double w = z[rate_] + z[m.bodies[static_cast<std::size_t>(cage_)].slot[swz]];
  e += 0.5 * inertia_ * w * w;
}

void CageBridge::set_tolerances(std::vector<double>& atol) const {
  atol[static_cast<std::size_t>(angle_)] = angle_tolerance_;
  atol[static_cast<std::size_t>(rate_)] = rate_tolerance_;
}

void CageBridge::initial_state(std::vector<double>& z) const {  // undeflected
  z[static_cast<std::size_t>(angle_)] = 0.0;
  z[static_cast<std::size_t>(rate_)] = 0.0;
}

std::string CageBridge::describe(const Model&) const {
  if (index_ > 0 && index_ < count_ - 1) return "";
  std::string out = fmt::format("  {:<12} mass {:.4g} kg, inertia {:.4g} kg m^2, {} states [{}..{}): {}\n", name(),
                                mass_, inertia_, 2, angle_, angle_ + 2,
                                "bending angle and rate (relative to the cage): border states");
  if (index_ == 0 && count_ > 2) out += fmt::format("  ... ({} more bridges alike)\n", count_ - 2);
  return out;
}

namespace {

/// A pocket bar riding on a bridge: the cage's translation, the cage's angle plus the bridge's.
class BridgeMarker final : public MarkerKind {
 public:
  BridgeMarker(std::shared_ptr<const CageBridge> bridge, int planning_id)
      : bridge_(std::move(bridge)), planning_id_(planning_id) {}
  int body() const override { return bridge_->cage(); }
  int planning_id() const override { return planning_id_; }
  contact::PlanarKinematics planar(const Model& m, double, const double* z, const contact::PlanarKinematics&,
                                   const double*, MarkerPoint&) const override {
    const auto& sl = m.bodies[static_cast<std::size_t>(bridge_->cage())].slot;
    auto state = [&](Coordinate c) { return sl[c] >= 0 ? z[sl[c]] : 0.0; };
    double theta = z[bridge_->angle_state()];
    double omega = z[bridge_->rate_state()];
    theta += z[sl[saz]];
    omega += z[sl[swz]];
    return {state(sx), state(sy), theta, state(svx), state(svy), omega};
  }
  /// The cage's translation columns and the bridge's own, each of which stands for the cage's
  /// angle (rate) too: the bar's angle is the sum.
  void columns(const Model& m, bool on_a, std::vector<SegmentColumn>& out) const override {
    const auto& sl = m.bodies[static_cast<std::size_t>(bridge_->cage())].slot;
    for (const Coordinate c : {sx, sy, saz, svx, svy, swz}) {
      if (c == saz)
        out.push_back({bridge_->cage(), c, bridge_->angle_state(), on_a, sl[saz]});
      else if (c == swz)
        out.push_back({bridge_->cage(), c, bridge_->rate_state(), on_a, sl[swz]});
      else if (sl[c] >= 0)
        out.push_back({bridge_->cage(), c, sl[c], on_a});
    }
  }
  /// The moment bends the bridge; the force moves the cage (both share one centre: no moment with it).
  void scatter(const Model&, const Segment&, bool, const double* w, double, const double*, Loads& loads) const override {
    loads.node[static_cast<std::size_t>(bridge_->force_offset)] += w[5];
    for (int i = 0; i < 3; ++i) loads.body[static_cast<std::size_t>(bridge_->cage())].force[i] += w[i];
  }
  void add_rate_derivative(const JacobianAssembly& a, int state, const Wrench& dw) const override {
    bridge_->add_moment_derivative(state, dw.moment.z(), a.jac);
    Wrench force = dw;
    force.moment = contact::Vec3::Zero();
    a.add_body_rate_derivative(bridge_->cage(), state, force);
  }

 private:
  std::shared_ptr<const CageBridge> bridge_;
  int planning_id_ = -1;
};

/// The bridges' nodes and markers, in bridge order.
struct BridgeParts {
  std::vector<int> node, marker;
};
BridgeParts bridge_parts(const Model& m) {
  BridgeParts parts;
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    if (dynamic_cast<const CageBridge*>(m.nodes[i].get())) parts.node.push_back(static_cast<int>(i));
  for (std::size_t i = 0; i < m.markers.size(); ++i)
    if (const auto* kind = std::get_if<std::shared_ptr<const MarkerKind>>(&m.markers[i]))
      if (dynamic_cast<const BridgeMarker*>(kind->get())) parts.marker.push_back(static_cast<int>(i));
  return parts;
}

}  // namespace

void add_cage_bridges(Model& m, const scene::Scene& scene, double cage_height) {
  if (scene.cage.bridges != scene::CageBridges::flexible) return;
  const BridgeBeam beam = bridge_beam(scene, cage_height);
  Body& cage = m.bodies[static_cast<std::size_t>(m.cage)];
  // The bridge's modal inertia moves with it: the cage keeps the rest of its inertia.
  const double bridge_inertia = beam.modal_mass * m.pitch_radius * m.pitch_radius;
  cage.axial_inertia -= m.element_count * bridge_inertia;
  if (!(cage.axial_inertia > 0))
    throw std::runtime_error(fmt::format("cage.inertia: the flexible bridges' inertia ({} x {:.4g} kg m^2) exceeds "
                                         "the cage's",
                                         m.element_count, bridge_inertia));
  // The angle class's tolerance (rtol rad) would allow k R rtol of bridge force, 21 N at rtol 1e-6
  // in seed 003's bearing, the size of the pocket forces without the carrier: the bending angle
  // gets rtol F / (k R), F the largest ring load (at least 1 N), so the bridge force is resolved to
  // rtol F; its rate that times the bending frequency.
  double load = 1.0;
  for (const scene::RingSpec* r : {&scene.inner_ring, &scene.outer_ring})
    load = std::max({load, max_abs(r->load.fx), max_abs(r->load.fy)});
  const double angle_tolerance = scene.solver.rtol * load / (beam.stiffness * m.pitch_radius);
  for (int k = 0; k < m.element_count; ++k) {
    const std::string name = fmt::format("cage_bridge[{}]", k);
    const int angle = add_state(m, VariableClass::angle, name + ".bending_angle");
    add_state(m, VariableClass::angular_velocity, name + ".bending_rate");
    auto bridge = std::make_shared<CageBridge>(k, m.element_count, m.cage, angle, beam, m.pitch_radius, angle_tolerance);
    const int node = m.add_node(bridge);
    m.add_marker(std::shared_ptr<const MarkerKind>(std::make_shared<BridgeMarker>(bridge, m.node_planning_id(node))));
    m.rate_followers.push_back({m.cage, swz, bridge->rate_state(), -1.0});  // relative: less the cage's
  }
}

void add_cage_bridge_segments(Model& m, const scene::Scene& scene, double cage_height) {
  const BridgeParts parts = bridge_parts(m);
  if (parts.node.empty()) return;
  const BridgeBeam beam = bridge_beam(scene, cage_height);
  m.laws.push_back(CageBridgeSpring{m.pitch_radius, beam.stiffness, beam.damping});
  const int law = static_cast<int>(m.laws.size()) - 1;
  for (std::size_t k = 0; k < parts.node.size(); ++k) {
    Segment seg{SegmentKind::cage_bridge, m.cage, m.cage, law, -1, fmt::format("cage_bridge[{}]", k)};
    seg.marker_b = parts.marker[k];
    m.segments.push_back(seg);
  }
}

int pocket_bar_marker(const Model& m, int k, int side) {
  const BridgeParts parts = bridge_parts(m);
  if (parts.marker.empty()) return -1;
  const int n = static_cast<int>(parts.marker.size());
  return parts.marker[static_cast<std::size_t>(side > 0 ? k : (k + n - 1) % n)];
}

std::vector<const CageBridge*> cage_bridges_of(const Model& m) {
  std::vector<const CageBridge*> out;
  for (const auto& n : m.nodes)
    if (const auto* b = dynamic_cast<const CageBridge*>(n.get())) out.push_back(b);
  return out;
}

std::string describe_bridge_segments(const Model& m) {
  const Segment* bridge = m.first_segment(SegmentKind::cage_bridge);
  if (!bridge) return "";
  int count = 0;
  for (const auto& s : m.segments) count += s.kind == SegmentKind::cage_bridge;
  const auto& b = m.law<CageBridgeSpring>(*bridge);
  return fmt::format("  cage_bridge x{}: flexible bridges (clamped beams), k = {:.4g} N/m, c = {:.4g} N s/m at "
                     "radius {:.4g} mm; the pocket bars ride on them\n",
                     count, b.stiffness, b.damping, 1e3 * b.radius);
}

}  // namespace raceway::bearing
