// The scene schema table (scene_schema.hpp): every key of a scene file, in reading order. This
// file holds [scene] to [*_ring.support]; scene_schema_run.cpp the rest.
#include "io/scene/scene_schema.hpp"

#include <algorithm>
#include <vector>

#include "io/scene/scene_rules.hpp"
#include "io/scene/scene_schema_rows.hpp"

namespace raceway::scene::schema {

namespace table {
namespace {

using contact::LawRole;
using enum ValueKind;
using namespace rules;

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
     .meaning = "a catalogue bearing (docs/catalogue.md: 60, 62, 63, 72..B, QJ2.., NU, NJ, NUP, 302, 322 series): fills every key of "
                "[bearing] and [cage], the model and first-scene defaults that the scene does not give; `raceway "
                "check` lists them"},
    {.section = "bearing", .key = "type", .kind = choice, .field = FIELD(scene.bearing.type),
     .then = model_fits_bearing_type, .options = kBearingTypes, .noun = "bearing type",
     .meaning = "cylindrical_roller: model = \"planar\" or \"spatial\"; tapered_roller and the ball bearings need model = "
                "\"spatial\""},
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
    {.section = "bearing", .key = "cup_angle", .kind = number, .field = FIELD(scene.bearing.roller.cup_angle),
     .dim = dim::angle, .bounds = kCupAngle, .bearings = spatial_rollers, .elsewhere = kTaperedOnly,
     .when = tapered_only,
     .missing = "required for type = \"tapered_roller\": the cup raceway's angle to the axis, e.g. \"14 deg\"",
     .then = cup_angle_fits, .example = "14 deg",
     .meaning = "tapered roller bearings: the cup (outer) raceway's angle alpha to the axis (the catalogue's contact "
                "angle); roller_diameter is the roller's diameter at its middle, pitch_diameter there; the roller's "
                "and the cone's angles follow so that the apexes meet on the axis"},
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
    {.section = "bearing", .key = "scatter_seed", .kind = integer, .field = FIELD(scene.bearing.scatter_seed),
     .bounds = {.lo = 0, .hi = 4294967295.0}, .def = value(1),
     .meaning = "seed of the drawn scatter (ball_diameter_scatter, roller_diameter_scatter, [cage] "
                "pocket_clearance_scatter): one seed draws the same values on every machine and rank count"},
    {.section = "bearing", .key = "ball_diameter_deviations", .kind = number_list,
     .field = FIELD(scene.bearing.ball_diameter_deviations), .dim = dim::length, .bounds = kScatterDeviation,
     .def = absent, .bearings = ball_bearings, .elsewhere = kBallOnly, .then = ball_deviations_per_ball,
     .example = "[\"0.5 um\", \"-0.2 um\", ...]",
     .meaning = "each ball's diameter minus ball_diameter, one per ball (ball[0] first; docs/vibration.md)"},
    {.section = "bearing", .key = "ball_diameter_scatter", .kind = number,
     .field = FIELD(scene.bearing.ball_diameter_scatter), .dim = dim::length, .bounds = kScatter,
     .def = value(0), .bearings = ball_bearings, .elsewhere = kBallOnly, .then = ball_diameters_drawn,
     .meaning = "standard deviation of the balls' diameters about ball_diameter, drawn with scatter_seed (0: every ball "
                "nominal; not with ball_diameter_deviations)"},
    {.section = "bearing", .key = "roller_diameter_deviations", .kind = number_list,
     .field = FIELD(scene.bearing.roller_diameter_deviations), .dim = dim::length, .bounds = kScatterDeviation,
     .def = absent, .bearings = roller_bearings, .elsewhere = kRollerOnly, .then = roller_deviations_per_roller,
     .example = "[\"0.5 um\", \"-0.2 um\", ...]",
     .meaning = "each roller's diameter minus roller_diameter (a tapered roller's at every section), one per roller "
                "(roller[0] first; docs/vibration.md)"},
    {.section = "bearing", .key = "roller_diameter_scatter", .kind = number,
     .field = FIELD(scene.bearing.roller_diameter_scatter), .dim = dim::length, .bounds = kScatter,
     .def = value(0), .bearings = roller_bearings, .elsewhere = kRollerOnly, .then = roller_diameters_drawn,
     .meaning = "standard deviation of the rollers' diameters about roller_diameter, drawn with scatter_seed (0: every "
                "roller nominal; not with roller_diameter_deviations)"},

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
    {.section = "cage", .key = "pocket_clearance_deviations", .kind = number_list,
     .field = FIELD(scene.cage.pocket_clearance_deviations), .dim = dim::length, .bounds = kScatterDeviation,
     .def = absent, .bearings = ball_bearings, .elsewhere = kBallOnly, .then = pocket_deviations_per_pocket,
     .example = "[\"5 um\", \"-3 um\", ...]",
     .meaning = "each pocket's clearance minus pocket_clearance, one per pocket (pocket k holds ball[k])"},
    {.section = "cage", .key = "pocket_clearance_scatter", .kind = number,
     .field = FIELD(scene.cage.pocket_clearance_scatter), .dim = dim::length, .bounds = kScatter, .def = value(0),
     .bearings = ball_bearings, .elsewhere = kBallOnly, .then = pocket_clearances_drawn,
     .meaning = "standard deviation of the pockets' clearances about pocket_clearance, drawn with [bearing] "
                "scatter_seed (0: every pocket nominal; not with pocket_clearance_deviations)"},
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
                                         "from the section (clamped beam, load along its length: 720 E I / L^3, "
                                         "with shear by bridge_theory)"},
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
    {.section = "cage", .key = "bridge_theory", .kind = choice, .field = FIELD(scene.cage.bridge_theory),
     .def = word("timoshenko"), .bearings = planar_rollers, .elsewhere = kRollerCage, .options = kBeamTheories,
     .noun = "bridge theory",
     .meaning = "flexible bridges: timoshenko (bending and shear, Cowper's shear coefficient: a stubby bar) or "
                "euler_bernoulli (bending only: a slender bar)"},
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
                "frame's x turned by cage.mass_eccentricity_angle: its centrifugal force turns with the cage"},
    {.section = "cage", .key = "mass_eccentricity_angle", .kind = number,
     .field = FIELD(scene.cage.mass_eccentricity_angle), .dim = dim::angle, .bounds = kUnbalanceAngle, .def = value(0),
     .bearings = ball_bearings, .elsewhere = kSpatialCage, .example = "90 deg",
     .meaning = "the unbalance's phase: the angle from the cage frame's x towards its y at which the centre of mass "
                "lies (cage.mass_eccentricity); one unbalance at several phases: its realisations"},
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
    {.section = "*_ring", .key = "rim_theory", .kind = choice, .field = FIELD(ring->rim_theory),
     .def = word("timoshenko"), .bearings = planar_rollers, .elsewhere = kPlanarRim, .when = ring_modes_only,
     .options = kBeamTheories, .noun = "rim theory",
     .meaning = "flexibility = \"ring_modes\": timoshenko (a thick ring: bending, extension and shear; modes n = "
                "0, 1, 2..modes) or euler_bernoulli (a thin inextensional ring: bending modes n = 2..modes)"},

    {.section = "*_ring", .key = "spall", .kind = table, .field = nullptr, .def = absent, .bearings = spatial_bearings,
     .elsewhere = kSpatialOnlyDefect, .then = spall_given, .sub = "*_ring.spall",
     .meaning = "a localized defect (spall) on the ring's race (docs/vibration.md)"},
    {.section = "*_ring", .key = "waviness", .kind = table, .field = nullptr, .def = absent, .bearings = spatial_bearings,
     .elsewhere = kSpatialOnlyDefect, .then = waviness_lists_match, .sub = "*_ring.waviness",
     .meaning = "the race's waviness: radius deviation sum A_k cos(n_k theta + phase_k) (docs/vibration.md)"},

    // ---- [*_ring.spall] and [*_ring.waviness]: the race's imperfections (spatial scenes) --------
    {.section = "*_ring.spall", .key = "angle", .kind = number, .field = FIELD(ring->spall.angle), .dim = dim::angle,
     .bounds = kSpallAngle, .def = value(0), .example = "90 deg",
     .meaning = "the spall's centre about the ring axis, in the ring's frame (0: along x; the inner ring's turns)"},
    {.section = "*_ring.spall", .key = "length", .kind = number, .field = FIELD(ring->spall.length),
     .dim = dim::length, .bounds = kSpallSize, .example = "0.178 mm", .meaning = "along the race"},
    {.section = "*_ring.spall", .key = "width", .kind = number, .field = FIELD(ring->spall.width), .dim = dim::length,
     .bounds = kSpallSize, .example = "0.178 mm", .meaning = "across the race, centred on its middle (a ball's contact track must lie within it; a roller's "
                "slices within it drop into it)"},
    {.section = "*_ring.spall", .key = "depth", .kind = number, .field = FIELD(ring->spall.depth), .dim = dim::length,
     .bounds = kSpallSize, .example = "0.28 mm",
     .meaning = "depth; a ball or roller of radius r drops at most r - sqrt(r^2 - (length/2)^2) into it"},
    {.section = "*_ring.spall", .key = "edge", .kind = choice, .field = FIELD(ring->spall.edge), .def = word("sharp"),
     .options = kSpallEdges, .noun = "spall edge",
     .meaning = "sharp: the rolling element pivots on the edges; smooth: a raised cosine to the same deepest drop"},
    {.section = "*_ring.waviness", .key = "orders", .kind = integer_list, .field = FIELD(ring->waviness.orders),
     .bounds = {.lo = 1, .hi = 1000}, .example = "[9, 10]", .meaning = "lobes round the race, one per term"},
    {.section = "*_ring.waviness", .key = "amplitudes", .kind = number_list,
     .field = FIELD(ring->waviness.amplitudes), .dim = dim::length, .bounds = kWavinessAmplitude,
     .example = "[\"1 um\", \"0.5 um\"]", .meaning = "radius deviation of each term"},
    {.section = "*_ring.waviness", .key = "phases", .kind = number_list, .field = FIELD(ring->waviness.phases),
     .dim = dim::angle, .def = absent, .example = "[\"0 deg\", \"90 deg\"]", .meaning = "of each term; absent: all 0"},

    // ---- [rolling_element]: optional; a ball's or roller's own spall and waviness (spatial scenes)
    {.section = "rolling_element", .key = "spall", .kind = table, .field = nullptr, .def = absent,
     .bearings = spatial_bearings, .elsewhere = kSpatialOnlyElementDefect, .then = element_spall_given,
     .sub = "rolling_element.spall",
     .meaning = "a spall on one ball (round its equator) or roller (round its circumference); it turns with it "
                "(docs/vibration.md)"},
    {.section = "rolling_element", .key = "waviness", .kind = table, .field = nullptr, .def = absent,
     .bearings = spatial_bearings, .elsewhere = kSpatialOnlyElementDefect, .then = element_waviness_given,
     .sub = "rolling_element.waviness",
     .meaning = "one ball's waviness round its equator, or one roller's round its circumference: radius deviation "
                "sum A_k cos(n_k phi + phase_k)"},
    {.section = "rolling_element.spall", .key = "element", .kind = integer,
     .field = FIELD(scene.rolling_element.spall_element), .bounds = kElementIndex, .example = "0",
     .meaning = "the ball or roller that carries it: ball[element] or roller[element]"},
    {.section = "rolling_element.spall", .key = "angle", .kind = number,
     .field = FIELD(scene.rolling_element.spall.angle), .dim = dim::angle, .bounds = kSpallAngle, .def = value(0),
     .example = "90 deg",
     .meaning = "the spall's centre round the ball's equator or the roller's circumference, in its own frame (at "
                "the start the bearing's: 0 along x)"},
    {.section = "rolling_element.spall", .key = "length", .kind = number,
     .field = FIELD(scene.rolling_element.spall.length), .dim = dim::length, .bounds = kSpallSize,
     .example = "0.178 mm", .meaning = "along the equator (a roller: round its circumference)"},
    {.section = "rolling_element.spall", .key = "width", .kind = number,
     .field = FIELD(scene.rolling_element.spall.width), .dim = dim::length, .bounds = kSpallSize,
     .example = "0.178 mm",
     .meaning = "across the equator (the contacts' track must cross it); a roller: along its axis, centred on its "
                "middle (the race slices within it meet it)"},
    {.section = "rolling_element.spall", .key = "depth", .kind = number,
     .field = FIELD(scene.rolling_element.spall.depth), .dim = dim::length, .bounds = kSpallSize,
     .example = "0.28 mm", .meaning = "depth; a race reaches at most r - sqrt(r^2 - (length/2)^2) into it"},
    {.section = "rolling_element.spall", .key = "edge", .kind = choice,
     .field = FIELD(scene.rolling_element.spall.edge), .def = word("sharp"), .options = kSpallEdges,
     .noun = "spall edge", .meaning = "sharp: the race pivots on the edges; smooth: a raised cosine"},
    {.section = "rolling_element.waviness", .key = "element", .kind = integer,
     .field = FIELD(scene.rolling_element.waviness_element), .bounds = kElementIndex, .example = "0",
     .meaning = "the ball or roller that carries it: ball[element] or roller[element]"},
    {.section = "rolling_element.waviness", .key = "orders", .kind = integer_list,
     .field = FIELD(scene.rolling_element.waviness.orders), .bounds = {.lo = 1, .hi = 1000}, .example = "[2, 4]",
     .meaning = "lobes round the ball's equator, one per term"},
    {.section = "rolling_element.waviness", .key = "amplitudes", .kind = number_list,
     .field = FIELD(scene.rolling_element.waviness.amplitudes), .dim = dim::length, .bounds = kWavinessAmplitude,
     .example = "[\"0.5 um\", \"0.2 um\"]", .meaning = "radius deviation of each term"},
    {.section = "rolling_element.waviness", .key = "phases", .kind = number_list,
     .field = FIELD(scene.rolling_element.waviness.phases), .dim = dim::angle, .def = absent,
     .example = "[\"0 deg\", \"90 deg\"]", .meaning = "of each term; absent: all 0"},

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
};

}  // namespace

std::span<const Row> bearing_rows() { return kRows; }

}  // namespace table

namespace {

constexpr std::string_view kTopSections[] = {"scene",     "bearing",   "materials", "cage",    "inner_ring",
                                             "outer_ring", "rolling_element", "housing", "carrier", "lubricant",
                                             "thermal",   "life",      "contact",   "solver",  "output"};

}  // namespace

std::string_view option_name(std::span<const Option> options, int value) {
  for (const Option& o : options)
    if (o.value == value) return o.name;
  return "";
}

std::span<const Row> scene_rows() {
  static const std::vector<Row> rows = [] {
    std::vector<Row> all(table::bearing_rows().begin(), table::bearing_rows().end());
    all.insert(all.end(), table::run_rows().begin(), table::run_rows().end());
    return all;
  }();
  return rows;
}

std::span<const Row> rows_of(std::string_view section) {
  const std::span<const Row> all = scene_rows();
  const auto first = std::find_if(all.begin(), all.end(), [&](const Row& r) { return r.section == section; });
  const auto last = std::find_if(first, all.end(), [&](const Row& r) { return r.section != section; });
  return {first, last};
}

std::span<const std::string_view> top_sections() { return kTopSections; }

}  // namespace raceway::scene::schema
