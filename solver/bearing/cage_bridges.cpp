#include "solver/bearing/cage_bridges.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace raceway::solver {

BridgeBeam bridge_beam(const io::Scene& scene, double cage_height) {
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
  b.stiffness = cs.bridge_stiffness > 0 ? cs.bridge_stiffness
                                        : 720.0 * b.youngs_modulus * b.area_moment / (b.span * b.span * b.span);
  b.mass = material.density * b.thickness * b.height * b.span;
  b.modal_mass = 10.0 / 7.0 * b.mass;
  b.damping = 2.0 * cs.bridge_damping_ratio * std::sqrt(b.stiffness * b.modal_mass);
  return b;
}

void add_cage_bridges(Model& m, const io::Scene& scene, double cage_height) {
  if (scene.cage.bridges != io::CageBridges::flexible) return;
  const BridgeBeam beam = bridge_beam(scene, cage_height);
  Body& cage = m.bodies[static_cast<std::size_t>(m.cage)];
  // The bridge's modal inertia moves with it: the cage keeps the rest of its inertia.
  const double bridge_inertia = beam.modal_mass * m.pitch_radius * m.pitch_radius;
  cage.axial_inertia -= m.element_count * bridge_inertia;
  if (!(cage.axial_inertia > 0))
    throw std::runtime_error(fmt::format("cage.inertia: the flexible bridges' inertia ({} x {:.4g} kg m^2) exceeds "
                                         "the cage's",
                                         m.element_count, bridge_inertia));
  for (int k = 0; k < m.element_count; ++k) {
    Body b;
    b.name = fmt::format("cage_bridge[{}]", k);
    b.kind = BodyKind::cage_bridge;
    b.index = k;
    b.mass = beam.modal_mass;
    // Its states: the angle and rate relative to the cage; u = pitch radius x angle.
    b.axial_inertia = bridge_inertia;
    b.carrier = m.cage;
    for (Coordinate c : {sx, sy, svx, svy}) b.slot[c] = cage.slot[c];
    b.offset = m.state_size;
    add_state(m, b, saz, VariableClass::angle, "bending_angle");
    add_state(m, b, swz, VariableClass::angular_velocity, "bending_rate");
    b.size = m.state_size - b.offset;
    m.border_bodies_after_elements.push_back(b);
  }
}

void add_cage_bridge_segments(Model& m, const io::Scene& scene, double cage_height) {
  if (m.bridge_count == 0) return;
  const BridgeBeam beam = bridge_beam(scene, cage_height);
  m.laws.push_back(contact::CageBridgeSegment{m.pitch_radius, beam.stiffness, beam.damping});
  const int law = static_cast<int>(m.laws.size()) - 1;
  for (int k = 0; k < m.bridge_count; ++k)
    m.segments.push_back({SegmentKind::cage_bridge, m.cage, m.first_bridge + k, law, -1,
                          fmt::format("cage_bridge[{}]", k)});
}

void set_bridge_tolerances(const Model& m, std::vector<double>& atol) {
  const Segment* spring = m.first_segment(SegmentKind::cage_bridge);
  if (!spring) return;
  const auto& law = m.law<contact::CageBridgeSegment>(*spring);
  double load = 1.0;
  for (const io::RingSpec* r : {&m.scene->inner_ring, &m.scene->outer_ring})
    load = std::max({load, max_abs(r->load.fx), max_abs(r->load.fy)});
  const double angle = m.scene->solver.rtol * load / (law.stiffness * law.radius);
  const double frequency = std::sqrt(law.stiffness * law.radius * law.radius /
                                     m.bodies[static_cast<std::size_t>(m.first_bridge)].axial_inertia);
  for (int k = 0; k < m.bridge_count; ++k) {
    const Body& b = m.bodies[static_cast<std::size_t>(m.first_bridge + k)];
    atol[static_cast<std::size_t>(b.slot[saz])] = angle;
    atol[static_cast<std::size_t>(b.slot[swz])] = angle * frequency;
  }
}

int pocket_bar_body(const Model& m, int k, int side) {
  if (m.bridge_count == 0) return m.cage;
  const int n = m.bridge_count;
  return m.first_bridge + (side > 0 ? k : (k + n - 1) % n);
}

}  // namespace raceway::solver
