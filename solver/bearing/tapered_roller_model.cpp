// The spatial tapered roller bearing: a cone (inner ring) and a cup (outer ring) whose raceways are
// cones, tapered rollers between them whose apexes meet the raceways' on the bearing axis
// (contact/laws/tapered_geometry.hpp), the rollers' large ends against the cone's back rib, and a
// cage with a pocket per roller. Bodies, states and dynamics are the spatial cylindrical roller
// bearing's (spatial_roller_model.cpp): each roller has 11 states, its axis leaning by the geometry's
// beta from the bearing axis at the start.
//
// Each roller's contact with a raceway is cut into slices along its axis, slice j a Palmgren line
// contact of the registry with the profile's drop at its centre (sliced_line_contact.hpp) on a
// conical race (roller_slice_segment.hpp: race_angle), seeing the roller's own radius there: a
// tapered roller is thicker at its large end. The large end touches the cone's back rib at +z: a
// Hertz point contact (roller_flange_segment.hpp), flat with a rounded edge or spherical, the rib
// face leaning by rib_angle from the plane normal to the roller's axis; it carries the rollers'
// axial component. The rib is placed so that a roller at its nominal place, touching both
// raceways, just touches it: no end play (a tapered roller is held between its raceways).
#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "contact/laws/tapered_geometry.hpp"
#include "solver/bearing/housing.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/race_defects.hpp"

