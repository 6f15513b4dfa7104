// The planar cylindrical roller bearing (seed 002): rings, cage and rollers in the bearing plane.
//
// A roller carries x, y, vx, vy and its spin rate (5 states: the contact does not depend on its
// angle); a ring's angle about its own axis is never a state; the cage keeps x, y and its angle
// (its pockets are not symmetric). Within a body: positions (x, y[, angle]) then velocities
// (vx, vy[, rate]).
#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "solver/bearing/cage_bridges.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/ring_modes.hpp"

namespace raceway::bearing {

namespace {

constexpr double pi = std::numbers::pi;


/// Adds the states of one planar body: translation if `translation`, angle if `angle`, spin rate if `spin`.
void add_planar_states(Model& m, Body& b, bool translation, bool angle, bool spin) {
  b.offset = m.state_size;
  if (translation) add_state(m, b, sx, VariableClass::position, "x"), add_state(m, b, sy, VariableClass::position, "y");
  if (angle) add_state(m, b, saz, VariableClass::angle, "theta");
  if (translation) {  // a rolling element's in the orbital frame (orbital_frame.hpp) where the model says so
    const bool orbital = m.orbital_velocities && b.kind == BodyKind::rolling_element;
    add_state(m, b, svx, VariableClass::velocity, orbital ? "v_r" : "vx");
    add_state(m, b, svy, VariableClass::velocity, orbital ? "v_theta" : "vy");
  }
  if (spin) add_state(m, b, swz, VariableClass::angular_velocity, "omega");
  b.size = m.state_size - b.offset;
}

void add_ring(Model& m, BodyKind kind, const char* name, const scene::RingSpec& spec, double r_in, double r_out,
              double width, double density) {
  Body b;
  b.name = name;
  b.kind = kind;
  b.ring = &spec;
  b.mass = spec.mass > 0 ? spec.mass : annulus_mass(density, r_in, r_out, width);
  b.axial_inertia = spec.inertia > 0 ? spec.inertia : 0.5 * b.mass * (r_in * r_in + r_out * r_out);
  const bool moves = spec.motion != scene::RingMotion::fixed;
  add_planar_states(m, b, moves && spec.translation_free, false, spec.motion == scene::RingMotion::free);
  m.bodies.push_back(b);
}

struct CageGeometry {
  double land_radius = 0, r_in = 0, r_out = 0;
};

/// Land radii: a rib half a roller radius high on the guiding ring.
CageGeometry cage_geometry(const Model& m, const scene::CageSpec& cs) {
  CageGeometry c;
  const double rr = m.element_radius;
  switch (cs.guidance) {
    case scene::CageGuidance::inner_land:
      c.land_radius = m.inner_race_radius + 0.5 * rr;
      c.r_in = c.land_radius + cs.land_clearance;
      c.r_out = m.pitch_radius + 0.6 * rr;
      break;
    case scene::CageGuidance::outer_land:
      c.land_radius = m.outer_race_radius - 0.5 * rr;
      c.r_out = c.land_radius - cs.land_clearance;
      c.r_in = m.pitch_radius - 0.6 * rr;
      break;
    case scene::CageGuidance::rolling_element:
      c.r_in = m.pitch_radius - 0.6 * rr;
      c.r_out = m.pitch_radius + 0.6 * rr;
      break;
  }
  return c;
}

/// Cage: two side rings (together 30 % of the roller length wide) and n bars between the pockets.
void add_cage(Model& m, const scene::Scene& scene, const CageGeometry& geo) {
  const auto& g = scene.bearing;
  const auto& cs = scene.cage;
  const auto& cage_mat = scene.material(cs.material);
  Body c;
  c.name = "cage";
  c.kind = BodyKind::cage;
  const double chord = g.pitch_diameter * std::sin(pi / g.rolling_elements);
  const double bar_thickness = chord - g.roller_diameter - cs.pocket_clearance;
  const double rings = annulus_mass(cage_mat.density, geo.r_in, geo.r_out, 0.3 * g.roller_length);
  const double bars = cage_mat.density * g.rolling_elements * bar_thickness * (geo.r_out - geo.r_in) * g.roller_length;
  c.mass = cs.mass > 0 ? cs.mass : rings + bars;
  c.axial_inertia = cs.inertia > 0 ? cs.inertia : 0.5 * c.mass * (geo.r_in * geo.r_in + geo.r_out * geo.r_out);
  add_planar_states(m, c, true, true, true);
  m.bodies.push_back(c);
  add_cage_bridges(m, scene, geo.r_out - geo.r_in);
}

void add_rollers(Model& m, const scene::Scene& scene) {
  const auto& g = scene.bearing;
  const double rr = m.element_radius;
  const double roller_mass = scene.material(g.roller_material).density * pi * rr * rr * g.roller_length;
  m.orbital_velocities = scene.solver.element_velocity_frame == scene::ElementVelocityFrame::orbital;
  add_rolling_elements(m, "roller", roller_mass, 0.5 * roller_mass * rr * rr, 0.0,
                       [](Model& model, Body& r) { add_planar_states(model, r, true, false, true); });
  scale_scattered_rollers(m, roller_mass, rr, rr, g.roller_length);
}

/// Line-contact law and traction of one contact: derived constants once, here.
struct LineLaws {
  const Model& m;
  contact::LineContactLaw law(const scene::ContactSpec& spec, const scene::Material& a, const scene::Material& b,
                              double length) const {
    const double e = contact::reduced_modulus(a.youngs_modulus, a.poisson_ratio, b.youngs_modulus, b.poisson_ratio);
    const double damping = spec.damping.id == contact::LawId::no_damping ? 0.0 : spec.damping.factor;
    // Validity: an approach of 2 % of the roller radius is far beyond any elastic deflection.
    return contact::make_line_contact_law(e, length, spec.normal.slices, spec.normal.crown_drop, damping,
                                          0.02 * m.element_radius);
  }
  static contact::TractionCurve traction(const scene::ContactSpec& spec) {
    contact::TractionCurve t;
    if (spec.traction.id != contact::LawId::no_traction) {
      t.friction_coefficient = spec.traction.friction_coefficient;
      t.slip_velocity_scale = spec.traction.slip_velocity_scale;
    }
    return t;
  }
};

/// The lubricated laws of seed 003 where the scene chooses them: the EHD film of a race of radius
/// `race_radius` (`internal`: the outer race) and the hydrodynamic film of a cage bar (line_film);
/// the cage film collapses to the dry contact at 0.2 um, the combined roughness of ground surfaces.
void add_race_film(contact::RollerRaceSegment& seg, const scene::Scene& scene) {
  const double length = scene.bearing.roller_length;
  const double e_star = seg.law.stiffness / contact::palmgren_stiffness(1.0, length);  // K = c_P E* l^(8/9)
  const double curvature = 1.0 / seg.roller_radius + (seg.internal ? -1.0 : 1.0) / seg.race_radius;
  seg.ehd = roller_race_film(scene, line_film(scene, e_star, 1.0 / curvature, length, seg.roller_radius),
                             seg.law.stiffness, seg.law.max_approach, seg.law.damping_factor);
}

void add_bar_film(contact::CageBarSegment& seg, const scene::Scene& scene, double length) {
  if (scene.roller_cage.normal.id != contact::LawId::hydrodynamic) return;
  const double e_star = seg.law.stiffness / contact::palmgren_stiffness(1.0, length);
  contact::HydrodynamicLineLaw film;
  film.film = line_film(scene, e_star, seg.roller_radius, length, seg.roller_radius);
  film.film_floor = 0.2e-6;
  film.dry = seg.law;
  seg.film = film;
}

int add_law(Model& m, SegmentLaw law) {
  m.laws.push_back(std::move(law));
  return static_cast<int>(m.laws.size()) - 1;
}

void add_roller_segments(Model& m, const scene::Scene& scene) {
  const auto& g = scene.bearing;
  const auto& cs = scene.cage;
  const auto& steel = scene.material(g.roller_material);
  const auto& ring_mat = scene.material(g.ring_material);
  const LineLaws laws{m};
  const auto race_law = laws.law(scene.roller_race, steel, ring_mat, g.roller_length);
  const auto race_traction = LineLaws::traction(scene.roller_race);
  const double bar_width = cs.bar_width > 0 ? cs.bar_width : g.roller_length;
  const auto bar_law = laws.law(scene.roller_cage, steel, scene.material(cs.material), bar_width);
  const auto bar_traction = LineLaws::traction(scene.roller_cage);
  const double rr0 = m.element_radius;
  contact::RollerRaceSegment inner_race{m.inner_race_radius, rr0, false, race_law, race_traction, std::nullopt};
  contact::RollerRaceSegment outer_race{m.outer_race_radius, rr0, true, race_law, race_traction, std::nullopt};
  add_race_film(inner_race, scene);
  add_race_film(outer_race, scene);
  const int shared_inner = add_law(m, inner_race);
  const int shared_outer = add_law(m, outer_race);
  const int outer_marker = outer_race_marker(m);  // a point on a flexible rim, or the ring's centre
  for (int k = 0; k < m.element_count; ++k) {
    const int body = m.first_element + k;
    const double pocket = 2.0 * pi * k / m.element_count;
    const double half = 0.5 * cs.pocket_clearance;
    // A scattered roller: race laws of its own radius (its film too); the shared ones otherwise.
    const double rr = m.radius_of_element(k);
    int inner = shared_inner, outer = shared_outer;
    if (!m.element_radii.empty()) {
      for (auto* race : {&inner_race, &outer_race}) race->roller_radius = rr;
      add_race_film(inner_race, scene);
      add_race_film(outer_race, scene);
      inner = add_law(m, inner_race);
      outer = add_law(m, outer_race);
    }
    contact::CageBarSegment front_bar{m.pitch_radius, pocket, half, rr, +1, bar_law, bar_traction, std::nullopt};
    contact::CageBarSegment rear_bar{m.pitch_radius, pocket, half, rr, -1, bar_law, bar_traction, std::nullopt};
    add_bar_film(front_bar, scene, bar_width);
    add_bar_film(rear_bar, scene, bar_width);
    const int front = add_law(m, front_bar);
    const int rear = add_law(m, rear_bar);
    m.segments.push_back({SegmentKind::roller_inner_race, m.inner_ring, body, inner, k, fmt::format("roller[{}]/inner_race", k)});
    m.segments.push_back({SegmentKind::roller_outer_race, m.outer_ring, body, outer, k,
                          fmt::format("roller[{}]/outer_race", k), outer_marker});
    // The pocket bars ride on flexible bridges where the cage has them.
    m.segments.push_back({SegmentKind::cage_bar_front, m.cage, body, front, k, fmt::format("roller[{}]/cage_bar_front", k),
                          pocket_bar_marker(m, k, +1)});
    m.segments.push_back({SegmentKind::cage_bar_rear, m.cage, body, rear, k, fmt::format("roller[{}]/cage_bar_rear", k),
                          pocket_bar_marker(m, k, -1)});
  }
}

void add_land_segment(Model& m, const scene::Scene& scene, const CageGeometry& geo) {
  const auto& cs = scene.cage;
  if (cs.guidance == scene::CageGuidance::rolling_element) return;
  const bool outer = cs.guidance == scene::CageGuidance::outer_land;
  const double land_width = cs.land_width > 0 ? cs.land_width : 0.5 * scene.bearing.roller_length;
  const LineLaws laws{m};
  const auto law = laws.law(scene.cage_land, scene.material(cs.material), scene.material(scene.bearing.ring_material),
                            land_width);
  contact::CageLandSegment land{geo.land_radius, cs.land_clearance, outer, law, LineLaws::traction(scene.cage_land),
                                std::nullopt};
  if (scene.cage_land.normal.id == contact::LawId::short_bearing) {
    // The land's short-bearing film (contact/laws/short_bearing_film.hpp) over its width, collapsing to
    // the dry law at 0.2 um, the combined roughness of ground surfaces (as the ball bearings' land).
    contact::ShortBearingFilm film;
    film.viscosity = scene.lubricant.viscosity;
    film.radius = geo.land_radius;
    film.width = land_width;
    film.clearance = cs.land_clearance;
    film.film_floor = 0.2e-6;
    land.film = film;
  }
  const int index = add_law(m, land);
  m.segments.push_back({SegmentKind::cage_land, m.cage, outer ? m.outer_ring : m.inner_ring, index, -1,
                        outer ? "cage/outer_ring_land" : "cage/inner_ring_land"});
}

void check_scene(const scene::Scene& scene) {
  if (scene.scene.model != scene::ModelKind::planar || scene.bearing.is_ball_bearing())
    throw std::runtime_error("scene.model: the planar model needs a cylindrical roller bearing (bearing.type)");
}

void set_geometry(Model& m, const scene::Scene& scene) {
  const auto& g = scene.bearing;
  m.kind = scene::ModelKind::planar;
  m.element_group = "rollers";
  m.element_count = g.rolling_elements;
  m.pitch_radius = 0.5 * g.pitch_diameter;
  m.element_radius = 0.5 * g.roller_diameter;
  m.inner_race_radius = 0.5 * g.inner_race_diameter();
  m.outer_race_radius = 0.5 * g.outer_race_diameter();
  set_roller_radii(m, g);
}

void add_rings(Model& m, const scene::Scene& scene) {
  const auto& g = scene.bearing;
  const double density = scene.material(g.ring_material).density;
  const double width = g.ring_width > 0 ? g.ring_width : g.roller_length;
  add_ring(m, BodyKind::inner_ring, "inner_ring", m.params().inner_ring, 0.5 * g.inner_bore_diameter,
           m.inner_race_radius, width, density);
  add_ring(m, BodyKind::outer_ring, "outer_ring", m.params().outer_ring, m.outer_race_radius,
           0.5 * g.outer_outside_diameter, width, density);
  add_ring_modes(m, scene);
}

void add_segments(Model& m, const scene::Scene& scene) {
  add_roller_segments(m, scene);
  const CageGeometry geo = cage_geometry(m, scene.cage);
  add_land_segment(m, scene, geo);
  add_cage_bridge_segments(m, scene, geo.r_out - geo.r_in);
  add_ring_mode_segments(m);
}

}  // namespace

std::string describe_roller_model(const Model& m);

const ModelBuilder& roller_model_builder() {
  static const ModelBuilder builder{
      check_scene, set_geometry, add_rings,
      [](Model& m, const scene::Scene& scene) { add_cage(m, scene, cage_geometry(m, scene.cage)); }, add_rollers,
      add_segments, describe_roller_model};
  return builder;
}

std::string describe_roller_model(const Model& m) {
  std::string out;
  const auto& sc = m.params();
  out += fmt::format("scene '{}' ({}): planar model, {} bodies{}, {} states, {} contact segments\n", sc.scene_name,
                     sc.source, m.bodies.size(), m.nodes.empty() ? "" : fmt::format(" and {} node{}", m.nodes.size(), m.nodes.size() == 1 ? "" : "s"),
                     m.state_size, m.segments.size());
  out += "bodies (border first, then one block per roller):\n";
  for (const Body& b : m.bodies) {
    std::string why;
    switch (b.kind) {
      case BodyKind::inner_ring:
      case BodyKind::outer_ring: {
        const auto motion = b.ring->motion;
        why = motion == scene::RingMotion::fixed ? "fixed: no states"
              : motion == scene::RingMotion::driven
                  ? (b.ring->translation_free ? "driven: speed prescribed, centre free under its load"
                                              : "driven, centre held: no states")
                  : "free: centre and spin integrated";
        if (b.ring->support.stiffness > 0) why += ", on a spring-damper support";
        break;
      }
      case BodyKind::cage: why = "x, y, angle and rates: its pockets are not symmetric"; break;
      case BodyKind::rolling_element: why = "x, y, spin rate: the contact does not depend on its angle"; break;
    }
    const bool repeated = b.kind == BodyKind::rolling_element;
    const int count = m.element_count;
    if (repeated && b.index > 0 && b.index < count - 1) continue;
    out += fmt::format("  {:<12} mass {:.4g} kg, inertia {:.4g} kg m^2, {} states [{}..{}): {}\n", b.name, b.mass,
                       b.axial_inertia, b.size, b.offset, b.offset + b.size, why);
    if (repeated && b.index == 0 && count > 2)
      out += fmt::format("  ... ({} more rollers{})\n", count - 2, m.element_radii.empty() ? " alike" : ", each of its own diameter");
  }
  for (const auto& node : m.nodes) out += node->describe(m);
  out += fmt::format("border states {}, roller blocks {} x {}\n", m.border_size, m.element_count, m.block_size);
  int counts[segment_kind_count] = {};
  for (const auto& s : m.segments) counts[static_cast<int>(s.kind)]++;
  auto count = [&](SegmentKind k) { return counts[static_cast<int>(k)]; };
  out += "segments:\n";
  const auto& race = m.law<contact::RollerRaceSegment>(*m.first_segment(SegmentKind::roller_inner_race));
  out += fmt::format("  roller_inner_race x{}, roller_outer_race x{}: Palmgren line contact, K = {:.4g} "
                     "N/m^(10/9), {} slice(s), Hunt-Crossley {:.3g} s/m, traction mu {:.3g}\n",
                     count(SegmentKind::roller_inner_race), count(SegmentKind::roller_outer_race), race.law.stiffness,
                     race.law.slice_stiffness.size(), race.law.damping_factor, race.traction.friction_coefficient);
  const auto& bar = m.law<contact::CageBarSegment>(*m.first_segment(SegmentKind::cage_bar_front));
  out += fmt::format("  cage_bar_front x{}, cage_bar_rear x{}: roller against pocket bars, pocket "
                     "clearance {:.4g} mm, K = {:.4g}, traction mu {:.3g}\n",
                     count(SegmentKind::cage_bar_front), count(SegmentKind::cage_bar_rear), 2e3 * bar.half_clearance,
                     bar.law.stiffness, bar.traction.friction_coefficient);
  if (const Segment* land = m.first_segment(SegmentKind::cage_land)) {
    const auto& l = m.law<contact::CageLandSegment>(*land);
    out += fmt::format("  cage_land x{}: cage on the {} ring land (radius {:.4g} mm, clearance {:.4g} "
                       "mm), K = {:.4g}, traction mu {:.3g}{}\n",
                       count(SegmentKind::cage_land), l.outer_land ? "outer" : "inner", 1e3 * l.land_radius,
                       1e3 * l.clearance, l.law.stiffness, l.traction.friction_coefficient,
                       l.film ? ", short-bearing film (Ocvirk, half-Sommerfeld)" : "");
  } else {
    out += "  no cage_land segment: the cage is guided by the rollers\n";
  }
  out += describe_roller_diameters(m);
  out += describe_bridge_segments(m);
  out += describe_ring_mode_segments(m);
  out += fmt::format("geometry: pitch radius {:.4f} mm, races {:.4f} / {:.4f} mm, roller radius {:.4f} mm\n",
                     1e3 * m.pitch_radius, 1e3 * m.inner_race_radius, 1e3 * m.outer_race_radius,
                     1e3 * m.element_radius);
  out += fmt::format("epicyclic cage speed at t=0: {:.2f} rpm\n", m.epicyclic_cage_speed(0) * 30 / pi);
  return out;
}

}  // namespace raceway::bearing
