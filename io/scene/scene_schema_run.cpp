// The scene schema table, second half: [carrier] to [output] (scene_schema.cpp holds the first).
#include <cmath>

#include <fmt/format.h>

#include "io/scene/scene_rules.hpp"
#include "io/scene/scene_schema_rows.hpp"

namespace raceway::scene::schema::table {

namespace {

using contact::LawRole;
using enum ValueKind;
using namespace rules;

/// A stride no longer than the run's output intervals: a longer one would store t = 0 alone.
void segment_every_within_run(const Row&, const Section& s, Bind& b) {
  const long every = b.scene.output.segment_every;
  const double intervals = std::floor(b.scene.scene.end_time / b.scene.scene.output_interval + 1e-9);
  s.check(static_cast<double>(every) <= intervals, "segment_every", [&] {
    return fmt::format("segment_every = {} is more than the run's {:.0f} output intervals (end_time / "
                       "output_interval): only t = 0 would be stored", every, intervals);
  });
}

/// The cage's share of the pocket tolerance exists only where the pocket factor tightens something.
std::optional<std::string> pocket_factor_given(const Section&, const Bind& b) {
  if (b.scene.solver.pocket_tolerance_factor > 1) return std::nullopt;
  return "only with pocket_tolerance_factor > 1: it tightens the cage's rotation rate by that factor";
}

/// The radial velocity tolerance exists only where the rolling elements' velocities are orbital.
std::optional<std::string> orbital_velocity_frame(const Section&, const Bind& b) {
  if (b.scene.solver.element_velocity_frame == ElementVelocityFrame::orbital) return std::nullopt;
  return "only with element_velocity_frame = \"orbital\": in the bearing frame vx and vy each carry part of the "
         "radial and of the orbital velocity";
}

constexpr Row kRows[] = {
    // ---- [carrier]: optional; the bearing on a rotating planet carrier (seed 003 eq. 1-6) ------
    {.section = "carrier", .key = "radius", .kind = number, .field = FIELD(scene.carrier.radius), .dim = dim::length,
     .bounds = positive, .bearings = planar_rollers, .elsewhere = kPlanarCarrier, .then = carrier_without_gravity,
     .example = "100 mm",
     .meaning = "R_c: distance from the sun (carrier) axis to the bearing axis, which lies on the carrier's +x"},
    {.section = "carrier", .key = "speed", .kind = time_function, .field = FIELD(scene.carrier.speed),
     .dim = dim::angular_speed, .bearings = planar_rollers, .elsewhere = kPlanarCarrier, .example = "3000 rpm",
     .meaning = "the carrier's speed about z; ring speeds and loads are in the bearing frame, which turns with it"},

    // ---- [housing]: optional; the fixed outer ring in a housing on a pedestal (spatial scenes) ---
    {.section = "housing", .key = "mass", .kind = number, .field = FIELD(scene.housing.mass), .dim = dim::mass,
     .bounds = positive, .bearings = spatial_bearings, .elsewhere = kSpatialOnlyHousing, .when = housing_holds_fixed_outer_ring,
     .meaning = "the housing's mass (the outer ring's is added: they move together in x and y)"},
    {.section = "housing", .key = "stiffness", .kind = number, .field = FIELD(scene.housing.stiffness),
     .dim = dim::stiffness, .bounds = positive, .bearings = spatial_bearings, .elsewhere = kSpatialOnlyHousing,
     .when = housing_holds_fixed_outer_ring, .meaning = "radial, in x and y, to ground"},
    {.section = "housing", .key = "damping", .kind = number, .field = FIELD(scene.housing.damping),
     .dim = dim::damping, .bounds = non_negative, .def = value(0), .bearings = spatial_bearings, .elsewhere = kSpatialOnlyHousing,
     .when = housing_holds_fixed_outer_ring, .meaning = "radial, in x and y, to ground"},
    {.section = "housing", .key = "sensor_interval", .kind = number, .field = FIELD(scene.housing.sensor_interval),
     .dim = dim::time, .bounds = positive, .bearings = spatial_bearings, .elsewhere = kSpatialOnlyHousing,
     .when = housing_holds_fixed_outer_ring, .then = sensor_interval_within_output, .example = "20 us",
     .meaning = "time between the sensor's samples (displacement, velocity, acceleration of the housing)"},
    {.section = "housing", .key = "modes", .kind = table, .field = nullptr, .def = absent, .bearings = spatial_bearings,
     .elsewhere = kSpatialOnlyHousing, .when = housing_holds_fixed_outer_ring, .then = housing_mode_lists_match,
     .sub = "housing.modes",
     .meaning = "further modes of the housing at the bearing seat: the seat moves by the sum of the modes' "
                "displacements (docs/vibration.md)"},
    {.section = "housing", .key = "sensor_participation", .kind = number_list,
     .field = FIELD(scene.housing.sensor_participation), .dim = dim::none, .bounds = {.lo = -100, .hi = 100},
     .def = absent, .bearings = spatial_bearings, .elsewhere = kSpatialOnlyHousing, .when = housing_holds_fixed_outer_ring,
     .then = sensor_participation_per_mode, .example = "[1.0, -0.4]",
     .meaning = "the sensor's displacement per unit displacement of each mode (the first mode's first, then "
                "[housing.modes]' in order); absent: all 1, the sensor at the seat"},
    {.section = "housing.modes", .key = "masses", .kind = number_list, .field = FIELD(scene.housing.mode_masses),
     .dim = dim::mass, .bounds = positive, .example = "[\"0.8 kg\"]", .meaning = "modal mass of each further mode"},
    {.section = "housing.modes", .key = "stiffnesses", .kind = number_list,
     .field = FIELD(scene.housing.mode_stiffnesses), .dim = dim::stiffness, .bounds = positive,
     .example = "[\"2000 MN/m\"]", .meaning = "modal stiffness of each further mode"},
    {.section = "housing.modes", .key = "dampings", .kind = number_list, .field = FIELD(scene.housing.mode_dampings),
     .dim = dim::damping, .bounds = non_negative, .def = absent, .example = "[\"400 N s/m\"]",
     .meaning = "modal damping of each further mode; absent: all 0"},

    // ---- [thermal]: optional; the thermal network (solver/bearing/thermal_network.hpp) --------
    {.section = "thermal", .key = "ambient_temperature", .kind = number, .field = FIELD(scene.thermal.ambient_temperature),
     .dim = dim::temperature, .bounds = positive, .def = value(293.15), .example = "20 degC",
     .meaning = "the air around the housing and the shaft beyond the inner ring's fit"},
    {.section = "thermal", .key = "initial_temperature", .kind = number, .field = FIELD(scene.thermal.initial_temperature),
     .dim = dim::temperature, .bounds = positive, .def = absent, .example = "20 degC",
     .meaning = "every part's temperature at the start (default: the lubricant's temperature where given, else the "
                "ambient temperature)"},
    {.section = "thermal", .key = "specific_heat", .kind = number, .field = FIELD(scene.thermal.specific_heat),
     .dim = dim::specific_heat, .bounds = positive, .def = value(460), .example = "460 J/kg K",
     .meaning = "of the rings and rolling elements (their heat capacity: mass x specific heat)"},
    {.section = "thermal", .key = "cage_specific_heat", .kind = number, .field = FIELD(scene.thermal.cage_specific_heat),
     .dim = dim::specific_heat, .bounds = positive, .def = value(460), .example = "380 J/kg K",
     .meaning = "of the cage"},
    {.section = "thermal", .key = "oil_heat_capacity", .kind = number, .field = FIELD(scene.thermal.oil_heat_capacity),
     .dim = dim::heat_capacity, .bounds = positive, .def = absent, .example = "5 J/K",
     .meaning = "the oil in the bearing (default: its free volume between the rings full of oil, 870 kg/m^3 "
                "or the lubricant's density, 1900 J/kg K)"},
    {.section = "thermal", .key = "housing_heat_capacity", .kind = number,
     .field = FIELD(scene.thermal.housing_heat_capacity), .dim = dim::heat_capacity, .bounds = positive, .def = absent,
     .example = "2 kJ/K", .meaning = "the housing (default: five times the outer ring's)"},
    {.section = "thermal", .key = "convection_coefficient", .kind = number,
     .field = FIELD(scene.thermal.convection_coefficient), .dim = dim::heat_transfer_coefficient,
     .bounds = non_negative, .def = value(200), .example = "200 W/m^2 K",
     .meaning = "between the oil and the rings' raceways, the rolling elements' and the cage's surfaces"},
    {.section = "thermal", .key = "ambient_convection_coefficient", .kind = number,
     .field = FIELD(scene.thermal.ambient_convection_coefficient), .dim = dim::heat_transfer_coefficient,
     .bounds = non_negative, .def = value(20), .example = "20 W/m^2 K",
     .meaning = "between the housing and the air, on a cylinder of twice the outer ring's outside diameter and "
                "three times its width"},
    {.section = "thermal", .key = "fit_conductance", .kind = number, .field = FIELD(scene.thermal.fit_conductance),
     .dim = dim::heat_transfer_coefficient, .bounds = non_negative, .def = value(5000), .example = "5000 W/m^2 K",
     .meaning = "through the rings' fits: the inner ring's bore to the shaft (at the ambient temperature), the "
                "outer ring's outside to the housing"},
    {.section = "thermal", .key = "element_ring_conductance", .kind = number,
     .field = FIELD(scene.thermal.element_ring_conductance), .dim = dim::thermal_conductance, .bounds = non_negative,
     .def = absent, .example = "0.05 W/K",
     .meaning = "one rolling element to one ring through their contact (default: the constriction of a contact "
                "of radius a tenth of the element's radius in steel, 2 k a with k = 45 W/(m K))"},

    // ---- [lubricant]: optional; without it the contacts are dry --------------------------------
    {.section = "lubricant", .key = "name", .kind = text, .field = FIELD(scene.lubricant.name), .def = word(""),
     .meaning = "label"},
    {.section = "lubricant", .key = "viscosity_40", .kind = number, .field = FIELD(scene.lubricant.viscosity_40),
     .dim = dim::kinematic_viscosity, .bounds = positive, .def = absent, .example = "68 mm^2/s",
     .meaning = "kinematic viscosity at 40 degC, as oil data sheets give it (with viscosity_100, density and "
                "temperature: the viscosity by Walther's equation, ASTM D341)"},
    {.section = "lubricant", .key = "viscosity_100", .kind = number, .field = FIELD(scene.lubricant.viscosity_100),
     .dim = dim::kinematic_viscosity, .bounds = positive, .def = derived(walther_point_default, "required with viscosity_40"),
     .then = walther_points_fit, .example = "8.5 mm^2/s", .meaning = "kinematic viscosity at 100 degC"},
    {.section = "lubricant", .key = "density", .kind = number, .field = FIELD(scene.lubricant.density),
     .dim = dim::density, .bounds = positive, .def = derived(walther_point_default, "required with viscosity_40"),
     .example = "870 kg/m^3", .meaning = "the oil's density (dynamic viscosity = density x kinematic viscosity)"},
    {.section = "lubricant", .key = "temperature", .kind = number, .field = FIELD(scene.lubricant.temperature),
     .dim = dim::temperature, .bounds = positive, .def = derived(walther_point_default, "required with viscosity_40"),
     .example = "70 degC", .meaning = "the oil's temperature, where viscosity_40 and viscosity_100 give the viscosity"},
    {.section = "lubricant", .key = "viscosity", .kind = number, .field = FIELD(scene.lubricant.viscosity),
     .dim = dim::viscosity, .bounds = positive,
     .def = derived(walther_viscosity_default, "from viscosity_40, viscosity_100, density and temperature where given"),
     .then = viscosity_given_once, .meaning = "dynamic viscosity at the bearing temperature"},
    {.section = "lubricant", .key = "pressure_viscosity", .kind = number,
     .field = FIELD(scene.lubricant.pressure_viscosity), .dim = dim::inverse_pressure, .bounds = non_negative,
     .def = value(0), .meaning = "pressure-viscosity coefficient alpha (Barus' exponent; Roelands' initial slope)"},
    {.section = "lubricant", .key = "pressure_viscosity_law", .kind = choice,
     .field = FIELD(scene.lubricant.roelands), .def = word("barus"), .options = kPressureViscosityLaws,
     .noun = "pressure-viscosity law",
     .meaning = "the viscosity's rise with pressure in the limiting-shear traction: barus (exp(alpha p)) or roelands "
                "(below Barus at high pressure, the same initial slope)"},
    {.section = "lubricant", .key = "limiting_shear_coefficient", .kind = number,
     .field = FIELD(scene.lubricant.limiting_shear_coefficient), .dim = dim::none,
     .bounds = {.lo = 0, .hi = 0.5, .note = " (0.02 to 0.1 for mineral oils)"}, .def = value(0),
     .meaning = "limiting shear stress / pressure (limiting_shear traction needs it); 0: none given"},
    {.section = "lubricant", .key = "viscosity_exponent_cap", .kind = number,
     .field = FIELD(scene.lubricant.viscosity_exponent_cap), .dim = dim::none,
     .bounds = {.lo = 0, .hi = 40, .lo_open = true, .note = " (exp(40) times the viscosity is beyond any lubricant)"},
     .def = value(12),
     .meaning = "largest alpha p in the Barus law (contact/laws/point_contact.hpp); 12 gives measured traction-curve "
                "shapes and practical steps"},
    {.section = "lubricant", .key = "inlet_meniscus", .kind = number, .field = FIELD(scene.lubricant.inlet_meniscus),
     .dim = dim::none, .bounds = {.lo = 1, .hi = 1000, .lo_open = true, .note = " (contact semi-widths; about 10 is "
                                                                           "flooded for most ball-race films)"},
     .def = {.kind = Default::Kind::absent, .text = "fully flooded"}, .bearings = ball_bearings, .elsewhere = kBallOnly,
     .example = "3",
     .meaning = "starvation of the ball-groove EHL films: the inlet meniscus's distance from the contact centre in "
                "semi-widths along the rolling direction (Hamrock and Dowson's m; docs/lubrication.md)"},
    {.section = "lubricant", .key = "oil_volume_fraction", .kind = number,
     .field = FIELD(scene.lubricant.oil_volume_fraction), .dim = dim::none,
     .bounds = {.lo = 0, .hi = 1, .note = " (jet and mist lubrication: about 0.01 to 0.1)"}, .def = value(0),
     .bearings = ball_bearings, .elsewhere = kBallOnly, .then = drag_has_oil_density, .example = "0.05",
     .meaning = "oil's share of the oil-air mixture in the bearing's cavity: each ball's drag and the cage's churning "
                "(docs/lubrication.md); 0: no drag"},

    // ---- [life]: optional; what the rating lives take besides the geometry and the run's loads ---
    // (computed by the report, io/report/report_life.py; docs/life.md). Absent keys store nothing:
    // the report uses the defaults named here.
    {.section = "life", .key = "reliability", .kind = number, .field = FIELD(scene.life.reliability), .dim = dim::none,
     .bounds = {.lo = 90, .hi = 99.95, .note = " (percent: ISO 281's a_1 table runs from 90 to 99.95)"},
     .def = {.kind = Default::Kind::absent, .text = "90"}, .example = "99",
     .meaning = "reliability in percent of the modified lives (ISO 281 life modification factor a_1)"},
    {.section = "life", .key = "contamination_factor", .kind = number, .field = FIELD(scene.life.contamination_factor),
     .dim = dim::none,
     .bounds = {.lo = 0, .hi = 1, .lo_open = true,
                .note = " (ISO 281: 1 extreme cleanliness, 0.5 to 0.6 normal, 0.1 to 0.3 typical contamination; "
                        "docs/life.md)"},
     .def = {.kind = Default::Kind::absent, .text = "0.5 (normal cleanliness)"}, .example = "0.5",
     .meaning = "contamination factor e_C of ISO 281 (docs/life.md gives the standard's guidance)"},
    {.section = "life", .key = "dynamic_load_rating", .kind = number, .field = FIELD(scene.life.dynamic_load_rating),
     .dim = dim::force, .bounds = positive,
     .def = {.kind = Default::Kind::absent, .text = "the catalogue's published value, else ISO 281 from the geometry"},
     .example = "14.8 kN", .meaning = "published basic dynamic load rating C (the one the lives use)"},
    {.section = "life", .key = "static_load_rating", .kind = number, .field = FIELD(scene.life.static_load_rating),
     .dim = dim::force, .bounds = positive,
     .def = {.kind = Default::Kind::absent, .text = "the catalogue's published value, else ISO 76 from the geometry"},
     .example = "7.8 kN", .meaning = "published basic static load rating C_0 (axial load factors, fatigue load limit)"},
    {.section = "life", .key = "fatigue_load_limit", .kind = number, .field = FIELD(scene.life.fatigue_load_limit),
     .dim = dim::force, .bounds = positive,
     .def = {.kind = Default::Kind::absent,
             .text = "the catalogue's published value, else estimated from C_0 (ISO 281)"},
     .example = "0.335 kN", .meaning = "published fatigue load limit C_u (a_ISO)"},
    {.section = "life", .key = "lubricant_density", .kind = number, .field = FIELD(scene.life.lubricant_density),
     .dim = dim::density, .bounds = positive,
     .def = {.kind = Default::Kind::absent, .text = "870 kg/m^3 (a mineral oil)"}, .example = "870 kg/m^3",
     .meaning = "lubricant density: the kinematic viscosity nu = [lubricant] viscosity / density of the viscosity "
                "ratio"},

    // ---- [contact]: one table per contact of the bearing ----------------------------------------
    {.section = "contact", .key = "roller_race", .kind = table, .field = FIELD(scene.roller_race), .def = empty_table,
     .bearings = roller_bearings, .contacts = contact::roller_race_contact, .elsewhere = kRollerContact,
     .sub = "contact.*", .meaning = "roller on the races (line contacts)"},
    {.section = "contact", .key = "roller_cage", .kind = table, .field = FIELD(scene.roller_cage), .def = empty_table,
     .bearings = roller_bearings, .contacts = contact::roller_cage_contact, .elsewhere = kRollerContact,
     .sub = "contact.*", .meaning = "roller on a cage bar (line contacts)"},
    {.section = "contact", .key = "ball_race", .kind = table, .field = FIELD(scene.ball_race), .def = empty_table,
     .bearings = ball_bearings, .contacts = contact::ball_race_contact, .elsewhere = kBallContact,
     .sub = "contact.*", .meaning = "ball in a groove (point contacts)"},
    {.section = "contact", .key = "ball_cage", .kind = table, .field = FIELD(scene.ball_cage), .def = empty_table,
     .bearings = ball_bearings, .contacts = contact::ball_cage_contact, .elsewhere = kBallContact,
     .sub = "contact.*", .meaning = "ball in its pocket (point contact)"},
    {.section = "contact", .key = "roller_flange", .kind = table, .field = FIELD(scene.roller_flange),
     .def = empty_table, .bearings = spatial_rollers, .contacts = contact::roller_flange_contact,
     .elsewhere = kFlangeContact, .sub = "contact.*",
     .meaning = "a roller's end on a rib (flange) of its ring (point contact; spatial roller bearings with ribs)"},
    {.section = "contact", .key = "cage_land", .kind = table, .field = FIELD(scene.cage_land), .def = empty_table,
     .contacts = contact::cage_land_contact, .sub = "contact.*",
     .meaning = "cage on the guiding land (line contact, land-guided cages)"},

    // ---- [contact.NAME]: laws from the law registry (contact/laws/law_registry.hpp) -------------
    {.section = "contact.*", .key = "normal", .kind = law, .field = FIELD(contact->normal), .def = registry,
     .then = film_law_has_lubricant, .role = LawRole::normal, .meaning = "normal force law"},
    {.section = "contact.*", .key = "slices", .kind = integer, .field = FIELD(contact->normal.slices),
     .bounds = {.lo = 1, .hi = 200}, .def = derived(slices_default, "1; spatial roller bearings' roller_race 20, roller_cage 4"),
     .contacts = contact::line_contacts, .elsewhere = kLineContact,
     .meaning = "slices along the roller length (planar: for crowning; spatial: the profile, tilt and skew)"},
    {.section = "contact.*", .key = "crown_drop", .kind = number, .field = FIELD(contact->normal.crown_drop),
     .dim = dim::length, .bounds = non_negative, .def = value(0), .contacts = contact::line_contacts,
     .elsewhere = kLineContact, .when = planar_crown_only, .then = crown_drop_fits,
     .meaning = "profile drop at the roller ends (circular crown); 0: straight"},
    {.section = "contact.*", .key = "damping", .kind = law, .field = FIELD(contact->damping), .def = registry,
     .role = LawRole::damping, .meaning = "damping law"},
    {.section = "contact.*", .key = "damping_factor", .kind = number, .field = FIELD(contact->damping.factor),
     .dim = dim::inverse_speed, .bounds = non_negative, .def = value(0.5), .when = damping_law_on, .otherwise = 0,
     .meaning = "F = F_elastic (1 + factor d(delta)/dt); 0.5 s/m: restitution about 0.93 at a 0.2 m/s impact"},
    {.section = "contact.*", .key = "traction", .kind = law, .field = FIELD(contact->traction), .def = registry,
     .then = traction_fits_normal_law, .role = LawRole::traction, .meaning = "traction (friction) law"},
    {.section = "contact.*", .key = "friction_coefficient", .kind = number,
     .field = FIELD(contact->traction.friction_coefficient), .dim = dim::none, .bounds = {.lo = 0, .hi = 1},
     .def = derived(friction_default, "0.1; cage_land 0.05"), .when = traction_law_on,
     .meaning = "limit of the traction curve"},
    {.section = "contact.*", .key = "slip_velocity_scale", .kind = number,
     .field = FIELD(contact->traction.slip_velocity_scale), .dim = dim::speed, .bounds = positive, .def = value(0.05),
     .when = traction_law_on, .otherwise = 0.05,
     .meaning = "u_s of the tanh curve: 70 % of the limit at about 1 % slide-to-roll at a few m/s"},
    {.section = "contact.*", .key = "grid", .kind = cell_grid, .field = FIELD(contact->traction),
     .def = {.kind = Default::Kind::absent, .text = "[5, 5]"}, .contacts = contact::ball_race_contact, .elsewhere = kBallRaceContact, .when = traction_law_on,
     .meaning = "traction cells over the contact ellipse (rolling, transverse); 5 x 5 keeps cage speed and loads "
                "within 0.1 % of a fine grid, but a spinning contact's net traction force is 43 % off (64 x 64: "
                "0.1 %; 6309_R3_fine_traction.toml)"},
    {.section = "contact.*", .key = "rolling_resistance", .kind = boolean,
     .field = FIELD(contact->traction.rolling_resistance),
     .def = derived(rolling_resistance_default, "true with a [lubricant], else false"),
     .contacts = contact::ball_race_contact, .elsewhere = kBallRaceContact, .then = rolling_resistance_has_film,
     .meaning = "EHL rolling resistance (needs a film)"},

    // ---- [solver]: CVODE --------------------------------------------------------------------------
    {.section = "solver", .key = "method", .kind = choice, .field = FIELD(scene.solver.method), .def = word("bdf"),
     .options = kMethods,
     .meaning = "bdf (stiff) or adams (non-stiff) multistep methods of CVODE; erk: explicit Runge-Kutta pairs, ark: "
                "diagonally implicit Runge-Kutta with the Newton solve (ARKODE)"},
    {.section = "solver", .key = "max_order", .kind = integer, .field = FIELD(scene.solver.max_order),
     .bounds = {.lo = 1, .hi_of = max_order_limit, .hi_text = kMaxOrderText}, .def = derived(max_order_default, kMaxOrderDefaultText),
     .then = order_exists_for_method,
     .meaning = "bdf, adams: largest order; erk: order of the pair (2, 3, 4, 5 Dormand-Prince, 6 Verner, 8 Fehlberg); "
                "ark: order of the implicit pair (2 to 5)"},
    {.section = "solver", .key = "automatic_order", .kind = boolean, .field = FIELD(scene.solver.automatic_order),
     .def = derived(automatic_order_default, "true for bdf unless max_order is given"), .when = bdf_order_choice,
     .then = automatic_order_has_choice, .otherwise = 0,
     .meaning = "bdf: the largest order switches between max_order and 2 (A-stable) by measured probes of the other "
                "order, where one advances the time 1.5 times further per unit of work (docs/integration_methods.md)"},
    {.section = "solver", .key = "stability_limit_detection", .kind = boolean,
     .field = FIELD(scene.solver.stability_limit_detection), .def = value(0), .when = bdf_only, .otherwise = 0,
     .meaning = "CVODE's BDF stability-limit detection: lowers the order where order 3 to 5 is unstable"},
    {.section = "solver", .key = "pocket_tolerance_factor", .kind = number,
     .field = FIELD(scene.solver.pocket_tolerance_factor), .dim = dim::none, .bounds = {.lo = 1, .hi = 1e6},
     .def = value(1),
     .meaning = "while a rolling element touches its cage pocket (or is within 1e-4 of its radius of it), the "
                "tolerances of its translational velocities are this many times tighter (a pocket contact's approach "
                "velocity lies far below rtol times the element's orbital speed); 1: off"},
    {.section = "solver", .key = "pocket_tolerance_cage", .kind = boolean,
     .field = FIELD(scene.solver.pocket_tolerance_cage), .def = value(0), .when = pocket_factor_given, .otherwise = 0,
     .meaning = "with pocket_tolerance_factor: while any rolling element touches its pocket, the cage's rotation "
                "rate is that many times tighter as well (the pocket's approach rate is the small difference of the "
                "element's orbital rate and the cage's; docs/integration_methods.md)"},
    {.section = "solver", .key = "element_velocity_frame", .kind = choice,
     .field = FIELD(scene.solver.element_velocity_frame), .def = word("bearing"),
     .bearings = ball_bearings | planar_rollers, .elsewhere = kElementVelocityFrame, .options = kElementVelocityFrames,
     .meaning = "the frame of the rolling elements' in-plane velocity states: bearing (vx, vy) or orbital (v_r, "
                "v_theta at the element's own angle about the axis), whose radial and circumferential tolerances "
                "can differ (docs/integration_methods.md)"},
    {.section = "solver", .key = "radial_velocity_tolerance_factor", .kind = number,
     .field = FIELD(scene.solver.radial_velocity_tolerance_factor), .dim = dim::none, .bounds = {.lo = 1e-3, .hi = 1e3},
     .def = value(1), .bearings = ball_bearings | planar_rollers, .elsewhere = kElementVelocityFrame,
     .when = orbital_velocity_frame, .otherwise = 1,
     .meaning = "orbital frame: the rolling elements' radial velocity tolerance is this many times the velocity "
                "tolerance (> 1 looser: the radial contact vibration; the circumferential velocity keeps its tolerance)"},
    {.section = "solver", .key = "rtol", .kind = number, .field = FIELD(scene.solver.rtol), .dim = dim::none,
     .bounds = {.lo = 1e-14, .hi = 1e-2, .lo_open = true}, .def = value(1e-6), .meaning = "relative tolerance"},
    {.section = "solver", .key = "atol", .kind = table, .field = nullptr, .def = empty_table, .sub = "solver.atol",
     .meaning = "absolute tolerances per kind of variable; 0 or absent: chosen from the physical scales"},
    {.section = "solver", .key = "linear_solver", .kind = choice, .field = FIELD(scene.solver.linear_solver),
     .def = word("auto"), .options = kLinearSolvers, .noun = "linear solver",
     .meaning = "Newton linear solver; auto picks by the number of rolling elements (README \"Newton linear "
                "solvers\"); bordered and dense are older names"},
    {.section = "solver", .key = "petsc_options", .kind = text, .field = FIELD(scene.solver.petsc_options),
     .def = word(""), .then = remember_petsc_options_place,
     .meaning = "PETSc options for petsc-bordered, checked when the run starts"},
    {.section = "solver", .key = "max_step", .kind = number, .field = FIELD(scene.solver.max_step), .dim = dim::time,
     .bounds = non_negative, .def = value(0), .meaning = "largest time step; 0: no limit"},
    {.section = "solver", .key = "initial_step", .kind = number, .field = FIELD(scene.solver.initial_step),
     .dim = dim::time, .bounds = non_negative, .def = value(0), .then = initial_step_within_run,
     .meaning = "first time step (at most end_time); 0: CVODE's estimate"},
    {.section = "solver", .key = "max_steps", .kind = integer, .field = FIELD(scene.solver.max_steps),
     .bounds = {.lo = 1}, .def = value(500000000), .meaning = "step budget of the run"},
    {.section = "solver", .key = "max_wall_time", .kind = number, .field = FIELD(scene.solver.max_wall_time),
     .dim = dim::time, .bounds = non_negative, .def = value(0), .example = "2 h",
     .meaning = "wall-clock budget of the integration: past it the run ends with a diagnosis (exit 3); 0: no limit"},
    {.section = "solver", .key = "jacobian_perturbation", .kind = number,
     .field = FIELD(scene.solver.jacobian_perturbation), .dim = dim::none, .bounds = {.lo = 1e-12, .hi = 1e-2},
     .def = value(1e-7), .meaning = "relative finite-difference increment"},

    // ---- [solver.atol] --------------------------------------------------------------------------
    {.section = "solver.atol", .key = "position", .kind = number, .field = FIELD(scene.solver.atol_position),
     .dim = dim::length, .bounds = positive, .def = value(0), .meaning = "positions"},
    {.section = "solver.atol", .key = "angle", .kind = number, .field = FIELD(scene.solver.atol_angle),
     .dim = dim::angle, .bounds = positive, .def = value(0), .meaning = "angles"},
    {.section = "solver.atol", .key = "velocity", .kind = number, .field = FIELD(scene.solver.atol_velocity),
     .dim = dim::speed, .bounds = positive, .def = value(0), .meaning = "velocities"},
    {.section = "solver.atol", .key = "angular_velocity", .kind = number,
     .field = FIELD(scene.solver.atol_angular_velocity), .dim = dim::angular_speed, .bounds = positive,
     .def = value(0), .meaning = "angular velocities"},

    // ---- [output] -------------------------------------------------------------------------------
    {.section = "output", .key = "segments", .kind = boolean, .field = FIELD(scene.output.segments), .def = value(1),
     .meaning = "per-segment (per-contact) diagnostics"},
    {.section = "output", .key = "segment_every", .kind = integer, .field = FIELD(scene.output.segment_every),
     .bounds = {.lo = 1}, .def = value(1), .then = segment_every_within_run, .example = "5",
     .meaning = "the segment diagnostics at every N-th output sample only (samples 0, N, 2N, ... from the run's "
                "start; /segments' attribute sample_stride); 1: at every sample"},
    {.section = "output", .key = "max_size", .kind = number, .field = FIELD(scene.output.max_size),
     .dim = dim::information, .bounds = positive, .def = value(4e9), .example = "4 GB",
     .meaning = "largest output file (its series uncompressed, samples x values x 8 bytes, plus a bound of names, "
                "attributes and indexes, estimated by `raceway check`); a larger run is refused before it starts; the "
                "`/scheduler` log is thinned to what is left"},
    {.section = "output", .key = "checkpoint_interval", .kind = number, .field = FIELD(scene.output.checkpoint_interval),
     .dim = dim::time, .bounds = non_negative, .def = value(0),
     .meaning = "simulated time between checkpoints, rounded to whole output intervals; CVODE restarts at each, so a "
                "resumed run repeats the uninterrupted one bitwise (0: none)"},
    {.section = "output", .key = "checkpoint_wall_interval", .kind = number,
     .field = FIELD(scene.output.checkpoint_wall_interval), .dim = dim::time, .bounds = non_negative, .def = value(300),
     .meaning = "wall-clock time after which a checkpoint is also written at the next output time (no restart of "
                "CVODE: a resume from it agrees with an uninterrupted run to the tolerances, not bitwise; 0: none)"},
};

#undef FIELD

}  // namespace

std::span<const Row> run_rows() { return kRows; }

}  // namespace raceway::scene::schema::table
