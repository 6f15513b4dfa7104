#include "solver/bearing/model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace raceway::solver {

using contact::Component;

const char* segment_kind_name(SegmentKind k) {
  switch (k) {
    case SegmentKind::roller_inner_race: return "roller_inner_race";
    case SegmentKind::roller_outer_race: return "roller_outer_race";
    case SegmentKind::cage_bar_front: return "cage_bar_front";
    case SegmentKind::cage_bar_rear: return "cage_bar_rear";
    case SegmentKind::cage_land: return "cage_land";
  }
  return "?";
}

namespace {

constexpr double pi = std::numbers::pi;

double annulus_mass(double density, double r_in, double r_out, double width) {
  return density * pi * (r_out * r_out - r_in * r_in) * width;
}

/// Adds the states of one body: translation if `translation`, angle if `angle`, spin rate if `spin`.
void add_states(Model& m, Body& b, bool translation, bool angle, bool spin) {
  b.offset = m.state_size;
  auto add = [&](Component c, VariableClass cls, const char* what) {
    b.slot[c] = m.state_size++;
    m.state_class.push_back(cls);
    m.state_name.push_back(b.name + "." + what);
  };
  if (translation) {
    add(Component::px, VariableClass::position, "x");
    add(Component::py, VariableClass::position, "y");
  }
  if (angle) add(Component::theta, VariableClass::angle, "theta");
  if (translation) {
    add(Component::vx, VariableClass::velocity, "vx");
    add(Component::vy, VariableClass::velocity, "vy");
  }
  if (spin) add(Component::omega, VariableClass::angular_velocity, "omega");
  b.size = m.state_size - b.offset;
}

void add_ring(Model& m, BodyKind kind, const char* name, const io::RingSpec& spec, double r_in,
              double r_out, double width, double density) {
  Body b;
  b.name = name;
  b.kind = kind;
  b.ring = &spec;
  b.mass = spec.mass > 0 ? spec.mass : annulus_mass(density, r_in, r_out, width);
  b.inertia = spec.inertia > 0 ? spec.inertia : 0.5 * b.mass * (r_in * r_in + r_out * r_out);
  const bool moves = spec.motion != io::RingMotion::fixed;
  add_states(m, b, moves && spec.translation_free, false, spec.motion == io::RingMotion::free);
  m.bodies.push_back(b);
}

double max_abs(const io::TimeFunction& f) {
  double v = 0;
  for (double x : f.values) v = std::max(v, std::abs(x));
  return v;
}

}  // namespace

