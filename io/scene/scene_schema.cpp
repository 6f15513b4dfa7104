// The scene schema table (scene_schema.hpp): every key of a scene file, in reading order.
#include "io/scene/scene_schema.hpp"

#include <algorithm>
#include <numbers>

#include "io/scene/scene_rules.hpp"

namespace raceway::scene::schema {

namespace {

using contact::LawRole;
using enum ValueKind;
using namespace rules;

/// Where a row's value goes, as a path from the Bind: FIELD(scene.bearing.pitch_diameter).
#define FIELD(path) [](Bind& b) -> Field { return &b.path; }

/// Tables: an absent one is read as empty, every key at its default.
constexpr Default empty_table = value(0);

// Why a key is rejected where the bearing or contact does not take it.
constexpr std::string_view kBallOnly =
    "only for ball bearings (type = \"deep_groove_ball\", \"four_point_contact_ball\" or \"angular_contact_ball\")";
constexpr std::string_view kSpatialCage =
    "only for ball bearings (model = \"spatial\"): a planar cage moves in x, y and about z, and a spatial roller "
    "bearing's cage takes its section from the rollers as the planar one does";
constexpr std::string_view kRollerCage =
    "only for planar roller bearings: the bars between a roller cage's pockets, flexible in the plane (a ball "
    "cage's pockets are drilled; a spatial roller cage's bars are rigid)";
constexpr std::string_view kSpatialRing =
    "only for spatial scenes (model = \"spatial\"): a planar ring moves in x, y and about z";
constexpr std::string_view kSpatialDirection =
    "only for spatial scenes (model = \"spatial\"): a planar model has no axial direction and no tilt";
constexpr std::string_view kRollerContact =
    "roller-race and roller-cage contacts belong to roller bearings; a ball bearing's are [contact.ball_race] and "
    "[contact.ball_cage]";
constexpr std::string_view kFlangeContact =
    "roller-end on rib contacts belong to spatial roller bearings (model = \"spatial\"): a planar roller has no "
    "axial direction";
constexpr std::string_view kBallContact =
    "ball-race and ball-cage contacts belong to ball bearings; a roller bearing's are [contact.roller_race], "
    "[contact.roller_cage] (and, spatial, [contact.roller_flange])";
constexpr std::string_view kLineContact =
    "slices and crown_drop are for line contacts (roller bearings); a ball contact is a Hertz point contact";
constexpr std::string_view kBallRaceContact =
    "only for [contact.ball_race], the ball-groove point contacts: the other contacts' friction is a traction curve "
    "at the contact centre";

constexpr std::string_view kSpatialRoller =
    "only for cylindrical roller bearings in the spatial model (model = \"spatial\"): the planar model's rollers have "
    "no profile, ends or ribs";
constexpr Bounds kRibAngle{.lo = 0, .hi = std::numbers::pi / 18, .hi_open = true, .unit = "deg",
                           .note = " (ribs open by a fraction of a degree to a few degrees)"};

constexpr std::string_view kPlanarCarrier =
    "only for planar roller bearings (model = \"planar\"): the carrier's frame terms act in the bearing's plane";

constexpr std::string_view kPlanarRim =
    "only for planar roller bearings (model = \"planar\"): the rim's in-plane bending modes";

constexpr std::string_view kMaxOrderText = "5 (bdf), 12 (adams), 8 (erk), 5 (ark)";
constexpr std::string_view kMaxOrderDefaultText = "5 (bdf), 12 (adams), 5 (erk), 4 (ark)";

constexpr Bounds kConformity{.lo = 0.5, .hi = 0.6, .lo_open = true,
                             .note = " (conformity = groove radius / ball diameter: the groove radius must exceed the "
                                     "ball radius; ball bearing grooves are 0.505 to 0.58)"};
constexpr Bounds kArcAngle{.lo = 0, .hi = std::numbers::pi / 3, .lo_open = true, .hi_open = true, .unit = "deg"};
constexpr std::string_view kContactAngleMissing =
    "required for type = \"angular_contact_ball\": its free contact angle, e.g. \"40 deg\" (or give the groove "
    "geometry's radial_clearance, from which it follows)";
constexpr Bounds kFreeContactAngle{.lo = 0, .hi = std::numbers::pi / 3, .lo_open = true, .hi_open = true, .unit = "deg",
                                   .note = " (angular contact bearings are made with 15 to 40 deg)"};
constexpr Bounds kAxialPosition{.lo = -1e-3, .hi = 1e-3, .unit = "um",
                                .note = " (preload displacements are micrometres to some tens of them)"};
constexpr Bounds kMisalignment{.lo = -0.05, .hi = 0.05, .unit = "mrad",
                               .note = " (a sanity limit: ball bearings run at a few mrad)"};

constexpr Bounds kMassEccentricity{.lo = 0, .hi = 1e-3, .unit = "um",
                                   .note = " (machined cages are balanced to some micrometres; 1 mm is a sanity limit)"};

constexpr Bounds kSpallAngle{.lo = -2 * std::numbers::pi, .hi = 2 * std::numbers::pi, .unit = "deg"};
constexpr Bounds kSpallSize{.lo = 0, .hi = 0.01, .lo_open = true, .unit = "mm",
                            .note = " (a spall is a fraction of a millimetre to some millimetres)"};
constexpr Bounds kWavinessAmplitude{.lo = 0, .hi = 1e-4, .unit = "um",
                                    .note = " (waviness is some tenths of a micrometre to some micrometres)"};

constexpr Row kRows[] = {
    // ---- [scene] --------------------------------------------------------------------------------
    {.section = "scene", .key = "name", .kind = text, .field = FIELD(scene.scene.name),
     .meaning = "label stored in the output"},
    {.section = "scene", .key = "model", .kind = choice, .field = FIELD(scene.scene.model), .options = kModels,
     .meaning = "planar: cylindrical roller bearings (x, y, rotation about z); spatial: ball and cylindrical roller "
                "bearings (all six directions; rollers sliced along their length, with ribs and tilt)"},
    {.section = "scene", .key = "allow_out_of_range", .kind = key_list, .field = FIELD(scene.scene.allow_out_of_range),
     .def = absent, .then = allowed_keys_in_scene,
     .meaning = "dotted keys (\"materials.rubber.youngs_modulus\") whose values may lie beyond the sane range of their "
                "quantity (see Sane ranges); read before the keys after it"},
    {.section = "scene", .key = "end_time", .kind = number, .field = FIELD(scene.scene.end_time), .dim = dim::time,
     .bounds = positive, .meaning = "simulated time"},
    {.section = "scene", .key = "output_interval", .kind = number, .field = FIELD(scene.scene.output_interval),
     .dim = dim::time, .bounds = positive, .then = output_interval_within_run,
     .meaning = "time between stored samples (at most end_time)"},
    {.section = "scene", .key = "gravity", .kind = boolean, .field = FIELD(scene.gravity), .def = value(0),
     .meaning = "gravity along -y (9.80665 m/s^2)"},

    // ---- [materials.NAME]: steel, brass and polyamide are built in; a section adds or replaces one
    {.section = "materials.*", .key = "density", .kind = number, .field = FIELD(material->density),
     .dim = dim::density, .bounds = positive, .meaning = "mass density"},
    {.section = "materials.*", .key = "youngs_modulus", .kind = number, .field = FIELD(material->youngs_modulus),
     .dim = dim::pressure, .bounds = positive, .meaning = "Young's modulus"},
    {.section = "materials.*", .key = "poisson_ratio", .kind = number, .field = FIELD(material->poisson_ratio),
     .dim = dim::none, .bounds = {.lo = 0, .hi = 0.5, .hi_open = true}, .meaning = "Poisson's ratio"},

    // ---- [bearing] ------------------------------------------------------------------------------
    {.section = "bearing", .key = "designation", .kind = text, .field = FIELD(scene.designation), .def = absent,
     .example = "6205",
     .meaning = "a catalogue bearing (docs/catalogue.md: 60, 62, 63, 72..B, QJ2.., NU2.. series): fills every key of "
                "[bearing] and [cage], the model and first-scene defaults that the scene does not give; `raceway "
                "check` lists them"},
    {.section = "bearing", .key = "type", .kind = choice, .field = FIELD(scene.bearing.type),
     .then = model_fits_bearing_type, .options = kBearingTypes, .noun = "bearing type",
     .meaning = "cylindrical_roller: model = \"planar\" or \"spatial\"; the ball bearings need model = \"spatial\""},
    {.section = "bearing", .key = "rolling_elements", .kind = integer, .field = FIELD(scene.bearing.rolling_elements),
     .bounds = {.lo = 3, .hi = 1000}, .meaning = "number of rollers or balls (large slewing rings have a few hundred)"},
    {.section = "bearing", .key = "roller_diameter", .kind = number, .field = FIELD(scene.bearing.roller_diameter),
     .dim = dim::length, .bounds = positive, .bearings = roller_bearings,
     .elsewhere = "a ball bearing has no roller diameter: give ball_diameter", .meaning = "roller diameter D"},
    {.section = "bearing", .key = "roller_length", .kind = number, .field = FIELD(scene.bearing.roller_length),
     .dim = dim::length, .bounds = positive, .bearings = roller_bearings,
     .elsewhere = "a ball bearing has no roller length: ring_width gives the width of the rings",
     .meaning = "effective contact length of a roller"},
    {.section = "bearing", .key = "ball_diameter", .kind = number, .field = FIELD(scene.bearing.ball.ball_diameter),
     .dim = dim::length, .bounds = positive, .bearings = ball_bearings, .elsewhere = kBallOnly,
     .meaning = "ball diameter D"},
    {.section = "bearing", .key = "inner_conformity", .kind = number,
     .field = FIELD(scene.bearing.ball.inner_conformity), .dim = dim::none, .bounds = kConformity,
     .bearings = ball_bearings, .elsewhere = kBallOnly, .meaning = "f_i = inner groove radius / ball diameter"},
    {.section = "bearing", .key = "outer_conformity", .kind = number,
     .field = FIELD(scene.bearing.ball.outer_conformity), .dim = dim::none, .bounds = kConformity,
     .bearings = ball_bearings, .elsewhere = kBallOnly, .meaning = "f_o = outer groove radius / ball diameter"},
    {.section = "bearing", .key = "arc_contact_angle", .kind = number,
     .field = FIELD(scene.bearing.ball.arc_contact_angle), .dim = dim::angle, .bounds = kArcAngle,
     .bearings = ball_bearings, .elsewhere = kBallOnly, .when = four_point_only,
     .missing = "required for type = \"four_point_contact_ball\": the angle at which a centred ball touches each "
                "gothic arc, e.g. \"35 deg\"",
     .example = "35 deg",
     .meaning = "four-point bearings: angle at which a centred ball touches each gothic arc (sets the arcs' offset)"},
    {.section = "bearing", .key = "pitch_diameter", .kind = number, .field = FIELD(scene.bearing.pitch_diameter),
     .dim = dim::length, .bounds = positive, .meaning = "diameter d_m of the circle through the element centres"},
    {.section = "bearing", .key = "radial_clearance", .kind = number, .field = FIELD(scene.bearing.radial_clearance),
     .dim = dim::length, .def = value(0), .then = clearance_fits_elements,
     .meaning = "diametral clearance P_d: race diameters are d_m -/+ (D + P_d/2); negative: a preload (roller bearings, at most 1 % of D)"},
    {.section = "bearing", .key = "contact_angle", .kind = number, .field = FIELD(scene.bearing.ball.free_contact_angle),
     .dim = dim::angle, .bounds = kFreeContactAngle, .bearings = ball_bearings, .elsewhere = kBallOnly,
     .when = contact_angle_applies, .missing = kContactAngleMissing, .example = "40 deg",
     .meaning = "angular contact bearings: the free (nominal) contact angle, at which the unloaded ball touches both "
                "grooves; the contact line runs from the inner groove at -z to the outer at +z"},
    {.section = "bearing", .key = "inner_bore_diameter", .kind = number,
     .field = FIELD(scene.bearing.inner_bore_diameter), .dim = dim::length, .bounds = positive,
     .def = derived(inner_bore_default, "inner race diameter - D"), .then = bore_inside_inner_race,
     .meaning = "bore of the inner ring (sets its mass)"},
    {.section = "bearing", .key = "outer_outside_diameter", .kind = number,
     .field = FIELD(scene.bearing.outer_outside_diameter), .dim = dim::length, .bounds = positive,
     .def = derived(outer_outside_default, "outer race diameter + D"), .then = outside_beyond_outer_race,
     .meaning = "outside diameter of the outer ring (sets its mass)"},
    {.section = "bearing", .key = "ring_width", .kind = number, .field = FIELD(scene.bearing.ring_width),
     .dim = dim::length, .bounds = positive,
     .def = derived(ring_width_default, "roller_length; required for ball bearings"), .then = ring_wider_than_ball,
     .meaning = "width of both rings"},
    {.section = "bearing", .key = "roller_material", .kind = material, .field = FIELD(scene.bearing.roller_material),
     .def = word("steel"), .when = unless_ball_material, .meaning = "material of the rollers (or balls)"},
    {.section = "bearing", .key = "ball_material", .kind = material, .field = FIELD(scene.bearing.roller_material),
     .def = absent, .bearings = ball_bearings, .elsewhere = kBallOnly,
     .meaning = "material of the balls (the same as roller_material: give one)"},
    {.section = "bearing", .key = "ring_material", .kind = material, .field = FIELD(scene.bearing.ring_material),
     .def = word("steel"), .meaning = "material of both rings"},

    {.section = "bearing", .key = "roller_profile", .kind = choice, .field = FIELD(scene.bearing.roller.profile),
     .def = word("straight"), .bearings = spatial_rollers, .elsewhere = kSpatialRoller, .options = kRollerProfiles,
     .noun = "roller profile", .meaning = "the roller's profile: straight, circular crown, logarithmic (lundberg, johns_gohar)"},
    {.section = "bearing", .key = "corner_radius", .kind = number, .field = FIELD(scene.bearing.roller.corner_radius),
     .dim = dim::length, .bounds = non_negative, .def = value(0), .bearings = spatial_rollers,
     .elsewhere = kSpatialRoller,
     .meaning = "r_c: the rounding of the roller's ends, beyond roller_length at each end (carries only when the "
                "roller tilts into it)"},
    {.section = "bearing", .key = "crown_radius", .kind = number, .field = FIELD(scene.bearing.roller.crown_radius),
     .dim = dim::length, .bounds = positive, .bearings = spatial_rollers, .elsewhere = kSpatialRoller,
     .when = circular_profile_only,
     .missing = "required for roller_profile = \"circular\": the crown's radius, e.g. \"500 mm\"",
     .example = "500 mm", .meaning = "circular crown: its radius R_c"},
    {.section = "bearing", .key = "flat_length", .kind = number, .field = FIELD(scene.bearing.roller.flat_length),
     .dim = dim::length, .bounds = non_negative, .def = value(0), .bearings = spatial_rollers, .elsewhere = kSpatialRoller,
     .when = circular_profile_only, .meaning = "circular crown: the straight middle (0: crowned over the whole length)"},
    {.section = "bearing", .key = "profile_design_load", .kind = number, .field = FIELD(scene.bearing.roller.design_load),
     .dim = dim::force, .bounds = positive, .bearings = spatial_rollers, .elsewhere = kSpatialRoller,
     .when = logarithmic_profile_only,
     .missing = "required for a logarithmic roller_profile: the roller load it is designed for, e.g. \"5 kN\"",
     .example = "5 kN", .meaning = "logarithmic profiles: the design load Q_d"},
    {.section = "bearing", .key = "ribs", .kind = choice, .field = FIELD(scene.bearing.roller.ribs), .def = word("NU"),
     .bearings = spatial_rollers, .elsewhere = kSpatialRoller, .then = roller_profile_fits, .options = kRibArrangements,
     .noun = "rib arrangement",
     .meaning = "NU: two ribs on the outer ring; NJ: and one on the inner ring's -z side; NUP: two on each ring; N: two "
                "on the inner ring"},
    {.section = "bearing", .key = "roller_end", .kind = choice, .field = FIELD(scene.bearing.roller.end), .def = word("flat"),
     .bearings = spatial_rollers, .elsewhere = kSpatialRoller, .options = kRollerEnds, .noun = "roller end",
     .meaning = "the roller's end faces: flat with a rounded edge, or spherical"},
    {.section = "bearing", .key = "end_radius", .kind = number, .field = FIELD(scene.bearing.roller.end_radius),
     .dim = dim::length, .bounds = positive,
     .def = derived(end_radius_default, "flat: corner_radius, or D / 10 where that is 0; spherical: d_m / 2"),
     .bearings = spatial_rollers, .elsewhere = kSpatialRoller, .then = end_radius_fits,
     .meaning = "flat ends: the rounding of the end face's edge, which touches the rib; spherical ends: the sphere's "
                "radius"},
    {.section = "bearing", .key = "rib_angle", .kind = number, .field = FIELD(scene.bearing.roller.rib_angle),
     .dim = dim::angle, .bounds = kRibAngle, .def = value(0.5 * std::numbers::pi / 180), .bearings = spatial_rollers,
     .elsewhere = kSpatialRoller, .then = rib_angle_fits_end,
     .meaning = "the rib face's opening angle from a radial plane (a flat roller end needs one: a flat end on a flat "
                "rib touches along an edge)"},
    {.section = "bearing", .key = "roller_end_clearance", .kind = number,
     .field = FIELD(scene.bearing.roller.end_clearance), .dim = dim::length, .bounds = non_negative,
     .def = value(50e-6), .bearings = spatial_rollers, .elsewhere = kSpatialRoller, .then = end_clearance_fits,
     .meaning = "axial play of a centred roller between the two ribs of a ring"},
    // ---- [cage] ---------------------------------------------------------------------------------
    {.section = "cage", .key = "guidance", .kind = choice, .field = FIELD(scene.cage.guidance), .options = kGuidances,
     .meaning = "what guides the cage radially: a ring's land or the rolling elements"},
    {.section = "cage", .key = "pocket_clearance", .kind = number, .field = FIELD(scene.cage.pocket_clearance),
     .dim = dim::length, .bounds = positive, .then = ball_pocket_clearance_fits,
     .meaning = "pocket width (diameter) minus roller (ball) diameter"},
    {.section = "cage", .key = "land_clearance", .kind = number, .field = FIELD(scene.cage.land_clearance),
     .dim = dim::length, .bounds = positive, .when = land_guided_only, .then = land_clearance_fits,
     .meaning = "land-guided cages: radial play between cage and guiding land"},
    {.section = "cage", .key = "bar_width", .kind = number, .field = FIELD(scene.cage.bar_width), .dim = dim::length,
     .bounds = positive, .def = derived(bar_width_default, "roller_length"), .bearings = roller_bearings,
     .elsewhere = "bar_width is for roller cages; a ball pocket is set by pocket_clearance and pocket_shape",
     .then = bars_within_rollers, .meaning = "axial length of the roller-bar contact"},
    {.section = "cage", .key = "land_width", .kind = number, .field = FIELD(scene.cage.land_width), .dim = dim::length,
     .bounds = positive, .def = derived(land_width_default, "roller_length / 2; balls: ring_width - D"),
     .then = land_width_within_rings, .meaning = "axial width of the guiding land contact"},
    {.section = "cage", .key = "material", .kind = material, .field = FIELD(scene.cage.material), .def = word("brass"),
     .meaning = "cage material"},
    {.section = "cage", .key = "mass", .kind = number, .field = FIELD(scene.cage.mass), .dim = dim::mass,
     .bounds = positive, .def = value(0), .meaning = "0: computed from geometry and material"},
    {.section = "cage", .key = "inertia", .kind = number, .field = FIELD(scene.cage.inertia), .dim = dim::inertia,
     .bounds = positive, .def = value(0), .meaning = "about the bearing axis; 0: computed"},
    {.section = "cage", .key = "bridges", .kind = choice, .field = FIELD(scene.cage.bridges), .def = word("rigid"),
     .bearings = planar_rollers, .elsewhere = kRollerCage, .options = kCageBridges, .noun = "bridge model",
     .meaning = "the bars between the pockets: rigid with the cage, or flexible (each a clamped beam whose "
                "tangential deflection is a state)"},
    {.section = "cage", .key = "bridge_stiffness", .kind = number, .field = FIELD(scene.cage.bridge_stiffness),
     .dim = dim::stiffness, .bounds = positive, .def = value(0), .bearings = planar_rollers,
     .elsewhere = kRollerCage, .meaning = "flexible bridges: tangential stiffness under the pocket force; 0: "
                                         "720 E I / L^3 from the section (clamped beam, load along its length)"},
    {.section = "cage", .key = "bridge_thickness", .kind = number, .field = FIELD(scene.cage.bridge_thickness),
     .dim = dim::length, .bounds = positive, .def = value(0), .bearings = planar_rollers, .elsewhere = kRollerCage,
     .meaning = "flexible bridges: circumferential thickness; 0: d_m sin(pi / Z) - D - pocket_clearance"},
    {.section = "cage", .key = "bridge_height", .kind = number, .field = FIELD(scene.cage.bridge_height),
     .dim = dim::length, .bounds = positive, .def = value(0), .bearings = planar_rollers, .elsewhere = kRollerCage,
     .meaning = "flexible bridges: radial height; 0: the cage's radial section"},
    {.section = "cage", .key = "bridge_damping_ratio", .kind = number,
     .field = FIELD(scene.cage.bridge_damping_ratio), .dim = dim::none, .bounds = {.lo = 0, .hi = 1},
     .def = value(0.02), .bearings = planar_rollers, .elsewhere = kRollerCage,
     .meaning = "flexible bridges: damping ratio of a bridge's bending mode"},
    {.section = "cage", .key = "pocket_shape", .kind = choice, .field = FIELD(scene.cage.pocket_shape),
     .def = word("cylindrical"), .bearings = ball_bearings, .elsewhere = kSpatialCage, .options = kPocketShapes,
     .noun = "pocket shape", .meaning = "cylindrical (drilled radially: machined cages) or spherical (pressed, snap)"},
    {.section = "cage", .key = "transverse_inertia", .kind = number, .field = FIELD(scene.cage.transverse_inertia),
     .dim = dim::inertia, .bounds = positive, .def = value(0), .bearings = ball_bearings, .elsewhere = kSpatialCage,
     .meaning = "about a diameter; 0: computed"},
    {.section = "cage", .key = "inner_diameter", .kind = number, .field = FIELD(scene.cage.inner_diameter),
     .dim = dim::length, .bounds = positive, .def = derived(cage_bore_default, "d_m - 0.6 D"),
     .bearings = ball_bearings, .elsewhere = kSpatialCage, .then = cage_bore_between_race_and_pitch,
     .meaning = "cage bore"},
    {.section = "cage", .key = "outer_diameter", .kind = number, .field = FIELD(scene.cage.outer_diameter),
     .dim = dim::length, .bounds = positive, .def = derived(cage_outside_default, "d_m + 0.6 D"),
     .bearings = ball_bearings, .elsewhere = kSpatialCage, .then = cage_outside_between_pitch_and_race,
     .meaning = "cage outside diameter"},
    {.section = "cage", .key = "width", .kind = number, .field = FIELD(scene.cage.width), .dim = dim::length,
     .bounds = positive, .def = derived(cage_width_default, "0.8 ring_width"), .bearings = ball_bearings,
     .elsewhere = kSpatialCage, .then = cage_width_fits, .meaning = "axial width of the cage (at most ring_width)"},
    {.section = "cage", .key = "initial_offset", .kind = number, .field = FIELD(scene.cage.initial_offset),
     .dim = dim::length, .bounds = non_negative, .def = value(0), .bearings = ball_bearings, .elsewhere = kSpatialCage,
     .then = cage_offset_within_clearances, .example = "50 um",
     .meaning = "the cage centre starts this far along +x from where the seated balls put it, at rest (a disturbed "
                "start: a centred cage under symmetric forces stays centred)"},
    {.section = "cage", .key = "mass_eccentricity", .kind = number, .field = FIELD(scene.cage.mass_eccentricity),
     .dim = dim::length, .bounds = kMassEccentricity, .def = value(0), .bearings = ball_bearings,
     .elsewhere = kSpatialCage, .example = "10 um",
     .meaning = "distance of the cage's centre of mass from its axis (static unbalance = mass x this), along the cage "
                "frame's x: its centrifugal force turns with the cage"},
    {.section = "cage", .key = "support", .kind = table, .field = nullptr, .def = absent, .bearings = ball_bearings,
     .elsewhere = kSpatialCage, .then = cage_support_has_spring, .sub = "cage.support",
     .meaning = "a cage on a spindle: a spring and a damper per direction"},

    // ---- [cage.support] -------------------------------------------------------------------------
    {.section = "cage.support", .key = "radial_stiffness", .kind = number,
     .field = FIELD(scene.cage.support.radial_stiffness), .dim = dim::stiffness, .bounds = positive, .def = value(0),
     .meaning = "in x and y"},
    {.section = "cage.support", .key = "radial_damping", .kind = number,
     .field = FIELD(scene.cage.support.radial_damping), .dim = dim::damping, .bounds = non_negative,
     .def = value(0), .then = damper_has_spring, .meaning = "in x and y (needs radial_stiffness)"},
    {.section = "cage.support", .key = "axial_stiffness", .kind = number,
     .field = FIELD(scene.cage.support.axial_stiffness), .dim = dim::stiffness, .bounds = positive, .def = value(0),
     .meaning = "along z"},
    {.section = "cage.support", .key = "axial_damping", .kind = number,
     .field = FIELD(scene.cage.support.axial_damping), .dim = dim::damping, .bounds = non_negative, .def = value(0),
     .then = damper_has_spring, .meaning = "along z (needs axial_stiffness)"},
    {.section = "cage.support", .key = "tilt_stiffness", .kind = number,
     .field = FIELD(scene.cage.support.tilt_stiffness), .dim = dim::angular_stiffness, .bounds = positive,
     .def = value(0), .meaning = "about x and y"},
    {.section = "cage.support", .key = "tilt_damping", .kind = number, .field = FIELD(scene.cage.support.tilt_damping),
     .dim = dim::angular_damping, .bounds = non_negative, .def = value(0), .then = damper_has_spring,
     .meaning = "about x and y (needs tilt_stiffness)"},

    // ---- [inner_ring] and [outer_ring] ----------------------------------------------------------
    {.section = "*_ring", .key = "motion", .kind = choice, .field = FIELD(ring->motion), .options = kRingMotions,
     .meaning = "fixed: held; driven: spun at speed; free: spun by the loads (and mz)"},
    {.section = "*_ring", .key = "speed", .kind = time_function, .field = FIELD(ring->speed),
     .dim = dim::angular_speed, .when = driven_ring_only, .missing = "required when motion = \"driven\"",
     .example = "1500 rpm", .meaning = "driven rings: speed about the axis"},
    {.section = "*_ring", .key = "translation", .kind = choice, .field = FIELD(ring->translation_free),
     .def = word("free"), .when = moving_ring_only, .options = kFreeOrFixed, .otherwise = 0,
     .meaning = "driven and free rings: centre free in x and y, or held"},
    {.section = "*_ring", .key = "axial", .kind = choice, .field = FIELD(ring->axial_free), .def = word("free"),
     .bearings = spatial_bearings, .elsewhere = kSpatialRing, .when = moving_ring_only, .options = kFreeOrFixed,
     .otherwise = 0, .meaning = "driven and free rings: free along z, or held"},
    {.section = "*_ring", .key = "axial_position", .kind = number, .field = FIELD(ring->axial_position),
     .dim = dim::length, .bounds = kAxialPosition, .def = value(0), .bearings = spatial_bearings,
     .elsewhere = kSpatialRing, .when = axially_held_only, .example = "20 um",
     .meaning = "rings held axially: where (preload by displacement: an angular contact bearing's inner ring held "
                "at +z)"},
    {.section = "*_ring", .key = "tilt", .kind = choice, .field = FIELD(ring->tilt), .def = word("fixed"),
     .bearings = spatial_bearings, .elsewhere = kSpatialRing, .then = fixed_ring_tilt_not_free, .options = kRingTilts,
     .meaning = "about x and y: held aligned, free (integrated), or prescribed (misalignment)"},
    {.section = "*_ring", .key = "misalignment", .kind = table, .field = nullptr, .bearings = spatial_bearings,
     .elsewhere = kSpatialRing, .when = prescribed_tilt_only,
     .missing = "required with tilt = \"prescribed\": e.g. misalignment = { x = \"1.42 mrad\" } (rotations about "
                "the x and y axes)",
     .then = misalignment_given, .sub = "*_ring.misalignment",
     .meaning = "tilt = \"prescribed\": rotations about x and y"},
    {.section = "*_ring", .key = "load", .kind = table, .field = nullptr, .def = empty_table, .sub = "*_ring.load",
     .meaning = "forces and moments on the ring, in the bearing frame"},
    {.section = "*_ring", .key = "support", .kind = table, .field = nullptr, .def = absent,
     .when = support_needs_moving_ring, .then = ring_support_has_spring, .sub = "*_ring.support",
     .meaning = "a linear spring-damper to ground per direction"},
    {.section = "*_ring", .key = "mass", .kind = number, .field = FIELD(ring->mass), .dim = dim::mass,
     .bounds = positive, .def = value(0), .meaning = "0: computed from geometry and material"},
    {.section = "*_ring", .key = "inertia", .kind = number, .field = FIELD(ring->inertia), .dim = dim::inertia,
     .bounds = positive, .def = value(0), .meaning = "about the bearing axis; 0: computed"},
    {.section = "*_ring", .key = "transverse_inertia", .kind = number, .field = FIELD(ring->transverse_inertia),
     .dim = dim::inertia, .bounds = positive, .def = value(0), .bearings = spatial_bearings, .elsewhere = kSpatialRing,
     .meaning = "about a diameter; 0: computed"},
    {.section = "*_ring", .key = "flexibility", .kind = choice, .field = FIELD(ring->flexibility),
     .def = word("rigid"), .bearings = planar_rollers, .elsewhere = kPlanarRim, .when = outer_ring_only,
     .options = kRingFlexibilities, .noun = "ring flexibility",
     .meaning = "the outer ring's raceway: rigid, or ring_modes (a thin elastic rim whose in-plane inextensional "
                "bending modes n = 2..modes are states: a planet gear's rim, seed 003 2.3)"},
    {.section = "*_ring", .key = "modes", .kind = integer, .field = FIELD(ring->modes), .bounds = {.lo = 2, .hi = 40},
     .def = value(8), .bearings = planar_rollers, .elsewhere = kPlanarRim, .when = ring_modes_only,
     .meaning = "flexibility = \"ring_modes\": the highest bending mode number kept (the point-load deflection "
                "converges as 1 / modes^3)"},
    {.section = "*_ring", .key = "rim_thickness", .kind = number, .field = FIELD(ring->rim_thickness),
     .dim = dim::length, .bounds = positive, .def = value(0), .bearings = planar_rollers, .elsewhere = kPlanarRim,
     .when = ring_modes_only, .example = "8 mm",
     .meaning = "flexibility = \"ring_modes\": radial thickness of the rim's bending section; 0: (outside diameter "
                "- outer race diameter) / 2"},
    {.section = "*_ring", .key = "rim_width", .kind = number, .field = FIELD(ring->rim_width), .dim = dim::length,
     .bounds = positive, .def = value(0), .bearings = planar_rollers, .elsewhere = kPlanarRim,
     .when = ring_modes_only, .meaning = "flexibility = \"ring_modes\": axial width of the rim's bending section; 0: "
                                        "the ring width"},
    {.section = "*_ring", .key = "rim_damping_ratio", .kind = number, .field = FIELD(ring->rim_damping_ratio),
     .dim = dim::none, .bounds = {.lo = 0, .hi = 1}, .def = value(0.02), .bearings = planar_rollers,
     .elsewhere = kPlanarRim, .when = ring_modes_only,
     .meaning = "flexibility = \"ring_modes\": damping ratio of every bending mode"},

    {.section = "*_ring", .key = "spall", .kind = table, .field = nullptr, .def = absent, .bearings = ball_bearings,
     .elsewhere = kBallOnly, .then = spall_given, .sub = "*_ring.spall",
     .meaning = "a localized defect (spall) on the ring's race (docs/vibration.md)"},
    {.section = "*_ring", .key = "waviness", .kind = table, .field = nullptr, .def = absent, .bearings = ball_bearings,
     .elsewhere = kBallOnly, .then = waviness_lists_match, .sub = "*_ring.waviness",
     .meaning = "the race's waviness: radius deviation sum A_k cos(n_k theta + phase_k) (docs/vibration.md)"},

    // ---- [*_ring.spall] and [*_ring.waviness]: the race's imperfections (ball bearings) ---------
    {.section = "*_ring.spall", .key = "angle", .kind = number, .field = FIELD(ring->spall.angle), .dim = dim::angle,
     .bounds = kSpallAngle, .def = value(0), .example = "90 deg",
     .meaning = "the spall's centre about the ring axis, in the ring's frame (0: along x; the inner ring's turns)"},
    {.section = "*_ring.spall", .key = "length", .kind = number, .field = FIELD(ring->spall.length),
     .dim = dim::length, .bounds = kSpallSize, .example = "0.178 mm", .meaning = "along the race"},
    {.section = "*_ring.spall", .key = "width", .kind = number, .field = FIELD(ring->spall.width), .dim = dim::length,
     .bounds = kSpallSize, .example = "0.178 mm", .meaning = "across the race (the contact's track must lie within it)"},
    {.section = "*_ring.spall", .key = "depth", .kind = number, .field = FIELD(ring->spall.depth), .dim = dim::length,
     .bounds = kSpallSize, .example = "0.28 mm",
     .meaning = "depth; a ball drops at most r - sqrt(r^2 - (length/2)^2) into it"},
    {.section = "*_ring.spall", .key = "edge", .kind = choice, .field = FIELD(ring->spall.edge), .def = word("sharp"),
     .options = kSpallEdges, .noun = "spall edge",
     .meaning = "sharp: the ball pivots on the edges; smooth: a raised cosine to the same deepest drop"},
    {.section = "*_ring.waviness", .key = "orders", .kind = integer_list, .field = FIELD(ring->waviness.orders),
     .bounds = {.lo = 1, .hi = 1000}, .example = "[9, 10]", .meaning = "lobes round the race, one per term"},
    {.section = "*_ring.waviness", .key = "amplitudes", .kind = number_list,
     .field = FIELD(ring->waviness.amplitudes), .dim = dim::length, .bounds = kWavinessAmplitude,
     .example = "[\"1 um\", \"0.5 um\"]", .meaning = "radius deviation of each term"},
    {.section = "*_ring.waviness", .key = "phases", .kind = number_list, .field = FIELD(ring->waviness.phases),
     .dim = dim::angle, .def = absent, .example = "[\"0 deg\", \"90 deg\"]", .meaning = "of each term; absent: all 0"},

    // ---- [*_ring.misalignment] ------------------------------------------------------------------
    {.section = "*_ring.misalignment", .key = "x", .kind = time_function, .field = FIELD(ring->misalignment_x),
     .dim = dim::angle, .bounds = kMisalignment, .def = value(0), .example = "1.42 mrad",
     .meaning = "rotation about x"},
    {.section = "*_ring.misalignment", .key = "y", .kind = time_function, .field = FIELD(ring->misalignment_y),
     .dim = dim::angle, .bounds = kMisalignment, .def = value(0), .example = "1.42 mrad",
     .meaning = "rotation about y"},

    // ---- [*_ring.load]: loads that cannot act are rejected ---------------------------------------
    {.section = "*_ring.load", .key = "fx", .kind = time_function, .field = FIELD(ring->load.fx), .dim = dim::force,
     .def = value(0), .when = force_needs_free_centre, .otherwise = 0, .meaning = "force along x"},
    {.section = "*_ring.load", .key = "fy", .kind = time_function, .field = FIELD(ring->load.fy), .dim = dim::force,
     .def = value(0), .when = force_needs_free_centre, .otherwise = 0, .meaning = "force along y"},
    {.section = "*_ring.load", .key = "fz", .kind = time_function, .field = FIELD(ring->load.fz), .dim = dim::force,
     .def = value(0), .bearings = spatial_bearings, .elsewhere = kSpatialDirection,
     .when = axial_force_needs_axially_free, .then = axial_load_carried_by_ribs, .otherwise = 0,
     .meaning = "axial force along z (spatial roller bearings: one their ribs carry)"},
    {.section = "*_ring.load", .key = "mx", .kind = time_function, .field = FIELD(ring->load.mx), .dim = dim::moment,
     .def = value(0), .bearings = spatial_bearings, .elsewhere = kSpatialDirection,
     .when = tilting_moment_needs_free_tilt, .otherwise = 0, .meaning = "tilting moment about x (tilt = \"free\")"},
    {.section = "*_ring.load", .key = "my", .kind = time_function, .field = FIELD(ring->load.my), .dim = dim::moment,
     .def = value(0), .bearings = spatial_bearings, .elsewhere = kSpatialDirection,
     .when = tilting_moment_needs_free_tilt, .otherwise = 0, .meaning = "tilting moment about y (tilt = \"free\")"},
    {.section = "*_ring.load", .key = "mz", .kind = time_function, .field = FIELD(ring->load.mz), .dim = dim::moment,
     .def = value(0), .when = moment_needs_free_ring, .otherwise = 0,
     .meaning = "moment about the axis (motion = \"free\")"},

    // ---- [*_ring.support]: directions the ring cannot move in are rejected -----------------------
    {.section = "*_ring.support", .key = "stiffness", .kind = number, .field = FIELD(ring->support.stiffness),
     .dim = dim::stiffness, .bounds = positive,
     .def = derived(ring_support_stiffness_default, "required (planar); 0 (spatial)"),
     .when = radial_support_needs_free_centre, .meaning = "radial, in x and y"},
    {.section = "*_ring.support", .key = "damping", .kind = number, .field = FIELD(ring->support.damping),
     .dim = dim::damping, .bounds = non_negative, .def = value(0), .when = radial_support_needs_free_centre,
     .then = damper_has_spring, .meaning = "radial, in x and y"},
    {.section = "*_ring.support", .key = "axial_stiffness", .kind = number,
     .field = FIELD(ring->support.axial_stiffness), .dim = dim::stiffness, .bounds = positive, .def = value(0),
     .bearings = spatial_bearings, .elsewhere = kSpatialDirection, .when = axial_support_needs_axially_free,
     .meaning = "along z"},
    {.section = "*_ring.support", .key = "axial_damping", .kind = number, .field = FIELD(ring->support.axial_damping),
     .dim = dim::damping, .bounds = non_negative, .def = value(0), .bearings = spatial_bearings,
     .elsewhere = kSpatialDirection, .when = axial_support_needs_axially_free, .then = damper_has_spring,
     .meaning = "along z"},
    {.section = "*_ring.support", .key = "tilt_stiffness", .kind = number,
     .field = FIELD(ring->support.tilt_stiffness), .dim = dim::angular_stiffness, .bounds = positive,
     .def = value(0), .bearings = spatial_bearings, .elsewhere = kSpatialDirection,
     .when = tilt_support_needs_free_tilt, .meaning = "about x and y (tilt = \"free\")"},
    {.section = "*_ring.support", .key = "tilt_damping", .kind = number, .field = FIELD(ring->support.tilt_damping),
     .dim = dim::angular_damping, .bounds = non_negative, .def = value(0), .bearings = spatial_bearings,
     .elsewhere = kSpatialDirection, .when = tilt_support_needs_free_tilt, .then = damper_has_spring,
     .meaning = "about x and y (tilt = \"free\")"},

    // ---- [carrier]: optional; the bearing on a rotating planet carrier (seed 003 eq. 1-6) ------
    {.section = "carrier", .key = "radius", .kind = number, .field = FIELD(scene.carrier.radius), .dim = dim::length,
     .bounds = positive, .bearings = planar_rollers, .elsewhere = kPlanarCarrier, .then = carrier_without_gravity,
     .example = "100 mm",
     .meaning = "R_c: distance from the sun (carrier) axis to the bearing axis, which lies on the carrier's +x"},
    {.section = "carrier", .key = "speed", .kind = time_function, .field = FIELD(scene.carrier.speed),
     .dim = dim::angular_speed, .bearings = planar_rollers, .elsewhere = kPlanarCarrier, .example = "3000 rpm",
     .meaning = "the carrier's speed about z; ring speeds and loads are in the bearing frame, which turns with it"},

    // ---- [housing]: optional; the fixed outer ring in a housing on a pedestal (ball bearings) ---
    {.section = "housing", .key = "mass", .kind = number, .field = FIELD(scene.housing.mass), .dim = dim::mass,
     .bounds = positive, .bearings = ball_bearings, .elsewhere = kBallOnly, .when = housing_holds_fixed_outer_ring,
     .meaning = "the housing's mass (the outer ring's is added: they move together in x and y)"},
    {.section = "housing", .key = "stiffness", .kind = number, .field = FIELD(scene.housing.stiffness),
     .dim = dim::stiffness, .bounds = positive, .bearings = ball_bearings, .elsewhere = kBallOnly,
     .when = housing_holds_fixed_outer_ring, .meaning = "radial, in x and y, to ground"},
    {.section = "housing", .key = "damping", .kind = number, .field = FIELD(scene.housing.damping),
     .dim = dim::damping, .bounds = non_negative, .def = value(0), .bearings = ball_bearings, .elsewhere = kBallOnly,
     .when = housing_holds_fixed_outer_ring, .meaning = "radial, in x and y, to ground"},
    {.section = "housing", .key = "sensor_interval", .kind = number, .field = FIELD(scene.housing.sensor_interval),
     .dim = dim::time, .bounds = positive, .bearings = ball_bearings, .elsewhere = kBallOnly,
     .when = housing_holds_fixed_outer_ring, .then = sensor_interval_within_output, .example = "20 us",
     .meaning = "time between the sensor's samples (displacement, velocity, acceleration of the housing)"},

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
    {.section = "solver", .key = "stability_limit_detection", .kind = boolean,
     .field = FIELD(scene.solver.stability_limit_detection), .def = value(0), .when = bdf_only, .otherwise = 0,
     .meaning = "CVODE's BDF stability-limit detection: lowers the order where order 3 to 5 is unstable"},
    {.section = "solver", .key = "pocket_tolerance_factor", .kind = number,
     .field = FIELD(scene.solver.pocket_tolerance_factor), .dim = dim::none, .bounds = {.lo = 1, .hi = 1e6},
     .def = value(1),
     .meaning = "while a rolling element touches its cage pocket (or is within 1e-4 of its radius of it), the "
                "tolerances of its states and the cage's are this many times tighter (a pocket contact's approach, "
                "nanometres, lies far below rtol times the pitch radius); 1: off"},
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

constexpr std::string_view kTopSections[] = {"scene",   "bearing", "materials", "cage",    "inner_ring", "outer_ring", "housing",
                                             "carrier", "lubricant", "life",    "contact", "solver",     "output"};

}  // namespace

std::string_view option_name(std::span<const Option> options, int value) {
  for (const Option& o : options)
    if (o.value == value) return o.name;
  return "";
}

std::span<const Row> scene_rows() { return kRows; }

std::span<const Row> rows_of(std::string_view section) {
  const std::span<const Row> all = kRows;
  const auto first = std::find_if(all.begin(), all.end(), [&](const Row& r) { return r.section == section; });
  const auto last = std::find_if(first, all.end(), [&](const Row& r) { return r.section != section; });
  return {first, last};
}

std::span<const std::string_view> top_sections() { return kTopSections; }

}  // namespace raceway::scene::schema
