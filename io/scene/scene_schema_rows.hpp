// What the two halves of the scene schema table share (internal to io/scene): the reasons a key is
// rejected where the bearing or contact does not take it, the bounds several rows use, and FIELD.
// The table is in two files to keep each readable: scene_schema.cpp holds the bearing and its parts
// ([scene] to [*_ring.support]), scene_schema_run.cpp the rest ([carrier] to [output]).
#pragma once

#include <numbers>
#include <span>
#include <string_view>

#include "io/scene/scene_schema.hpp"

namespace raceway::scene::schema::table {

/// Where a row's value goes, as a path from the Bind: FIELD(scene.bearing.pitch_diameter).
#define FIELD(path) [](Bind& b) -> Field { return &b.path; }

/// Tables: an absent one is read as empty, every key at its default.
inline constexpr Default empty_table = value(0);

// Why a key is rejected where the bearing or contact does not take it.
inline constexpr std::string_view kBallOnly =
    "only for ball bearings (type = \"deep_groove_ball\", \"four_point_contact_ball\" or \"angular_contact_ball\")";
inline constexpr std::string_view kRollerOnly =
    "only for roller bearings (type = \"cylindrical_roller\" or \"tapered_roller\"); a ball bearing's is "
    "ball_diameter_scatter or ball_diameter_deviations";
inline constexpr std::string_view kSpatialOnlyDefect =
    "only for spatial scenes (ball bearings, or roller bearings with model = \"spatial\"): a planar roller's line "
    "contact has no place across the race for a defect";
inline constexpr std::string_view kSpatialOnlyElementDefect =
    "only for spatial scenes (ball bearings, or roller bearings with model = \"spatial\"): a planar roller has no "
    "angle about its own axis to carry a defect round";
inline constexpr std::string_view kSpatialOnlyHousing =
    "only for spatial scenes (ball bearings, or roller bearings with model = \"spatial\")";
inline constexpr std::string_view kSpatialCage =
    "only for ball bearings (model = \"spatial\"): a planar cage moves in x, y and about z, and a spatial roller "
    "bearing's cage takes its section from the rollers as the planar one does";
inline constexpr std::string_view kRollerCage =
    "only for planar roller bearings: the bars between a roller cage's pockets, flexible in the plane (a ball "
    "cage's pockets are drilled; a spatial roller cage's bars are rigid)";
inline constexpr std::string_view kSpatialRing =
    "only for spatial scenes (model = \"spatial\"): a planar ring moves in x, y and about z";
inline constexpr std::string_view kSpatialDirection =
    "only for spatial scenes (model = \"spatial\"): a planar model has no axial direction and no tilt";
inline constexpr std::string_view kRollerContact =
    "roller-race and roller-cage contacts belong to roller bearings; a ball bearing's are [contact.ball_race] and "
    "[contact.ball_cage]";
inline constexpr std::string_view kFlangeContact =
    "roller-end on rib contacts belong to spatial roller bearings (model = \"spatial\"): a planar roller has no "
    "axial direction";
inline constexpr std::string_view kBallContact =
    "ball-race and ball-cage contacts belong to ball bearings; a roller bearing's are [contact.roller_race], "
    "[contact.roller_cage] (and, spatial, [contact.roller_flange])";
inline constexpr std::string_view kLineContact =
    "slices and crown_drop are for line contacts (roller bearings); a ball contact is a Hertz point contact";
inline constexpr std::string_view kElementVelocityFrame =
    "only for ball bearings and planar roller bearings: a spatial roller's velocity states stay in the bearing frame";
inline constexpr std::string_view kBallRaceContact =
    "only for [contact.ball_race], the ball-groove point contacts: the other contacts' friction is a traction curve "
    "at the contact centre";

inline constexpr std::string_view kSpatialRoller =
    "only for cylindrical roller bearings in the spatial model (model = \"spatial\"): the planar model's rollers have "
    "no profile, ends or ribs";
inline constexpr std::string_view kTaperedOnly =
    "only for tapered roller bearings (type = \"tapered_roller\", model = \"spatial\")";
inline constexpr Bounds kCupAngle{.lo = 5 * std::numbers::pi / 180, .hi = 35 * std::numbers::pi / 180, .unit = "deg",
                                  .note = " (tapered roller bearings are made with cup angles of about 10 to 30 deg)"};
inline constexpr Bounds kRibAngle{.lo = 0, .hi = std::numbers::pi / 18, .hi_open = true, .unit = "deg",
                           .note = " (ribs open by a fraction of a degree to a few degrees)"};

inline constexpr std::string_view kPlanarCarrier =
    "only for planar roller bearings (model = \"planar\"): the carrier's frame terms act in the bearing's plane";

inline constexpr std::string_view kPlanarRim =
    "only for planar roller bearings (model = \"planar\"): the rim's in-plane bending modes";

inline constexpr std::string_view kMaxOrderText = "5 (bdf), 12 (adams), 8 (erk), 5 (ark)";
inline constexpr std::string_view kMaxOrderDefaultText = "5 (bdf), 12 (adams), 5 (erk), 4 (ark)";

inline constexpr Bounds kConformity{.lo = 0.5, .hi = 0.6, .lo_open = true,
                             .note = " (conformity = groove radius / ball diameter: the groove radius must exceed the "
                                     "ball radius; ball bearing grooves are 0.505 to 0.58)"};
inline constexpr Bounds kArcAngle{.lo = 0, .hi = std::numbers::pi / 3, .lo_open = true, .hi_open = true, .unit = "deg"};
inline constexpr std::string_view kContactAngleMissing =
    "required for type = \"angular_contact_ball\": its free contact angle, e.g. \"40 deg\" (or give the groove "
    "geometry's radial_clearance, from which it follows)";
inline constexpr Bounds kFreeContactAngle{.lo = 0, .hi = std::numbers::pi / 3, .lo_open = true, .hi_open = true, .unit = "deg",
                                   .note = " (angular contact bearings are made with 15 to 40 deg)"};
inline constexpr Bounds kAxialPosition{.lo = -1e-3, .hi = 1e-3, .unit = "um",
                                .note = " (preload displacements are micrometres to some tens of them)"};
inline constexpr Bounds kMisalignment{.lo = -0.05, .hi = 0.05, .unit = "mrad",
                               .note = " (a sanity limit: ball bearings run at a few mrad)"};

// The scatter of the balls' diameters and the pockets' clearances (a sanity limit: ISO 3290 ball
// grades hold a lot's diameter variation to a fraction of a micrometre up to a few).
inline constexpr Bounds kScatter{.lo = 0, .hi = 20e-6, .unit = "um",
                          .note = " (a sanity limit: ground balls and pockets scatter by micrometres)"};
inline constexpr Bounds kScatterDeviation{.lo = -20e-6, .hi = 20e-6, .unit = "um",
                                   .note = " (a sanity limit: ground balls and pockets scatter by micrometres)"};
inline constexpr Bounds kMassEccentricity{.lo = 0, .hi = 1e-3, .unit = "um",
                                   .note = " (machined cages are balanced to some micrometres; 1 mm is a sanity limit)"};

// The unbalance's direction in the cage frame: one turn either way is every direction.
inline constexpr Bounds kUnbalanceAngle{.lo = -2 * std::numbers::pi, .hi = 2 * std::numbers::pi, .unit = "deg",
                                  .note = " (one turn either way holds every direction)"};
inline constexpr Bounds kSpallAngle{.lo = -2 * std::numbers::pi, .hi = 2 * std::numbers::pi, .unit = "deg"};
inline constexpr Bounds kSpallSize{.lo = 0, .hi = 0.01, .lo_open = true, .unit = "mm",
                            .note = " (a spall is a fraction of a millimetre to some millimetres)"};
inline constexpr Bounds kWavinessAmplitude{.lo = 0, .hi = 1e-4, .unit = "um",
                                    .note = " (waviness is some tenths of a micrometre to some micrometres)"};

/// A rolling element's index: 0 to rolling_elements - 1.
inline long last_element_index(const Bind& b) { return b.scene.bearing.rolling_elements - 1; }
inline constexpr Bounds kElementIndex{.lo = 0, .hi_of = last_element_index, .hi_text = "rolling_elements - 1"};

/// The rows of [scene] to [*_ring.support], then those of [carrier] to [output], in reading order.
std::span<const Row> bearing_rows();
std::span<const Row> run_rows();

}  // namespace raceway::scene::schema::table