Model build_model(const io::Scene& scene) {
  if (scene.scene.model != io::ModelKind::planar)
    throw std::runtime_error("scene.model: only the planar model is available in this build");
  Model m;
  m.scene = &scene;
  const auto& g = scene.bearing;
  const auto& steel = scene.material(g.roller_material);
  const auto& ring_mat = scene.material(g.ring_material);
  const auto& cage_mat = scene.material(scene.cage.material);
  m.roller_count = g.rolling_elements;
  m.pitch_radius = 0.5 * g.pitch_diameter;
  m.roller_radius = 0.5 * g.roller_diameter;
  m.inner_race_radius = 0.5 * g.inner_race_diameter();
  m.outer_race_radius = 0.5 * g.outer_race_diameter();
  m.gravity = scene.gravity ? 9.80665 : 0.0;
  const double width = g.ring_width > 0 ? g.ring_width : g.roller_length;

  // Border: rings and cage.
  add_ring(m, BodyKind::inner_ring, "inner_ring", scene.inner_ring, 0.5 * g.inner_bore_diameter,
           m.inner_race_radius, width, ring_mat.density);
  add_ring(m, BodyKind::outer_ring, "outer_ring", scene.outer_ring, m.outer_race_radius,
           0.5 * g.outer_outside_diameter, width, ring_mat.density);

  // Cage: two side rings (together 30 % of the roller length wide) and n bars between the pockets.
  // Land radii: a rib half a roller radius high on the guiding ring.
  const auto& cs = scene.cage;
  double land_radius = 0, cage_r_in = 0, cage_r_out = 0;
  switch (cs.guidance) {
    case io::CageGuidance::inner_land:
      land_radius = m.inner_race_radius + 0.5 * m.roller_radius;
      cage_r_in = land_radius + cs.land_clearance;
      cage_r_out = m.pitch_radius + 0.6 * m.roller_radius;
      break;
    case io::CageGuidance::outer_land:
      land_radius = m.outer_race_radius - 0.5 * m.roller_radius;
      cage_r_out = land_radius - cs.land_clearance;
      cage_r_in = m.pitch_radius - 0.6 * m.roller_radius;
      break;
    case io::CageGuidance::rolling_element:
      cage_r_in = m.pitch_radius - 0.6 * m.roller_radius;
      cage_r_out = m.pitch_radius + 0.6 * m.roller_radius;
      break;
  }
  {
    Body c;
    c.name = "cage";
    c.kind = BodyKind::cage;
    const double chord = g.pitch_diameter * std::sin(pi / g.rolling_elements);
    const double bar_thickness = chord - g.roller_diameter - cs.pocket_clearance;
    const double rings = annulus_mass(cage_mat.density, cage_r_in, cage_r_out, 0.3 * g.roller_length);
    const double bars = cage_mat.density * g.rolling_elements * bar_thickness *
                        (cage_r_out - cage_r_in) * g.roller_length;
    c.mass = cs.mass > 0 ? cs.mass : rings + bars;
    c.inertia = cs.inertia > 0 ? cs.inertia
                               : 0.5 * c.mass * (cage_r_in * cage_r_in + cage_r_out * cage_r_out);
    add_states(m, c, true, true, true);
    m.bodies.push_back(c);
  }
  m.border_size = m.state_size;

  // Rollers.
  const double roller_mass = steel.density * pi * m.roller_radius * m.roller_radius * g.roller_length;
  for (int k = 0; k < g.rolling_elements; ++k) {
    Body r;
    r.name = fmt::format("roller[{}]", k);
    r.kind = BodyKind::roller;
    r.index = k;
    r.mass = roller_mass;
    r.inertia = 0.5 * roller_mass * m.roller_radius * m.roller_radius;
    add_states(m, r, true, false, true);
    m.bodies.push_back(r);
  }

  // Laws: derived constants once, here.
  auto law_for = [&](const io::ContactSpec& spec, const io::Material& a, const io::Material& b,
                     double length) {
    const double e = contact::reduced_modulus(a.youngs_modulus, a.poisson_ratio, b.youngs_modulus,
                                              b.poisson_ratio);
    const double damping = spec.damping.name == "none" ? 0.0 : spec.damping.factor;
    // Validity: an approach of 2 % of the roller radius is far beyond any elastic deflection.
    return contact::make_line_contact_law(e, length, spec.normal.slices, spec.normal.crown_drop,
                                          damping, 0.02 * m.roller_radius);
  };
  auto traction_for = [](const io::ContactSpec& spec) {
    contact::TractionCurve t;
    if (spec.traction.name != "none") {
      t.friction_coefficient = spec.traction.friction_coefficient;
      t.slip_velocity_scale = spec.traction.slip_velocity_scale;
    }
    return t;
  };
  const auto race_law = law_for(scene.roller_race, steel, ring_mat, g.roller_length);
  const auto race_traction = traction_for(scene.roller_race);
  const double bar_width = cs.bar_width > 0 ? cs.bar_width : g.roller_length;
  const auto bar_law = law_for(scene.roller_cage, steel, cage_mat, bar_width);
  const auto bar_traction = traction_for(scene.roller_cage);

  m.race_segments.push_back({m.inner_race_radius, m.roller_radius, false, race_law, race_traction});
  m.race_segments.push_back({m.outer_race_radius, m.roller_radius, true, race_law, race_traction});
  for (int k = 0; k < m.roller_count; ++k) {
    const int body = m.first_roller + k;
    const double pocket = 2.0 * pi * k / m.roller_count;
    const int front = static_cast<int>(m.bar_segments.size());
    m.bar_segments.push_back({m.pitch_radius, pocket, 0.5 * cs.pocket_clearance, m.roller_radius, +1,
                              bar_law, bar_traction});
    m.bar_segments.push_back({m.pitch_radius, pocket, 0.5 * cs.pocket_clearance, m.roller_radius, -1,
                              bar_law, bar_traction});
    m.segments.push_back({SegmentKind::roller_inner_race, m.inner_ring, body, 0, k,
                          fmt::format("roller[{}]/inner_race", k)});
    m.segments.push_back({SegmentKind::roller_outer_race, m.outer_ring, body, 1, k,
                          fmt::format("roller[{}]/outer_race", k)});
    m.segments.push_back({SegmentKind::cage_bar_front, m.cage, body, front, k,
                          fmt::format("roller[{}]/cage_bar_front", k)});
    m.segments.push_back({SegmentKind::cage_bar_rear, m.cage, body, front + 1, k,
                          fmt::format("roller[{}]/cage_bar_rear", k)});
  }
  if (cs.guidance != io::CageGuidance::rolling_element) {
    const bool outer = cs.guidance == io::CageGuidance::outer_land;
    const int ring = outer ? m.outer_ring : m.inner_ring;
    const double land_width = cs.land_width > 0 ? cs.land_width : 0.5 * g.roller_length;
    m.land_segments.push_back({land_radius, cs.land_clearance, outer,
                               law_for(scene.cage_land, cage_mat, ring_mat, land_width),
                               traction_for(scene.cage_land)});
    m.segments.push_back({SegmentKind::cage_land, m.cage, ring, 0, -1,
                          outer ? "cage/outer_ring_land" : "cage/inner_ring_land"});
  }
  return m;
}