namespace raceway::bearing {

using contact::Vec3;

namespace {

constexpr double pi = std::numbers::pi;

double max_approach(const Model& m) { return 0.02 * m.element_radius; }
double damping_of(const scene::ContactSpec& spec) {
  return spec.damping.id == contact::LawId::no_damping ? 0.0 : spec.damping.factor;
}
double e_star(const scene::Material& a, const scene::Material& b) {
  return contact::reduced_modulus(a.youngs_modulus, a.poisson_ratio, b.youngs_modulus, b.poisson_ratio);
}
contact::TractionCurve traction_curve(const scene::ContactSpec& spec) {
  contact::TractionCurve t;
  if (spec.traction.id != contact::LawId::no_traction) {
    t.friction_coefficient = spec.traction.friction_coefficient;
    t.slip_velocity_scale = spec.traction.slip_velocity_scale;
  }
  return t;
}
int add_law(Model& m, SegmentLaw law) {
  m.laws.push_back(std::move(law));
  return static_cast<int>(m.laws.size()) - 1;
}

contact::TaperedGeometry geometry_of(const scene::Scene& scene) {
  const auto& g = scene.bearing;
  return contact::tapered_geometry(0.5 * g.pitch_diameter, 0.5 * g.roller_diameter, g.roller.cup_angle);
}

/// The roller's whole length along its axis: the straight part and the rounded corners.
double roller_length_of(const scene::Scene& scene) {
  return scene.bearing.roller_length + 2 * scene.bearing.roller.corner_radius;
}

void check_scene(const scene::Scene& scene) {
  if (scene.scene.model != scene::ModelKind::spatial || !scene.bearing.is_tapered())
    throw std::runtime_error("scene.model: the tapered roller model needs a tapered_roller bearing in the spatial model");
}

void set_geometry(Model& m, const scene::Scene& scene) {
  const auto& g = scene.bearing;
  const contact::TaperedGeometry t = geometry_of(scene);
  m.kind = scene::ModelKind::spatial;
  m.element_group = "rollers";
  m.element_count = g.rolling_elements;
  m.pitch_radius = 0.5 * g.pitch_diameter;
  m.element_radius = 0.5 * g.roller_diameter;
  // The raceways' radii at the foot of the normal from the roller's middle (r_r cos(gamma) away).
  m.inner_race_radius = m.pitch_radius - m.element_radius * std::cos(t.half_angle) * std::cos(t.cone_angle);
  m.outer_race_radius = m.pitch_radius + m.element_radius * std::cos(t.half_angle) * std::cos(t.cup_angle);
  m.cone_angle = t.cone_angle;
  m.cup_angle = t.cup_angle;
  set_roller_radii(m, g);
}

void add_rings(Model& m, const scene::Scene& scene) {
  const auto& g = scene.bearing;
  const double density = scene.material(g.ring_material).density;
  const double width = g.ring_width > 0 ? g.ring_width : g.roller_length;
  add_spatial_ring(m, BodyKind::inner_ring, "inner_ring", m.params().inner_ring, 0.5 * g.inner_bore_diameter,
                   m.inner_race_radius, width, density);
  add_spatial_ring(m, BodyKind::outer_ring, "outer_ring", m.params().outer_ring, m.outer_race_radius,
                   0.5 * g.outer_outside_diameter, width, density);
  add_housing(m, scene);
}

struct CageGeometry {
  double land_radius = 0, r_in = 0, r_out = 0;
};
CageGeometry cage_geometry(const Model& m, const scene::CageSpec& cs) {
  CageGeometry c;
  const double rr = m.element_radius;
  c.r_in = m.pitch_radius - 0.6 * rr;
  c.r_out = m.pitch_radius + 0.6 * rr;
  if (cs.guidance == scene::CageGuidance::inner_land) {
    c.land_radius = m.inner_race_radius + 0.5 * rr;
    c.r_in = c.land_radius + cs.land_clearance;
  } else if (cs.guidance == scene::CageGuidance::outer_land) {
    c.land_radius = m.outer_race_radius - 0.5 * rr;
    c.r_out = c.land_radius - cs.land_clearance;
  }
  return c;
}

/// A window cage: two side rings 30 % of the roller length wide and a bar between each pair of
/// pockets (the spatial cylindrical roller bearing's estimate), full pose.
void add_cage(Model& m, const scene::Scene& scene) {
  const auto& g = scene.bearing;
  const auto& cs = scene.cage;
  const CageGeometry geo = cage_geometry(m, cs);
  const double density = scene.material(cs.material).density;
  Body c;
  c.name = "cage";
  c.kind = BodyKind::cage;
  const double chord = g.pitch_diameter * std::sin(pi / g.rolling_elements);
  const double bar_thickness = std::max(chord - g.roller_diameter - cs.pocket_clearance, 0.1 * g.roller_diameter);
  const double rings = annulus_mass(density, geo.r_in, geo.r_out, 0.3 * g.roller_length);
  const double bars = density * g.rolling_elements * bar_thickness * (geo.r_out - geo.r_in) * g.roller_length;
  c.mass = cs.mass > 0 ? cs.mass : rings + bars;
  const double rr2 = geo.r_in * geo.r_in + geo.r_out * geo.r_out;
  c.axial_inertia = cs.inertia > 0 ? cs.inertia : 0.5 * c.mass * rr2;
  c.transverse_inertia = c.mass * (3.0 * rr2 + g.roller_length * g.roller_length) / 12.0;
  c.offset = m.state_size;
  add_states(m, c, sx, VariableClass::position, {"x", "y", "z"});
  add_states(m, c, sax, VariableClass::angle, {"angle_x", "angle_y", "angle_z"});
  add_states(m, c, svx, VariableClass::velocity, {"vx", "vy", "vz"});
  add_states(m, c, swx, VariableClass::angular_velocity, {"wx_body", "wy_body", "wz_body"});
  c.size = m.state_size - c.offset;
  m.bodies.push_back(c);
}

/// Rollers: a frustum's mass between the end radii; inertias of the cylinder of the mean square
/// radius (the frustum's centre of mass, a few per cent of the length towards the large end, is
/// taken at the middle).
void add_rollers(Model& m, const scene::Scene& scene) {
  const contact::TaperedGeometry t = geometry_of(scene);
  const double l = roller_length_of(scene);
  const double r1 = t.roller_radius_at(-0.5 * l), r2 = t.roller_radius_at(0.5 * l);
  const double mean_square = (r1 * r1 + r1 * r2 + r2 * r2) / 3.0;
  const double mass = scene.material(scene.bearing.roller_material).density * pi * mean_square * l;
  add_rolling_elements(m, "roller", mass, 0.5 * mass * mean_square, mass * (3.0 * mean_square + l * l) / 12.0,
                       spatial_roller_states(scene.rolling_element.any()));
  scale_scattered_rollers(m, mass, r1, r2, l);
}

/// The cone's back rib against the large end, placed so that a nominal roller just touches it.
contact::RollerFlangeSegment rib_law(const Model& m, const scene::Scene& scene, const contact::TaperedGeometry& t) {
  const auto& g = scene.bearing;
  const auto& r = g.roller;
  const double beta = t.axis_angle;
  const Vec3 centre(m.pitch_radius, 0.0, 0.0);
  const contact::RollerFlangeGeometry geo = contact::tapered_back_rib(
      t, m.pitch_radius, roller_length_of(scene),
      r.end == scene::RollerEnd::flat ? contact::RollerEndShape::flat : contact::RollerEndShape::spherical,
      r.end_radius, r.rib_angle);
  const auto& spec = scene.roller_flange;
  contact::PointTraction traction;
  traction.model = spec.traction.id == contact::LawId::no_traction ? contact::TractionModel::none
                                                                  : contact::TractionModel::curve;
  traction.friction_coefficient = spec.traction.friction_coefficient;
  traction.slip_velocity_scale = spec.traction.slip_velocity_scale > 0 ? spec.traction.slip_velocity_scale : 1.0;
  const double e = e_star(scene.material(g.roller_material), scene.material(g.ring_material));
  contact::RollerFlangeSegment law = contact::make_roller_flange_segment(geo, e, damping_of(spec), max_approach(m), traction);
  contact::SpatialKinematics ring_at_rest, roller_at_rest;
  roller_at_rest.position = centre;
  roller_at_rest.rotation = cardan_rotation(0.0, beta, 0.0);
  for (int pass = 0; pass < 2; ++pass) {
    const double approach = contact::evaluate(law, ring_at_rest, roller_at_rest).diagnostics.approach;
    law.geometry.rib_axial += approach / std::cos(law.geometry.rib_angle);
  }
  return law;
}

/// One slice law per slice and race: the raceway's cone, the roller's radius at the slice.
void add_slice_laws(Model& m, const scene::Scene& scene, const contact::TaperedGeometry& t, std::vector<int>& inner,
                    std::vector<int>& outer) {
  const auto& g = scene.bearing;
  const double e_race = e_star(scene.material(g.roller_material), scene.material(g.ring_material));
  const double rolling = m.element_radius * m.inner_race_radius / (m.element_radius + m.inner_race_radius);
  const contact::SlicedLineContact sliced = contact::make_sliced_line_contact(
      e_race, g.roller_profile(e_race, rolling), scene.roller_race.normal.slices, damping_of(scene.roller_race),
      max_approach(m));
  const auto traction = traction_curve(scene.roller_race);
  const auto cone_race = race_imperfections(scene.inner_ring, t.cone_radius, m.element_radius);
  const auto cup_race = race_imperfections(scene.outer_ring, t.cup_radius, m.element_radius);
  for (std::size_t j = 0; j < sliced.slice_centre.size(); ++j) {
    const double reach = t.roller_radius_at(sliced.slice_centre[j]) * std::cos(t.half_angle);
    auto cone = contact::make_roller_slice_segment(sliced, j, t.cone_radius, reach, false, traction);
    cone.race_angle = t.cone_angle;
    auto cup = contact::make_roller_slice_segment(sliced, j, t.cup_radius, reach, true, traction);
    cup.race_angle = t.cup_angle;
    cone.imperfections = cone_race, cup.imperfections = cup_race;
    inner.push_back(add_law(m, cone));
    outer.push_back(add_law(m, cup));
  }
}

void add_land_segment(Model& m, const scene::Scene& scene) {
  const auto& cs = scene.cage;
  if (cs.guidance == scene::CageGuidance::rolling_element) return;
  const CageGeometry geo = cage_geometry(m, cs);
  contact::CageLandSegment3 l;
  l.outer_land = cs.guidance == scene::CageGuidance::outer_land;
  l.clearance = cs.land_clearance;
  l.land_radius = geo.land_radius;
  l.width = cs.land_width > 0 ? cs.land_width : 0.5 * scene.bearing.roller_length;
  l.stations = 2;
  l.law = contact::make_line_contact_law(e_star(scene.material(cs.material), scene.material(scene.bearing.ring_material)),
                                         l.width, 1, 0.0, damping_of(scene.cage_land), max_approach(m));
  l.law.stiffness /= l.stations;
  l.law.slice_stiffness[0] = l.law.stiffness;
  const auto friction = traction_curve(scene.cage_land);
  l.friction.friction_coefficient = friction.friction_coefficient;
  l.friction.slip_velocity_scale = friction.slip_velocity_scale;
  const int law = add_law(m, l);
  m.segments.push_back({SegmentKind::cage_land, m.cage, l.outer_land ? m.outer_ring : m.inner_ring, law, -1,
                        l.outer_land ? "cage/outer_ring_land" : "cage/inner_ring_land"});
}

void add_segments(Model& m, const scene::Scene& scene) {
  const auto& g = scene.bearing;
  const auto& cs = scene.cage;
  const contact::TaperedGeometry t = geometry_of(scene);
  std::vector<int> inner_slices, outer_slices;
  add_slice_laws(m, scene, t, inner_slices, outer_slices);
  const int rib = add_law(m, rib_law(m, scene, t));
  const double bar_width = cs.bar_width > 0 ? cs.bar_width : g.roller_length;
  const double e_bar = e_star(scene.material(g.roller_material), scene.material(cs.material));
  for (int k = 0; k < m.element_count; ++k) {
    const int body = m.first_element + k;
    const std::vector<int> inner = roller_slice_laws(m, scene, k, inner_slices, std::cos(t.half_angle));
    const std::vector<int> outer = roller_slice_laws(m, scene, k, outer_slices, std::cos(t.half_angle));
    for (std::size_t j = 0; j < inner.size(); ++j)
      m.segments.push_back({SegmentKind::roller_inner_slice, m.inner_ring, body, inner[j], k,
                            fmt::format("roller[{}]/inner_race/slice[{}]", k, j)});
    for (std::size_t j = 0; j < outer.size(); ++j)
      m.segments.push_back({SegmentKind::roller_outer_slice, m.outer_ring, body, outer[j], k,
                            fmt::format("roller[{}]/outer_race/slice[{}]", k, j)});
    const double pocket = 2.0 * pi * k / m.element_count;
    for (const int side : {+1, -1}) {
      const int law = add_law(m, contact::make_roller_pocket_bar_segment(
                                     e_bar, bar_width, scene.roller_cage.normal.slices, m.pitch_radius, pocket,
                                     0.5 * cs.pocket_clearance, m.radius_of_element(k), side, damping_of(scene.roller_cage),
                                     max_approach(m), traction_curve(scene.roller_cage)));
      m.segments.push_back({side > 0 ? SegmentKind::cage_bar_front : SegmentKind::cage_bar_rear, m.cage, body, law, k,
                            fmt::format("roller[{}]/cage_bar_{}", k, side > 0 ? "front" : "rear")});
    }
    m.segments.push_back({SegmentKind::roller_flange, m.inner_ring, body, rib, k,
                          fmt::format("roller[{}]/inner_rib_plus_z", k)});
  }
  add_land_segment(m, scene);
  attach_outer_ring_to_housing(m);
}

std::string describe(const Model& m) {
  const auto& sc = m.params();
  const auto& r = sc.bearing.roller;
  const double deg = 180 / pi;
  std::string out = fmt::format("scene '{}' ({}): spatial model, {} bodies, {} states, {} contact segments\n",
                                sc.scene_name, sc.source, m.bodies.size(), m.state_size, m.segments.size());
  out += fmt::format("  {} tapered rollers, mean D = {:.4g} mm, length {:.4g} mm, pitch diameter {:.5g} mm; cup angle "
                     "{:.4g} deg, cone angle {:.4g} deg (apexes on the axis)\n",
                     m.element_count, 2e3 * m.element_radius, 1e3 * sc.bearing.roller_length, 2e3 * m.pitch_radius,
                     m.cup_angle * deg, m.cone_angle * deg);
  out += "bodies (states integrated; prescribed motions are functions of time, not states):\n";
  for (const auto& b : m.bodies) {
    if (b.kind == BodyKind::rolling_element && b.index > 0) continue;
    out += fmt::format("  {:<12} mass {:.4g} kg, inertia {:.4g} / {:.4g} kg m^2 (axial / transverse), {} states\n", b.name,
                       b.mass, b.axial_inertia, b.transverse_inertia, b.size);
  }
  for (const auto& node : m.nodes) out += node->describe(m);
  int count[segment_kind_count] = {};
  for (const auto& s : m.segments) ++count[static_cast<int>(s.kind)];
  out += "contact segments:\n";
  for (int k = 0; k < segment_kind_count; ++k)
    if (count[k] > 0) out += fmt::format("  {:<18} {}\n", segment_kind_name(static_cast<SegmentKind>(k)), count[k]);
  if (const Segment* rib = m.first_segment(SegmentKind::roller_flange)) {
    const auto& f = m.law<contact::RollerFlangeSegment>(*rib);
    out += fmt::format("  cone back rib: {} large ends (radius {:.4g} mm), rib face {:.3g} deg from the roller's end "
                       "plane, Hertz K = {:.4g}\n",
                       r.end == scene::RollerEnd::flat ? "flat" : "spherical", 1e3 * r.end_radius, r.rib_angle * deg,
                       f.hertz.stiffness);
  }
  out += describe_race_imperfections(m);
  out += describe_roller_diameters(m);
  out += fmt::format("state layout: border {} states (rings, cage), then {} blocks of {} (rollers)\n", m.border_size,
                     m.element_count, m.block_size);
  return out;
}

}  // namespace

const ModelBuilder& tapered_roller_model_builder() {
  static const ModelBuilder builder{check_scene, set_geometry, add_rings, add_cage, add_rollers, add_segments, describe};
  return builder;
}

}  // namespace raceway::bearing
