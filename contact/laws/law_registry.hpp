// The registry of contact laws: the only place their names live. A scene names a law per role
// (normal, damping, traction) and contact kind; the parser looks the name up here (an unknown
// name is an error listing the known ones for that contact), stores the law's id, and the model
// builders build from the id. Adding a law: one row in the table (law_registry.cpp) and its
// implementation in contact/laws; nothing else compares names.
#pragma once

#include <span>
#include <string>
#include <string_view>

namespace raceway::contact {

/// What part of a contact a law describes.
enum class LawRole { normal, damping, traction };

/// Every law raceway knows.
enum class LawId {
  palmgren,       ///< normal, line contact: Q = K delta^(10/9) (per slice)
  hertz,          ///< normal, point contact: Q = K delta^1.5, K from the exact ellipticity
  hunt_crossley,  ///< damping: F = F_el (1 + factor * d(delta)/dt), continuous at onset
  no_damping,     ///< damping: none
  tanh_traction,  ///< traction: mu = mu_max tanh(u / u_s), smooth through zero slip
  no_traction,    ///< traction: none
  limiting_shear,  ///< traction, lubricated point contacts: Barus viscosity, limiting shear stress
  moes_ehd,        ///< normal, roller-race: Palmgren carrying a Moes EHD film (seed 003 eq. 8-9)
  ehd_traction,    ///< traction, roller-race EHD film: Couette and Poiseuille (seed 003 eq. 10)
  hydrodynamic,    ///< normal, roller-cage: rigid film with squeeze, dry Palmgren once it collapses
  short_bearing,   ///< normal, ball-bearing cage land: short journal-bearing film, dry Palmgren once it collapses
  pocket_film      ///< normal, ball in a cylindrical pocket: Reynolds film in narrow strips, dry Hertz once it collapses
};

/// The contacts of a scene, as bits: a law lists the ones it applies to.
enum ContactKindBit : unsigned {
  roller_race_contact = 1u << 0,  ///< [contact.roller_race]
  roller_cage_contact = 1u << 1,  ///< [contact.roller_cage]
  ball_race_contact = 1u << 2,    ///< [contact.ball_race]
  ball_cage_contact = 1u << 3,    ///< [contact.ball_cage]
  cage_land_contact = 1u << 4,    ///< [contact.cage_land]
  roller_flange_contact = 1u << 5,  ///< [contact.roller_flange]: a roller's end on a rib (spatial roller bearings)
};
/// Line contacts (rollers on races and cage bars, the cage on its land) and point contacts (balls,
/// and a roller's end on a rib: a Hertz point, contact/segments/roller_flange_segment.hpp).
inline constexpr unsigned line_contacts = roller_race_contact | roller_cage_contact | cage_land_contact;
inline constexpr unsigned point_contacts = ball_race_contact | ball_cage_contact | roller_flange_contact;
inline constexpr unsigned all_contacts = line_contacts | point_contacts;

struct LawEntry {
  LawRole role;
  LawId id;
  std::string_view name;     ///< the scene's spelling
  unsigned contacts;         ///< ContactKindBit mask of the contacts that accept it
  std::string_view meaning;  ///< one line, for errors, `raceway check` and docs
};

/// All registered laws, in a fixed order. The first law of a role that a contact accepts is that
/// contact's default.
std::span<const LawEntry> registered_laws();
/// The law of `role` called `name` that `contact` accepts, or nullptr.
const LawEntry* find_law(LawRole role, std::string_view name, ContactKindBit contact);
/// The law of `role` called `name`, whatever contacts accept it, or nullptr.
const LawEntry* find_law(LawRole role, std::string_view name);
/// The entry of a law id (always exists).
const LawEntry& law_entry(LawId id);
/// The default law of `role` for `contact`: the first registered one it accepts.
const LawEntry& default_law(LawRole role, ContactKindBit contact);
/// "a, b, c": the names of `role` that `contact` accepts, in registry order, for error messages.
std::string known_law_names(LawRole role, ContactKindBit contact);

/// "normal", "damping", "traction".
std::string_view role_name(LawRole role);
/// The six contacts, in the order of the ContactKindBit values.
std::span<const ContactKindBit> contact_kinds();
/// The scene's name of a contact: "roller_race", ..., "roller_flange" (its [contact.NAME] section).
std::string_view contact_name(ContactKindBit contact);
/// The contacts of a mask in words: "line contacts (roller_race, roller_cage, cage_land)",
/// "point contacts (ball_race, ball_cage, roller_flange)", "ball_race contacts".
std::string contacts_description(unsigned contacts);

}  // namespace raceway::contact