contact::PlanarKinematics Model::kinematics(int b, double t, const double* z) const {
  const Body& body = bodies[b];
  double v[6] = {0, 0, 0, 0, 0, 0};
  for (int c = 0; c < 6; ++c)
    if (body.slot[c] >= 0) v[c] = z[body.slot[c]];
  if (body.ring && body.ring->motion == io::RingMotion::driven) v[Component::omega] = body.ring->speed(t);
  return {v[0], v[1], v[2], v[3], v[4], v[5]};
}

double Model::epicyclic_cage_speed(double t) const {
  auto speed = [&](const Body& ring) {
    return ring.ring->motion == io::RingMotion::driven ? ring.ring->speed(t) : 0.0;
  };
  const double ri = inner_race_radius, ro = outer_race_radius;
  return (speed(bodies[inner_ring]) * ri + speed(bodies[outer_ring]) * ro) / (ri + ro);
}

std::vector<double> physical_absolute_tolerance(const io::Scene& scene, const std::vector<VariableClass>& state_class,
                                                double pitch_radius, double rolling_element_radius) {
  const auto& s = scene.solver;
  double drive = std::max(max_abs(scene.inner_ring.speed), max_abs(scene.outer_ring.speed));
  drive = std::max(drive, 1.0);
  const double surface_speed = drive * pitch_radius;
  const double spin_scale = drive * pitch_radius / rolling_element_radius;
  std::vector<double> atol(state_class.size());
  for (std::size_t i = 0; i < state_class.size(); ++i) {
    switch (state_class[i]) {
      case VariableClass::position: atol[i] = s.atol_position > 0 ? s.atol_position : s.rtol * pitch_radius; break;
      case VariableClass::angle: atol[i] = s.atol_angle > 0 ? s.atol_angle : s.rtol; break;
      case VariableClass::velocity: atol[i] = s.atol_velocity > 0 ? s.atol_velocity : s.rtol * surface_speed; break;
      case VariableClass::angular_velocity:
        atol[i] = s.atol_angular_velocity > 0 ? s.atol_angular_velocity : s.rtol * spin_scale;
        break;
    }
  }
  return atol;
}

