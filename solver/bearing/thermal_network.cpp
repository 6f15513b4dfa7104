#include "solver/bearing/thermal_network.hpp"

#include <fmt/format.h>

#include <numbers>

#include "solver/bearing/element_traits.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/segment_record.hpp"

namespace raceway::bearing {

namespace {

constexpr double pi = std::numbers::pi;
constexpr double steel_conductivity = 45.0;  ///< W/(m K)
constexpr double oil_specific_heat = 1900.0;  ///< J/(kg K)
constexpr double oil_density = 870.0;         ///< kg/m^3, where the scene's lubricant gives none

int part_of(const Model& m, int body) {
  if (body == m.inner_ring) return ThermalNetwork::inner_ring;
  if (body == m.outer_ring) return ThermalNetwork::outer_ring;
  if (body == m.cage) return ThermalNetwork::cage;
  return ThermalNetwork::rolling_elements;
}

/// Where each segment's loss goes: drag and churning into the oil, a contact's to its two bodies.
std::vector<ThermalNetwork::Heat> heat_routing(const Model& m) {
  std::vector<ThermalNetwork::Heat> heat;
  for (const Segment& seg : m.segments) {
    const int field = std::visit([](const auto& l) { return diagnostic_index<std::decay_t<decltype(l)>>("power_loss"); },
                                 m.laws[static_cast<std::size_t>(seg.law)]);
    if (seg.kind == SegmentKind::ball_drag || seg.kind == SegmentKind::cage_churning)
      heat.push_back({ThermalNetwork::oil, ThermalNetwork::oil, field});
    else
      heat.push_back({part_of(m, seg.body_a), part_of(m, seg.body_b), field});
  }
  return heat;
}

/// The geometry the defaults come from (docs/lubrication.md, "Thermal network").
struct ThermalGeometry {
  double width, r_inner_race, r_outer_race, r_bore, r_outside, element_diameter, element_length, elements;
  explicit ThermalGeometry(const scene::BearingGeometry& g)
      : width(g.ring_width > 0 ? g.ring_width : g.roller_length),
        r_inner_race(0.5 * g.inner_race_diameter()),
        r_outer_race(0.5 * g.outer_race_diameter()),
        r_bore(0.5 * g.inner_bore_diameter),
        r_outside(0.5 * g.outer_outside_diameter),
        element_diameter(g.element_diameter()),
        element_length(g.is_ball_bearing() ? 0.0 : g.roller_length),
        elements(static_cast<double>(g.rolling_elements)) {}
  bool balls() const { return element_length == 0.0; }
  double element_area() const {
    const double d = element_diameter;
    return elements * (balls() ? pi * d * d : pi * d * element_length + 0.5 * pi * d * d);
  }
  double element_volume() const {
    const double d = element_diameter;
    return elements * (balls() ? pi * d * d * d / 6.0 : 0.25 * pi * d * d * element_length);
  }
  double free_volume() const {
    return pi * (r_outer_race * r_outer_race - r_inner_race * r_inner_race) * width - element_volume();
  }
  /// The housing: a cylinder of twice the outer ring's outside diameter and three times its width.
  double housing_area() const {
    const double r = 2.0 * r_outside;
    return 2.0 * pi * r * 3.0 * width + 2.0 * pi * (r * r - r_outside * r_outside);
  }
};

double or_default(double given, double fallback) { return given >= 0 ? given : fallback; }

std::vector<ThermalNetwork::Link> links_of(const scene::ThermalSpec& th, const ThermalGeometry& g) {
  using TN = ThermalNetwork;
  const double contact = or_default(th.element_ring_conductance, 2.0 * steel_conductivity * g.element_diameter / 20.0);
  const double h = th.convection_coefficient;
  return {{TN::inner_ring, TN::rolling_elements, g.elements * contact, "inner_ring-rolling_elements"},
          {TN::outer_ring, TN::rolling_elements, g.elements * contact, "outer_ring-rolling_elements"},
          {TN::inner_ring, TN::oil, h * 2.0 * pi * g.r_inner_race * g.width, "inner_ring-oil"},
          {TN::outer_ring, TN::oil, h * 2.0 * pi * g.r_outer_race * g.width, "outer_ring-oil"},
          {TN::rolling_elements, TN::oil, h * g.element_area(), "rolling_elements-oil"},
          {TN::cage, TN::oil, h * 2.0 * 2.0 * pi * 0.5 * (g.r_inner_race + g.r_outer_race) * g.width, "cage-oil"},
          {TN::outer_ring, TN::housing, th.fit_conductance * 2.0 * pi * g.r_outside * g.width, "outer_ring-housing"},
          {TN::inner_ring, TN::ambient, th.fit_conductance * 2.0 * pi * g.r_bore * g.width, "inner_ring-shaft"},
          {TN::housing, TN::ambient, th.ambient_convection_coefficient * g.housing_area(), "housing-ambient"}};
}

}  // namespace

ThermalNetwork::ThermalNetwork(std::array<double, parts> capacity, std::vector<Link> links, std::vector<Heat> heat,
                               double ambient_temperature, double initial_temperature, int first_state)
    : capacity_(capacity), links_(std::move(links)), heat_(std::move(heat)), ambient_(ambient_temperature),
      initial_(initial_temperature), first_state_(first_state) {}

void ThermalNetwork::heat_inputs(const double* records, double out[parts]) const {
  for (int k = 0; k < parts; ++k) out[k] = 0.0;
  for (std::size_t s = 0; s < heat_.size(); ++s) {
    const double p = records[s * SegmentRecord::size + SegmentRecord::diagnostics + static_cast<std::size_t>(heat_[s].field)];
    out[heat_[s].a] += 0.5 * p;
    out[heat_[s].b] += 0.5 * p;
  }
}

void ThermalNetwork::link_flows(const double* z, double* out) const {
  for (std::size_t i = 0; i < links_.size(); ++i)
    out[i] = links_[i].conductance * (temperature(z, links_[i].a) - temperature(z, links_[i].b));
}

void ThermalNetwork::rates(const Model&, double, const double* z, const double*, double* zdot) const {
  double net[parts] = {};
  for (const Link& l : links_) {
    const double flow = l.conductance * (temperature(z, l.a) - temperature(z, l.b));
    net[l.a] -= flow;
    if (l.b != ambient) net[l.b] += flow;
  }
  for (int k = 0; k < parts; ++k) zdot[state(k)] = net[k] / capacity_[static_cast<std::size_t>(k)];
}

void ThermalNetwork::add_segment_rates(const Model&, double, const double*, const double* records, double* zdot) const {
  double q[parts];
  heat_inputs(records, q);
  for (int k = 0; k < parts; ++k) zdot[state(k)] += q[k] / capacity_[static_cast<std::size_t>(k)];
}

void ThermalNetwork::add_own_jacobian(const Model&, double, numerics::BorderedMatrix& jac) const {
  for (const Link& l : links_) {
    const double ca = capacity_[static_cast<std::size_t>(l.a)];
    jac.add(state(l.a), state(l.a), -l.conductance / ca);
    if (l.b == ambient) continue;
    const double cb = capacity_[static_cast<std::size_t>(l.b)];
    jac.add(state(l.a), state(l.b), l.conductance / ca);
    jac.add(state(l.b), state(l.b), -l.conductance / cb);
    jac.add(state(l.b), state(l.a), l.conductance / cb);
  }
}

void ThermalNetwork::set_tolerances(std::vector<double>& atol) const {
  for (int k = 0; k < parts; ++k) atol[static_cast<std::size_t>(state(k))] = 1e-4;  // K
}

void ThermalNetwork::initial_state(std::vector<double>& z) const {
  for (int k = 0; k < parts; ++k) z[static_cast<std::size_t>(state(k))] = initial_;
}

std::string ThermalNetwork::describe(const Model&) const {
  std::string out = fmt::format("  {}: states {}..{}, temperatures [K] of", name(), first_state_, first_state_ + parts - 1);
  for (int k = 0; k < parts; ++k) out += fmt::format(" {} ({:.4g} J/K)", part_names[k], capacity_[static_cast<std::size_t>(k)]);
  out += fmt::format("; ambient {:.5g} K; links [W/K]:", ambient_);
  for (const Link& l : links_) out += fmt::format(" {} {:.4g}", l.name, l.conductance);
  return out + "\n";
}

int add_thermal_states(Model& m, const scene::Scene& scene) {
  if (!scene.thermal.present) return -1;
  int first = -1;
  for (int k = 0; k < ThermalNetwork::parts; ++k) {
    const int s = add_state(m, VariableClass::angle, std::string("thermal.") + ThermalNetwork::part_names[k]);
    if (k == 0) first = s;
  }
  return first;
}

void add_thermal_network(Model& m, const scene::Scene& scene, int first_state) {
  const scene::ThermalSpec& th = scene.thermal;
  const ThermalGeometry g(scene.bearing);
  double element_mass = 0;
  for (std::size_t b = static_cast<std::size_t>(m.first_element); b < m.bodies.size(); ++b) element_mass += m.bodies[b].mass;
  std::array<double, ThermalNetwork::parts> c{};
  c[ThermalNetwork::inner_ring] = th.specific_heat * m.bodies[static_cast<std::size_t>(m.inner_ring)].mass;
  c[ThermalNetwork::outer_ring] = th.specific_heat * m.bodies[static_cast<std::size_t>(m.outer_ring)].mass;
  c[ThermalNetwork::rolling_elements] = th.specific_heat * element_mass;
  c[ThermalNetwork::cage] = th.cage_specific_heat * m.bodies[static_cast<std::size_t>(m.cage)].mass;
  const double rho = scene.lubricant.density > 0 ? scene.lubricant.density : oil_density;
  c[ThermalNetwork::oil] = or_default(th.oil_heat_capacity, g.free_volume() * rho * oil_specific_heat);
  c[ThermalNetwork::housing] = or_default(th.housing_heat_capacity, 5.0 * c[ThermalNetwork::outer_ring]);
  const scene::Lubricant& oil = scene.lubricant;
  const double initial = th.initial_temperature > 0 ? th.initial_temperature
                         : oil.temperature > 0      ? oil.temperature
                                                    : th.ambient_temperature;
  // The ball-groove contacts' viscosity at the oil's temperature, where the data sheet gives it.
  if (oil.viscosity_40 > 0 && oil.viscosity_100 > 0 && oil.density > 0)
    m.oil_viscosity = {first_state + ThermalNetwork::oil,
                       contact::walther_constants(oil.viscosity_40, 313.15, oil.viscosity_100, 373.15), oil.density};
  m.add_node(std::make_shared<ThermalNetwork>(c, links_of(th, g), heat_routing(m), th.ambient_temperature, initial,
                                              first_state));
}

const ThermalNetwork* thermal_network_of(const Model& m) {
  for (const auto& node : m.nodes)
    if (const auto* t = dynamic_cast<const ThermalNetwork*>(node.get())) return t;
  return nullptr;
}

}  // namespace raceway::bearing
