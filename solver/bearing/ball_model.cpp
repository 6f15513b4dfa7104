#include "solver/bearing/model.hpp"

#include <fmt/format.h>

#include "contact/laws/viscosity.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "solver/bearing/housing.hpp"
#include "solver/bearing/race_defects.hpp"

namespace raceway::bearing {

using contact::Mat3;
using contact::Vec3;

namespace {

constexpr double pi = std::numbers::pi;

/// Polar and diametral moments of inertia of a thick ring (hollow cylinder).
double annulus_axial_inertia(double mass, double r_in, double r_out) { return 0.5 * mass * (r_in * r_in + r_out * r_out); }
double annulus_transverse_inertia(double mass, double r_in, double r_out, double width) {
  return mass * (3.0 * (r_in * r_in + r_out * r_out) + width * width) / 12.0;
}

}  // namespace

/// Ring states: positions (x, y, z, tilts) then velocities (vx, vy, vz, tilt rates, spin).
void add_spatial_ring(Model& m, BodyKind kind, const char* name, const scene::RingSpec& spec, double r_in,
                      double r_out, double width, double density) {
  Body b;
  b.name = name;
  b.kind = kind;
  b.ring = &spec;
  b.mass = spec.mass > 0 ? spec.mass : annulus_mass(density, r_in, r_out, width);
  b.axial_inertia = spec.inertia > 0 ? spec.inertia : annulus_axial_inertia(b.mass, r_in, r_out);
  b.transverse_inertia =
      spec.transverse_inertia > 0 ? spec.transverse_inertia : annulus_transverse_inertia(b.mass, r_in, r_out, width);
  const bool moves = spec.motion != scene::RingMotion::fixed;
  const bool radial = moves && spec.translation_free, axial = moves && spec.axial_free;
  const bool tilt = moves && spec.tilt == scene::RingTilt::free;
  const bool spin = spec.motion == scene::RingMotion::free;
  b.offset = m.state_size;
  auto add = [&](Coordinate c, VariableClass cls, const char* what) { add_state(m, b, c, cls, what); };
  if (radial) add(sx, VariableClass::position, "x"), add(sy, VariableClass::position, "y");
  if (axial) add(sz, VariableClass::position, "z");
  if (tilt) add(sax, VariableClass::angle, "tilt_x"), add(say, VariableClass::angle, "tilt_y");
  if (radial) add(svx, VariableClass::velocity, "vx"), add(svy, VariableClass::velocity, "vy");
  if (axial) add(svz, VariableClass::velocity, "vz");
  if (tilt) add(swx, VariableClass::angular_velocity, "tilt_rate_x"), add(swy, VariableClass::angular_velocity, "tilt_rate_y");
  if (spin) add(swz, VariableClass::angular_velocity, "spin");
  b.size = m.state_size - b.offset;
  m.bodies.push_back(b);
}

namespace {

/// The cage annulus: bore and outside radius, axial width.
struct CageGeometry {
  double r_in, r_out, width;
};

/// Cage: an annulus with one radial hole per pocket; full pose and body-frame angular velocity.
void add_cage(Model& m, const scene::Scene& scene, const CageGeometry& geo) {
  const auto& cs = scene.cage;
  const auto& cage_mat = scene.material(cs.material);
  const double D = scene.bearing.ball.ball_diameter;
  Body c;
  c.name = "cage";
  c.kind = BodyKind::cage;
  const double pocket_r = 0.5 * (D + cs.pocket_clearance);
  const double holes = cage_mat.density * m.element_count * pi * pocket_r * pocket_r * (geo.r_out - geo.r_in);
  const double computed = annulus_mass(cage_mat.density, geo.r_in, geo.r_out, geo.width) - holes;
  c.mass = cs.mass > 0 ? cs.mass : computed;
  if (c.mass <= 0)
    throw std::runtime_error("cage: the pockets leave no material (check cage.inner_diameter, outer_diameter, width)");
  c.axial_inertia = cs.inertia > 0 ? cs.inertia : annulus_axial_inertia(c.mass, geo.r_in, geo.r_out);
  c.transverse_inertia = cs.transverse_inertia > 0 ? cs.transverse_inertia
                                                   : annulus_transverse_inertia(c.mass, geo.r_in, geo.r_out, geo.width);
  c.offset = m.state_size;
  add_states(m, c, sx, VariableClass::position, {"x", "y", "z"});
  add_states(m, c, sax, VariableClass::angle, {"angle_x", "angle_y", "angle_z"});
  add_states(m, c, svx, VariableClass::velocity, {"vx", "vy", "vz"});
  add_states(m, c, swx, VariableClass::angular_velocity, {"wx_body", "wy_body", "wz_body"});
  c.size = m.state_size - c.offset;
  m.bodies.push_back(c);
}

/// A ball's velocity states: the bearing frame's, or its orbital frame's (orbital_frame.hpp).
std::array<const char*, 3> velocity_names(const Model& m) {
  if (m.orbital_velocities) return {"v_r", "v_theta", "vz"};
  return {"vx", "vy", "vz"};
}

/// Balls: position, velocity, angular velocity (bearing frame): 9 states, no orientation; with a ball's
/// own defect in the scene, every ball's orientation too (12 states).
void add_balls(Model& m, const scene::Scene& scene) {
  const double rb = m.element_radius;
  const double ball_mass = scene.material(scene.bearing.roller_material).density * 4.0 / 3.0 * pi * rb * rb * rb;
  const double inertia = 0.4 * ball_mass * rb * rb;
  m.orbital_velocities = scene.solver.element_velocity_frame == scene::ElementVelocityFrame::orbital;
  if (!scene.rolling_element.any()) {
    add_rolling_elements(m, "ball", ball_mass, inertia, inertia, [](Model& model, Body& b) {
      add_states(model, b, sx, VariableClass::position, {"x", "y", "z"});
      add_states(model, b, svx, VariableClass::velocity, velocity_names(model));
      add_states(model, b, swx, VariableClass::angular_velocity, {"wx", "wy", "wz"});
    });
  } else {
    // A ball's own defect turns with it: every ball's orientation is a state (equal blocks), its
    // Cardan angles after its position, starting at 0 (the ball's frame is the bearing's).
    add_rolling_elements(m, "ball", ball_mass, inertia, inertia, [](Model& model, Body& b) {
      add_states(model, b, sx, VariableClass::position, {"x", "y", "z"});
      add_states(model, b, sax, VariableClass::angle, {"angle_x", "angle_y", "angle_z"});
      add_states(model, b, svx, VariableClass::velocity, velocity_names(model));
      add_states(model, b, swx, VariableClass::angular_velocity, {"wx", "wy", "wz"});
      b.ball_orientation = true;
    });
  }
  // A scattered ball's mass and inertia follow its own diameter (a solid sphere).
  for (Body& b : m.bodies) {
    if (b.kind != BodyKind::rolling_element || m.element_radii.empty()) continue;
    const double r = m.radius_of_element(b.index), scale = r / rb;
    b.mass = ball_mass * scale * scale * scale;
    b.axial_inertia = b.transverse_inertia = 0.4 * b.mass * r * r;
  }
}

double e_star(const scene::Material& a, const scene::Material& b) {
  return contact::reduced_modulus(a.youngs_modulus, a.poisson_ratio, b.youngs_modulus, b.poisson_ratio);
}
double damping_of(const scene::ContactSpec& spec) { return spec.damping.id == contact::LawId::no_damping ? 0.0 : spec.damping.factor; }
/// Validity: an approach of 2 % of the ball radius is far beyond any elastic deflection.
double max_approach(const Model& m) { return 0.02 * m.element_radius; }

/// A groove arc's cross-section circle: centre (radius, axial position) in the ring frame, radius.
struct Arc {
  bool outer;
  double centre_radius, centre_axial, groove_radius;
  const char* label;
};

/// Groove arcs. u: unit vector from the ball centre to the design contact point in the (radial,
/// axial) plane; the arc centre lies at (R_b - r_groove) u from a centred ball, and the clearance
/// moves the outer arcs out and the inner arcs in by P_d / 4 each (radial play P_d / 2). An angular
/// contact bearing's design contact points lie on one line through the ball centre at its free
/// contact angle (outer at +z, inner at -z), touching without load: its free contact angle is its
/// play, so no clearance shift.
std::vector<Arc> groove_arcs(const Model& m, const scene::Scene& scene) {
  const auto& g = scene.bearing;
  const bool four_point = g.type == scene::BearingType::four_point_contact_ball;
  const bool angular = g.type == scene::BearingType::angular_contact_ball;
  const double D = g.ball.ball_diameter, rb = m.element_radius, rp = m.pitch_radius, a0 = m.nominal_contact_angle;
  std::vector<Arc> arcs;
  for (int ring = 0; ring < 2; ++ring) {
    const bool outer = ring == 1;
    const double rg = (outer ? g.ball.outer_conformity : g.ball.inner_conformity) * D;
    const double shift = angular ? 0.0 : (outer ? 1.0 : -1.0) * 0.25 * g.radial_clearance;
    for (int side = 0; side < m.arcs_per_ring; ++side) {
      const double sign_axial = four_point ? (side == 0 ? 1.0 : -1.0) : angular ? (outer ? 1.0 : -1.0) : 0.0;
      const double u_r = (outer ? 1.0 : -1.0) * std::cos(a0), u_z = sign_axial * std::sin(a0);
      const char* label = four_point ? (side == 0 ? "a" : "b") : "";
      arcs.push_back({outer, rp + (rb - rg) * u_r + shift, (rb - rg) * u_z, rg, label});
    }
  }
  return arcs;
}

contact::PointTraction race_traction(const scene::Scene& scene) {
  contact::PointTraction t;
  const auto& rt = scene.ball_race.traction;
  t.model = rt.id == contact::LawId::no_traction      ? contact::TractionModel::none
            : rt.id == contact::LawId::limiting_shear ? contact::TractionModel::limiting_shear
                                                      : contact::TractionModel::curve;
  t.friction_coefficient = rt.friction_coefficient;
  t.slip_velocity_scale = rt.slip_velocity_scale > 0 ? rt.slip_velocity_scale : 1.0;
  t.grid_x = rt.grid_x;
  t.grid_y = rt.grid_y;
  return t;
}

contact::PointLubricant lubricant(const scene::Scene& scene) {
  contact::PointLubricant lube;
  lube.viscosity = scene.lubricant.viscosity;
  lube.pressure_viscosity = scene.lubricant.pressure_viscosity;
  lube.limiting_shear_coefficient = scene.lubricant.limiting_shear_coefficient;
  lube.viscosity_exponent_cap = scene.lubricant.viscosity_exponent_cap;
  lube.inlet_meniscus = scene.lubricant.inlet_meniscus;
  if (scene.lubricant.roelands && lube.viscosity > 0 && lube.pressure_viscosity > 0)
    lube.roelands_index = contact::roelands_index(lube.viscosity, lube.pressure_viscosity);
  return lube;
}

/// The ball-groove law of one arc: Hertz constants over cos(contact angle) in [0.2, 1]: ball 1/R_b
/// both ways; groove -1/r_g across; race +-cos(a)/rho along the rolling direction, rho = r_p -+ R_b cos(a).
contact::BallGrooveSegment groove_law(const Model& m, const scene::Scene& scene, const Arc& arc, double rb) {
  const double rp = m.pitch_radius;
  const double e_race = e_star(scene.material(scene.bearing.roller_material), scene.material(scene.bearing.ring_material));
  contact::BallGrooveSegment s;
  s.centre_radius = arc.centre_radius;
  s.centre_axial = arc.centre_axial;
  s.groove_radius = arc.groove_radius;
  s.ball_radius = rb;
  s.outer = arc.outer;
  const double rg = arc.groove_radius;
  const bool outer = arc.outer;
  s.normal.hertz = contact::HertzTable(
      [&](double c, double& kx, double& ky) {
        const double rho = outer ? rp + rb * c : rp - rb * c;
        kx = 1.0 / rb + (outer ? -c : c) / rho;
        ky = 1.0 / rb - 1.0 / rg;
      },
      0.2, 1.0, 33, e_race);
  s.normal.reduced_modulus = e_race;
  s.normal.damping_factor = damping_of(scene.ball_race);
  s.normal.max_approach = max_approach(m);
  s.traction = race_traction(scene);
  s.lubricant = lubricant(scene);
  s.rolling_resistance = scene.ball_race.traction.rolling_resistance && s.lubricant.viscosity > 0;
  if (scene.bearing.type == scene::BearingType::angular_contact_ball) s.groove_side = arc.outer ? 1 : -1;
  const auto& g = scene.bearing;
  s.imperfections = race_imperfections(outer ? scene.outer_ring : scene.inner_ring,
                                       0.5 * (outer ? g.outer_race_diameter() : g.inner_race_diameter()), rb);
  return s;
}

/// The ball-pocket law (the same for every pocket but its angle).
contact::BallPocketSegment pocket_law(const Model& m, const scene::Scene& scene) {
  const auto& cs = scene.cage;
  const double rb = m.element_radius;
  const double e_pocket = e_star(scene.material(scene.bearing.roller_material), scene.material(cs.material));
  const double pocket_r = rb + 0.5 * cs.pocket_clearance;
  const bool spherical = cs.pocket_shape == scene::PocketShape::spherical;
  const double conformal = 1.0 / rb - 1.0 / pocket_r;
  contact::BallPocketSegment p;
  p.normal.hertz = contact::HertzTable(contact::hertz_point_contact(spherical ? conformal : 1.0 / rb, conformal, e_pocket));
  p.normal.reduced_modulus = e_pocket;
  p.normal.damping_factor = damping_of(scene.ball_cage);
  p.normal.max_approach = max_approach(m);
  const auto& friction = scene.ball_cage.traction;
  if (friction.id != contact::LawId::no_traction) {
    p.friction.friction_coefficient = friction.friction_coefficient;
    p.friction.slip_velocity_scale = friction.slip_velocity_scale > 0 ? friction.slip_velocity_scale : 0.01;
  }
  p.pitch_radius = m.pitch_radius;
  p.clearance = cs.pocket_clearance;
  p.ball_radius = rb;
  p.shape = spherical ? contact::PocketShape::spherical : contact::PocketShape::cylindrical;
  if (scene.ball_cage.normal.id == contact::LawId::pocket_film) {
    // The pocket's film (contact/laws/pocket_film.hpp; cylindrical pockets, the scene's rule), collapsing to
    // the dry law at 0.2 um, the combined roughness of ground surfaces (as the cage land's).
    contact::PocketFilm film;
    film.viscosity = scene.lubricant.viscosity;
    film.ball_radius = rb;
    film.clearance = 0.5 * cs.pocket_clearance;
    film.film_floor = 0.2e-6;
    p.film = film;
  }
  return p;
}

/// The ball-groove laws of each arc: one for every ball alike, or with a diameter scatter one per ball
/// and arc (the arcs are the rings' and stay where the nominal ball puts them; a larger ball's
/// surface reaches further into them). law_of[k][a]: ball k's law on arc a.
std::vector<std::vector<int>> add_groove_laws(Model& m, const scene::Scene& scene, const std::vector<Arc>& arcs) {
  std::vector<std::vector<int>> law_of(static_cast<std::size_t>(m.element_count));
  const bool alike = m.element_radii.empty() && !scene.rolling_element.any();
  for (int k = 0; k < m.element_count; ++k) {
    if (k > 0 && alike) {
      law_of[std::size_t(k)] = law_of[0];
      continue;
    }
    for (const Arc& arc : arcs) {
      m.laws.push_back(groove_law(m, scene, arc, m.radius_of_element(k)));
      std::get<contact::BallGrooveSegment>(m.laws.back()).element_imperfections =
          element_imperfections(scene, k, m.radius_of_element(k));
      law_of[std::size_t(k)].push_back(static_cast<int>(m.laws.size()) - 1);
    }
  }
  return law_of;
}

/// Pocket k of a scattered cage or holding a scattered ball: the pocket's diameter is the nominal
/// ball's plus its own clearance; the clearance the law sees is that less its ball's diameter.
void scatter_pocket(contact::BallPocketSegment& p, const Model& m, const scene::Scene& scene, int k,
                    double clearance_deviation) {
  const double rb = m.radius_of_element(k);
  const double pocket_r = m.element_radius + 0.5 * (scene.cage.pocket_clearance + clearance_deviation);
  p.ball_radius = rb;
  p.clearance = 2.0 * (pocket_r - rb);
  const bool spherical = p.shape == contact::PocketShape::spherical;
  const double conformal = 1.0 / rb - 1.0 / pocket_r;
  p.normal.hertz = contact::HertzTable(
      contact::hertz_point_contact(spherical ? conformal : 1.0 / rb, conformal, p.normal.reduced_modulus));
  if (p.film) {
    p.film->ball_radius = rb;
    p.film->clearance = 0.5 * p.clearance;
  }
}

void add_ball_segments(Model& m, const scene::Scene& scene) {
  const std::vector<Arc> arcs = groove_arcs(m, scene);
  const std::vector<std::vector<int>> law_of = add_groove_laws(m, scene, arcs);
  const contact::BallPocketSegment pocket = pocket_law(m, scene);
  const auto& pocket_deviations = scene.cage.pocket_clearance_deviations;
  for (int k = 0; k < m.element_count; ++k) {
    const int body = m.first_element + k;
    const std::vector<int>& arc_law = law_of[std::size_t(k)];
    for (std::size_t a = 0; a < arcs.size(); ++a) {
      const bool outer = arcs[a].outer;
      m.segments.push_back({outer ? SegmentKind::ball_outer_groove : SegmentKind::ball_inner_groove,
                            outer ? m.outer_ring : m.inner_ring, body, arc_law[a], k,
                            fmt::format("ball[{}]/{}_groove{}", k, outer ? "outer" : "inner", arcs[a].label)});
    }
    contact::BallPocketSegment p = pocket;
    p.pocket_angle = 2.0 * pi * k / m.element_count;
    if (!m.element_radii.empty() || !pocket_deviations.empty())
      scatter_pocket(p, m, scene, k, pocket_deviations.empty() ? 0.0 : pocket_deviations[std::size_t(k)]);
    m.laws.push_back(std::move(p));
    m.segments.push_back({SegmentKind::ball_pocket, m.cage, body, static_cast<int>(m.laws.size()) - 1, k,
                          fmt::format("ball[{}]/pocket", k)});
  }
}

void add_land_segment(Model& m, const scene::Scene& scene, const CageGeometry& geo) {
  const auto& cs = scene.cage;
  if (cs.guidance == scene::CageGuidance::rolling_element) return;
  const bool outer = cs.guidance == scene::CageGuidance::outer_land;
  contact::CageLandSegment3 l;
  l.outer_land = outer;
  l.clearance = cs.land_clearance;
  l.land_radius = outer ? geo.r_out + cs.land_clearance : geo.r_in - cs.land_clearance;
  l.width = cs.land_width > 0 ? cs.land_width : 0.3 * geo.width;
  l.stations = 2;
  const double e_land = e_star(scene.material(cs.material), scene.material(scene.bearing.ring_material));
  l.law = contact::make_line_contact_law(e_land, l.width / l.stations, 1, 0.0, damping_of(scene.cage_land),
                                         0.02 * m.element_radius);
  if (scene.cage_land.traction.id != contact::LawId::no_traction) {
    l.friction.friction_coefficient = scene.cage_land.traction.friction_coefficient;
    l.friction.slip_velocity_scale =
        scene.cage_land.traction.slip_velocity_scale > 0 ? scene.cage_land.traction.slip_velocity_scale : 0.01;
  }
  if (scene.cage_land.normal.id == contact::LawId::short_bearing) {
    // The land's short-bearing film (contact/laws/short_bearing_film.hpp): radius and clearance of the
    // land, its whole width (each station takes its strip), collapsing to the dry law at 0.2 um, the
    // combined roughness of ground surfaces (as the roller/cage film).
    contact::ShortBearingFilm film;
    film.viscosity = scene.lubricant.viscosity;
    film.radius = l.land_radius;
    film.width = l.width;
    film.clearance = l.clearance;
    film.film_floor = 0.2e-6;
    l.film = film;
  }
  m.laws.push_back(l);
  m.segments.push_back({SegmentKind::cage_land, m.cage, outer ? m.outer_ring : m.inner_ring,
                        static_cast<int>(m.laws.size()) - 1, -1, outer ? "cage/outer_ring_land" : "cage/inner_ring_land"});
}

// Drag and churning in the oil-air mixture (contact/segments/drag_segments.hpp), where the scene gives
// an oil volume fraction: a drag element per ball and the cage's churning, each against the outer ring
// (the mixture moves with it). None otherwise: the model is then the same as without the key.
void add_mixture_drag(Model& m, const scene::Scene& scene, const CageGeometry& geo) {
  const scene::Lubricant& oil = scene.lubricant;
  if (!(oil.oil_volume_fraction > 0)) return;
  const contact::OilAirMixture mixture = contact::oil_air_mixture(oil.density, oil.viscosity, oil.oil_volume_fraction);
  m.laws.push_back(contact::BallDragSegment{mixture, scene.bearing.ball.ball_diameter});
  const int ball_law = static_cast<int>(m.laws.size()) - 1;
  for (int k = 0; k < m.element_count; ++k)
    m.segments.push_back({SegmentKind::ball_drag, m.outer_ring, m.first_element + k, ball_law, k,
                          fmt::format("ball[{}]/drag", k)});
  m.laws.push_back(contact::CageChurningSegment{mixture, geo.r_in, geo.r_out});
  m.segments.push_back({SegmentKind::cage_churning, m.outer_ring, m.cage, static_cast<int>(m.laws.size()) - 1, -1,
                        "cage/churning"});
}

void check_scene(const scene::Scene& scene) {
  if (scene.scene.model != scene::ModelKind::spatial || !scene.bearing.is_ball_bearing())
    throw std::runtime_error("scene.model: the spatial model needs a ball bearing (bearing.type)");
}

void set_geometry(Model& m, const scene::Scene& scene) {
  const auto& g = scene.bearing;
  const bool four_point = g.type == scene::BearingType::four_point_contact_ball;
  m.kind = scene::ModelKind::spatial;
  m.element_group = "balls";
  m.element_count = g.rolling_elements;
  m.pitch_radius = 0.5 * g.pitch_diameter;
  m.element_radius = 0.5 * g.ball.ball_diameter;
  m.element_radii.clear();
  for (const double deviation : g.ball_diameter_deviations) m.element_radii.push_back(0.5 * (g.ball.ball_diameter + deviation));
  m.nominal_contact_angle = four_point                                    ? g.ball.arc_contact_angle
                            : g.type == scene::BearingType::angular_contact_ball ? g.ball.free_contact_angle
                                                                              : 0.0;
  m.arcs_per_ring = four_point ? 2 : 1;
}

double ring_width(const scene::Scene& scene) {
  const auto& g = scene.bearing;
  return g.ring_width > 0 ? g.ring_width : 1.5 * g.ball.ball_diameter;
}

/// Rings: the groove side of each ring is taken as a quarter ball diameter deep on average.
void add_rings(Model& m, const scene::Scene& scene) {
  const auto& g = scene.bearing;
  const double D = g.ball.ball_diameter, width = ring_width(scene);
  const double density = scene.material(g.ring_material).density;
  add_spatial_ring(m, BodyKind::inner_ring, "inner_ring", m.params().inner_ring, 0.5 * g.inner_bore_diameter,
           0.5 * g.inner_race_diameter() + 0.25 * D, width, density);
  add_spatial_ring(m, BodyKind::outer_ring, "outer_ring", m.params().outer_ring, 0.5 * g.outer_race_diameter() - 0.25 * D,
           0.5 * g.outer_outside_diameter, width, density);
  add_housing(m, scene);
}

CageGeometry cage_geometry(const Model& m, const scene::Scene& scene) {
  const auto& cs = scene.cage;
  const double rp = m.pitch_radius, rb = m.element_radius;
  return {cs.inner_diameter > 0 ? 0.5 * cs.inner_diameter : rp - 0.6 * rb,
          cs.outer_diameter > 0 ? 0.5 * cs.outer_diameter : rp + 0.6 * rb,
          cs.width > 0 ? cs.width : 0.8 * ring_width(scene)};
}

void add_segments(Model& m, const scene::Scene& scene) {
  add_ball_segments(m, scene);
  add_land_segment(m, scene, cage_geometry(m, scene));
  add_mixture_drag(m, scene, cage_geometry(m, scene));
  attach_outer_ring_to_housing(m);
}

}  // namespace

std::string describe_ball_model(const Model& m);

namespace {
/// Lines for the balls' diameter and the pockets' clearance scatter, each value in micrometres.
std::string describe_scatter(const Model& m, const ModelParameters& sc) {
  std::string out;
  const auto list = [](const std::vector<double>& deviations) {
    std::string values;
    for (const double d : deviations) values += fmt::format("{}{:+.4g}", values.empty() ? "" : " ", 1e6 * d);
    return values;
  };
  const auto how = [&](double scatter) {
    return scatter > 0 ? fmt::format("drawn, standard deviation {:.4g} um, scatter_seed {}", 1e6 * scatter,
                                     sc.bearing.scatter_seed)
                       : std::string("given");
  };
  if (!m.element_radii.empty())
    out += fmt::format("  ball diameters ({}): D + [{}] um\n", how(sc.bearing.ball_diameter_scatter),
                       list(sc.bearing.ball_diameter_deviations));
  if (!sc.cage.pocket_clearance_deviations.empty())
    out += fmt::format("  pocket clearances ({}): {:.4g} um + [{}] um\n", how(sc.cage.pocket_clearance_scatter),
                       1e6 * sc.cage.pocket_clearance, list(sc.cage.pocket_clearance_deviations));
  return out;
}
}  // namespace

const ModelBuilder& ball_model_builder() {
  static const ModelBuilder builder{
      check_scene, set_geometry, add_rings,
      [](Model& m, const scene::Scene& scene) { add_cage(m, scene, cage_geometry(m, scene)); }, add_balls, add_segments,
      describe_ball_model};
  return builder;
}

std::string describe_ball_model(const Model& m) {
  std::string out;
  const auto& sc = m.params();
  out += fmt::format("scene '{}' ({}): spatial model, {} bodies, {} states, {} contact segments\n", sc.scene_name,
                     sc.source, m.bodies.size(), m.state_size, m.segments.size());
  out += fmt::format("  {} {} balls, D = {:.4g} mm, pitch diameter {:.5g} mm, nominal contact angle {:.3g} deg\n",
                     m.element_count,
                     m.arcs_per_ring == 2                                           ? "four-point contact"
                     : sc.bearing.type == scene::BearingType::angular_contact_ball ? "angular contact"
                                                                                    : "deep groove",
                     2e3 * m.element_radius,
                     2e3 * m.pitch_radius, m.nominal_contact_angle * 180 / std::numbers::pi);
  out += describe_scatter(m, sc);
  out += "bodies (states integrated; prescribed motions are functions of time, not states):\n";
  for (const auto& b : m.bodies) {
    if (b.kind == BodyKind::rolling_element && b.index > 0) continue;
    std::string why;
    switch (b.kind) {
      case BodyKind::inner_ring:
      case BodyKind::outer_ring: {
        const auto& r = *b.ring;
        const char* motion = r.motion == scene::RingMotion::fixed ? "fixed" : r.motion == scene::RingMotion::driven ? "driven" : "free";
        const char* tilt = r.tilt == scene::RingTilt::free ? "tilt free" : r.tilt == scene::RingTilt::prescribed ? "misalignment prescribed" : "tilt held";
        why = fmt::format("{}, {}; its angle about its own axis is not a state (grooves are surfaces of revolution)", motion, tilt);
        break;
      }
      case BodyKind::cage: why = "full pose and body-frame angular velocity: its pockets are not symmetric"; break;
      case BodyKind::rolling_element:
        why = b.ball_orientation
                  ? fmt::format("each of the {} balls: position, orientation (a ball's defect turns with it), velocity, "
                                "angular velocity", m.element_count)
                  : fmt::format("each of the {} balls: position, velocity, angular velocity; no orientation (a sphere)",
                                m.element_count);
        break;
    }
    out += fmt::format("  {:<12} mass {:.4g} kg, inertia {:.4g} / {:.4g} kg m^2 (axial / transverse), {} states: {}\n",
                       b.name, b.mass, b.axial_inertia, b.transverse_inertia, b.size, why);
  }
  for (const auto& node : m.nodes) out += node->describe(m);
  int count[segment_kind_count] = {};
  for (const auto& s : m.segments) ++count[static_cast<int>(s.kind)];
  out += "contact segments:\n";
  for (int k = 0; k < segment_kind_count; ++k)
    if (count[k] > 0) out += fmt::format("  {:<18} {}\n", segment_kind_name(static_cast<SegmentKind>(k)), count[k]);
  const Segment* groove = m.first_segment(SegmentKind::ball_inner_groove);
  const Segment* land = m.first_segment(SegmentKind::cage_land);
  out += fmt::format("  ball-groove: Hertz (exact ellipticity, tabulated over the contact angle), damping {}, traction {} "
                     "({}x{} grid), rolling resistance {}\n",
                     sc.ball_race.damping.name(), sc.ball_race.traction.name(), sc.ball_race.traction.grid_x,
                     sc.ball_race.traction.grid_y, groove && m.law<contact::BallGrooveSegment>(*groove).rolling_resistance ? "on" : "off");
  out += describe_race_imperfections(m);
  out += fmt::format("  ball-pocket: Hertz in a {} pocket, clearance {:.4g} mm, friction {}{}\n",
                     sc.cage.pocket_shape == scene::PocketShape::spherical ? "spherical" : "cylindrical",
                     1e3 * sc.cage.pocket_clearance, sc.ball_cage.traction.name(),
                     sc.ball_cage.normal.id == contact::LawId::pocket_film
                         ? ", Reynolds film (narrow strips, Reynolds cavitation) and Couette shear"
                         : "");
  if (!land)
    out += "  cage-land: none (the cage is guided by the balls" + std::string(sc.cage.support.any() ? " and its spindle support)\n" : ")\n");
  else
    out += fmt::format("  cage-land: {} land, clearance {:.4g} mm, 2 stations (tilt moments){}\n",
                       m.law<contact::CageLandSegment3>(*land).outer_land ? "outer-ring" : "inner-ring",
                       1e3 * m.law<contact::CageLandSegment3>(*land).clearance,
                       m.law<contact::CageLandSegment3>(*land).film ? ", short-bearing film (Ocvirk, half-Sommerfeld)" : "");
  if (const Segment* drag = m.first_segment(SegmentKind::ball_drag))
    out += fmt::format("  drag: oil-air mixture {:.4g} kg/m^3, {:.4g} Pa s; sphere drag (Schiller-Naumann) on each "
                       "ball, von Karman's disc moment on the cage's faces\n",
                       m.law<contact::BallDragSegment>(*drag).mixture.density,
                       m.law<contact::BallDragSegment>(*drag).mixture.viscosity);
  out += fmt::format("state layout: border {} states (rings, cage), then {} blocks of {} (balls)\n", m.border_size,
                     m.element_count, m.block_size);
  return out;
}

}  // namespace raceway::bearing