std::vector<double> Model::absolute_tolerance() const {
  return physical_absolute_tolerance(*scene, state_class, pitch_radius, roller_radius);
}

std::string Model::describe() const {
  std::string out;
  const auto& sc = *scene;
  out += fmt::format("scene '{}' ({}): planar model, {} bodies, {} states, {} contact segments\n",
                     sc.scene.name, sc.source, bodies.size(), state_size, segments.size());
  out += "bodies (border first, then one block per roller):\n";
  for (const Body& b : bodies) {
    std::string why;
    switch (b.kind) {
      case BodyKind::inner_ring:
      case BodyKind::outer_ring: {
        const auto m = b.ring->motion;
        why = m == io::RingMotion::fixed ? "fixed: no states"
              : m == io::RingMotion::driven
                  ? (b.ring->translation_free ? "driven: speed prescribed, centre free under its load"
                                              : "driven, centre held: no states")
                  : "free: centre and spin integrated";
        if (b.ring->support.stiffness > 0) why += ", on a spring-damper support";
        break;
      }
      case BodyKind::cage: why = "x, y, angle and rates: its pockets are not symmetric"; break;
      case BodyKind::roller: why = "x, y, spin rate: the contact does not depend on its angle"; break;
    }
    if (b.kind == BodyKind::roller && b.index > 0 && b.index < roller_count - 1) continue;
    out += fmt::format("  {:<12} mass {:.4g} kg, inertia {:.4g} kg m^2, {} states [{}..{}): {}\n",
                       b.name, b.mass, b.inertia, b.size, b.offset, b.offset + b.size, why);
    if (b.kind == BodyKind::roller && b.index == 0 && roller_count > 2)
      out += fmt::format("  ... ({} more rollers alike)\n", roller_count - 2);
  }
  out += fmt::format("border states {}, roller blocks {} x 5\n", border_size, roller_count);
  int counts[segment_kind_count] = {};
  for (const auto& s : segments) counts[static_cast<int>(s.kind)]++;
  out += "segments:\n";
  const auto& race = race_segments.front().law;
  out += fmt::format("  roller_inner_race x{}, roller_outer_race x{}: Palmgren line contact, K = {:.4g} "
                     "N/m^(10/9), {} slice(s), Hunt-Crossley {:.3g} s/m, traction mu {:.3g}\n",
                     counts[0], counts[1], race.stiffness, race.slice_stiffness.size(),
                     race.damping_factor, race_segments.front().traction.friction_coefficient);
  const auto& bar = bar_segments.front();
  out += fmt::format("  cage_bar_front x{}, cage_bar_rear x{}: roller against pocket bars, pocket "
                     "clearance {:.4g} mm, K = {:.4g}, traction mu {:.3g}\n",
                     counts[2], counts[3], 2e3 * bar.half_clearance, bar.law.stiffness,
                     bar.traction.friction_coefficient);
  if (!land_segments.empty()) {
    const auto& l = land_segments.front();
    out += fmt::format("  cage_land x{}: cage on the {} ring land (radius {:.4g} mm, clearance {:.4g} "
                       "mm), K = {:.4g}, traction mu {:.3g}\n",
                       counts[4], l.outer_land ? "outer" : "inner", 1e3 * l.land_radius,
                       1e3 * l.clearance, l.law.stiffness, l.traction.friction_coefficient);
  } else {
    out += "  no cage_land segment: the cage is guided by the rollers\n";
  }
  out += fmt::format("geometry: pitch radius {:.4f} mm, races {:.4f} / {:.4f} mm, roller radius {:.4f} mm\n",
                     1e3 * pitch_radius, 1e3 * inner_race_radius, 1e3 * outer_race_radius,
                     1e3 * roller_radius);
  out += fmt::format("epicyclic cage speed at t=0: {:.2f} rpm\n", epicyclic_cage_speed(0) * 30 / pi);
  return out;
}

}  // namespace raceway::solver
