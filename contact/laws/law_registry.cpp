// The table of contact laws (law_registry.hpp). Implementations: line_contact.hpp (palmgren, the
// tanh traction curve and Hunt-Crossley damping of line contacts), point_contact.hpp (hertz,
// limiting-shear traction, and the same damping and curve for point contacts), lubricated_line_contact.hpp
// (moes_ehd, ehd, hydrodynamic), short_bearing_film.hpp (short_bearing), pocket_film.hpp (pocket_film).
#include "contact/laws/law_registry.hpp"

#include <array>

namespace raceway::contact {

namespace {

constexpr LawEntry kLaws[] = {
    {LawRole::normal, LawId::palmgren, "palmgren", line_contacts,
     "Palmgren line contact: Q = K delta^(10/9), per slice of a crowned roller"},
    {LawRole::normal, LawId::hertz, "hertz", point_contacts,
     "Hertz point contact: Q = K delta^1.5, K from the exact ellipticity of the contact"},
    {LawRole::damping, LawId::hunt_crossley, "hunt_crossley", all_contacts,
     "Hunt-Crossley: F = F_elastic (1 + damping_factor * d(delta)/dt), continuous at first touch"},
    {LawRole::damping, LawId::no_damping, "none", all_contacts, "no damping: the elastic force only"},
    {LawRole::traction, LawId::tanh_traction, "tanh", all_contacts,
     "friction curve mu = friction_coefficient * tanh(u / slip_velocity_scale), smooth through zero slip"},
    {LawRole::traction, LawId::no_traction, "none", all_contacts, "no traction: frictionless contact"},
    {LawRole::traction, LawId::limiting_shear, "limiting_shear", ball_race_contact,
     "lubricated traction: Barus viscosity and a limiting shear stress over the contact ellipse (needs "
     "[lubricant] viscosity and limiting_shear_coefficient); the tanh curve where there is no film"},
    {LawRole::normal, LawId::moes_ehd, "moes_ehd", roller_race_contact,
     "EHD line contact (seed 003 eq. 8-9): Palmgren's law carrying a Moes film (Martin's rigid-isoviscous "
     "constant), fully flooded up to a gap of 2 % of the roller radius; spatial cylindrical roller bearings: "
     "each race slice a film of its width (needs [lubricant] viscosity)"},
    {LawRole::traction, LawId::ehd_traction, "ehd", roller_race_contact,
     "EHD traction (seed 003 eq. 10): Couette friction linear in the slide-to-roll ratio up to "
     "friction_coefficient (saturating at 5 %; slip_velocity_scale keeps it finite at rest) and the Poiseuille "
     "rolling force (needs normal = \"moes_ehd\")"},
    {LawRole::normal, LawId::hydrodynamic, "hydrodynamic", roller_cage_contact,
     "hydrodynamic film (seed 003 2.2.1): rigid roller on a flat bar, rolling and squeeze film up to a gap of 2 % "
     "of the roller radius, the dry Palmgren law once the film collapses to 0.2 um; viscous Couette drag (needs "
     "[lubricant] viscosity)"},
    {LawRole::normal, LawId::short_bearing, "short_bearing", cage_land_contact,
     "short journal-bearing film of the cage on its land (Ocvirk: rolling and squeeze together, half-Sommerfeld "
     "cavitation; a ball bearing's station by station), the dry Palmgren law once the film collapses to 0.2 um (needs "
     "[lubricant] viscosity)"},
    {LawRole::normal, LawId::pocket_film, "pocket_film", ball_cage_contact,
     "Reynolds film of the ball in its cylindrical pocket (rolling, sliding and squeeze together, Reynolds' "
     "cavitation, in narrow strips around the pocket) with the Couette shear of a flooded pocket, the dry Hertz law "
     "once the film collapses to 0.2 um (cylindrical pockets; needs [lubricant] viscosity)"},
};

constexpr std::array<ContactKindBit, 6> kContacts = {roller_race_contact, roller_cage_contact, ball_race_contact,
                                                     ball_cage_contact,   cage_land_contact,   roller_flange_contact};
constexpr std::array<std::string_view, 6> kContactNames = {"roller_race", "roller_cage", "ball_race",
                                                           "ball_cage",   "cage_land",   "roller_flange"};

std::string names_of(unsigned contacts) {
  std::string s;
  for (std::size_t i = 0; i < kContacts.size(); ++i)
    if (contacts & kContacts[i]) s += (s.empty() ? "" : ", ") + std::string(kContactNames[i]);
  return s;
}

}  // namespace

std::span<const LawEntry> registered_laws() { return kLaws; }

const LawEntry* find_law(LawRole role, std::string_view name, ContactKindBit contact) {
  const LawEntry* law = find_law(role, name);
  return law && (law->contacts & contact) ? law : nullptr;
}

const LawEntry* find_law(LawRole role, std::string_view name) {
  for (const LawEntry& law : kLaws)
    if (law.role == role && law.name == name) return &law;
  return nullptr;
}

const LawEntry& law_entry(LawId id) {
  for (const LawEntry& law : kLaws)
    if (law.id == id) return law;
  return kLaws[0];  // unreachable: every LawId has a row
}

const LawEntry& default_law(LawRole role, ContactKindBit contact) {
  for (const LawEntry& law : kLaws)
    if (law.role == role && (law.contacts & contact)) return law;
  return kLaws[0];  // unreachable: every contact accepts a law of every role
}

std::string known_law_names(LawRole role, ContactKindBit contact) {
  std::string s;
  for (const LawEntry& law : kLaws)
    if (law.role == role && (law.contacts & contact)) s += (s.empty() ? "" : ", ") + std::string(law.name);
  return s;
}

std::string_view role_name(LawRole role) {
  switch (role) {
    case LawRole::normal: return "normal";
    case LawRole::damping: return "damping";
    case LawRole::traction: return "traction";
  }
  return "";
}

std::span<const ContactKindBit> contact_kinds() { return kContacts; }

std::string_view contact_name(ContactKindBit contact) {
  for (std::size_t i = 0; i < kContacts.size(); ++i)
    if (kContacts[i] == contact) return kContactNames[i];
  return "";
}

std::string contacts_description(unsigned contacts) {
  if (contacts == line_contacts) return "line contacts (" + names_of(contacts) + ")";
  if (contacts == point_contacts) return "point contacts (" + names_of(contacts) + ")";
  if (contacts == all_contacts) return "all contacts";
  return names_of(contacts) + " contacts";
}

}  // namespace raceway::contact
