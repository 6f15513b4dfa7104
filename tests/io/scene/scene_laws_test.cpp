// Contact laws: the registry (contact/laws/law_registry.hpp) accepts exactly the laws each contact
// takes, and the scene parser names laws only through it: an unknown or misplaced name is an error
// that lists the laws the contact knows, and an accepted one is stored as its id.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "contact/laws/law_registry.hpp"
#include "io/scene/scene_parser.hpp"
#include "tests/support/scene_test_util.hpp"

namespace raceway::scene {
namespace {

using namespace test;
using contact::ContactKindBit;
using contact::LawId;
using contact::LawRole;

struct Accepted {
  LawRole role;
  std::string_view name;
  LawId id;
  unsigned contacts;
};
constexpr unsigned kLine = contact::roller_race_contact | contact::roller_cage_contact | contact::cage_land_contact;
constexpr unsigned kPoint = contact::ball_race_contact | contact::ball_cage_contact | contact::roller_flange_contact;
constexpr unsigned kAll = kLine | kPoint;

/// kPlanarMinimal in the spatial model, its outer ring held axially.
std::string spatial_roller_minimal() {
  return replaced(replaced(kPlanarMinimal, "model = \"planar\"", "model = \"spatial\""), "translation = \"fixed\"",
                  "translation = \"fixed\"\naxial = \"fixed\"");
}

/// What each contact accepts today, written out independently of the registry's table.
constexpr Accepted kExpected[] = {
    {LawRole::normal, "palmgren", LawId::palmgren, kLine},
    {LawRole::normal, "hertz", LawId::hertz, kPoint},
    {LawRole::damping, "hunt_crossley", LawId::hunt_crossley, kAll},
    {LawRole::damping, "none", LawId::no_damping, kAll},
    {LawRole::traction, "tanh", LawId::tanh_traction, kAll},
    {LawRole::traction, "none", LawId::no_traction, kAll},
    {LawRole::traction, "limiting_shear", LawId::limiting_shear, contact::ball_race_contact},
    {LawRole::normal, "moes_ehd", LawId::moes_ehd, contact::roller_race_contact},
    {LawRole::traction, "ehd", LawId::ehd_traction, contact::roller_race_contact},
    {LawRole::normal, "hydrodynamic", LawId::hydrodynamic, contact::roller_cage_contact},
    {LawRole::normal, "short_bearing", LawId::short_bearing, contact::cage_land_contact},
    {LawRole::normal, "pocket_film", LawId::pocket_film, contact::ball_cage_contact},
};
constexpr LawRole kRoles[] = {LawRole::normal, LawRole::damping, LawRole::traction};

bool expected(LawRole role, std::string_view name, ContactKindBit contact) {
  for (const Accepted& a : kExpected)
    if (a.role == role && a.name == name) return (a.contacts & contact) != 0;
  return false;
}

TEST(LawRegistry, EachContactAcceptsExactlyTheListedLaws) {
  std::set<std::string_view> names = {"bogus", "", "Hertz", "palmgren "};
  for (const Accepted& a : kExpected) names.insert(a.name);
  ASSERT_EQ(contact::contact_kinds().size(), 6u);
  for (const ContactKindBit contact : contact::contact_kinds())
    for (const LawRole role : kRoles)
      for (const std::string_view name : names) {
        SCOPED_TRACE(std::string(contact::contact_name(contact)) + " " + std::string(contact::role_name(role)) + " '" +
                     std::string(name) + "'");
        const contact::LawEntry* law = contact::find_law(role, name, contact);
        EXPECT_EQ(law != nullptr, expected(role, name, contact));
        if (law) {
          EXPECT_EQ(law->name, name);
          EXPECT_EQ(law->role, role);
        }
      }
}

TEST(LawRegistry, IdsNamesAndDefaults) {
  EXPECT_EQ(contact::registered_laws().size(), std::size(kExpected));
  for (const Accepted& a : kExpected) {
    SCOPED_TRACE(std::string(a.name));
    const contact::LawEntry& entry = contact::law_entry(a.id);
    EXPECT_EQ(entry.id, a.id);
    EXPECT_EQ(entry.role, a.role);
    EXPECT_EQ(entry.name, a.name);
    EXPECT_EQ(entry.contacts, a.contacts);
    EXPECT_FALSE(entry.meaning.empty());
    EXPECT_EQ(contact::find_law(a.role, a.name), &entry);
  }
  EXPECT_EQ(contact::default_law(LawRole::normal, contact::roller_race_contact).id, LawId::palmgren);
  EXPECT_EQ(contact::default_law(LawRole::normal, contact::cage_land_contact).id, LawId::palmgren);
  EXPECT_EQ(contact::default_law(LawRole::normal, contact::ball_cage_contact).id, LawId::hertz);
  for (const ContactKindBit contact : contact::contact_kinds()) {
    EXPECT_EQ(contact::default_law(LawRole::damping, contact).id, LawId::hunt_crossley);
    EXPECT_EQ(contact::default_law(LawRole::traction, contact).id, LawId::tanh_traction);
  }
  EXPECT_EQ(contact::known_law_names(LawRole::traction, contact::ball_race_contact), "tanh, none, limiting_shear");
  EXPECT_EQ(contact::known_law_names(LawRole::traction, contact::ball_cage_contact), "tanh, none");
  EXPECT_EQ(contact::known_law_names(LawRole::normal, contact::roller_cage_contact), "palmgren, hydrodynamic");
  EXPECT_EQ(contact::known_law_names(LawRole::normal, contact::roller_flange_contact), "hertz");
  EXPECT_EQ(contact::known_law_names(LawRole::traction, contact::roller_flange_contact), "tanh, none");
  EXPECT_EQ(contact::default_law(LawRole::normal, contact::roller_flange_contact).id, LawId::hertz);
  EXPECT_EQ(contact::contact_name(contact::roller_flange_contact), "roller_flange");
  EXPECT_EQ(contact::contacts_description(kPoint), "point contacts (ball_race, ball_cage, roller_flange)");
  EXPECT_EQ(contact::contacts_description(kLine), "line contacts (roller_race, roller_cage, cage_land)");
  EXPECT_EQ(contact::contacts_description(contact::ball_race_contact), "ball_race contacts");
}

// ---- the laws through the scene parser ---------------------------------------------------------

/// A planar roller, spatial roller or spatial ball scene (with a lubricant that limiting-shear
/// traction and the film laws need) and one law set (EHD traction with the EHD film it needs).
std::string scene_with_law(ContactKindBit contact, LawRole role, std::string_view name) {
  const bool planar = contact == contact::roller_race_contact || contact == contact::roller_cage_contact;
  const std::string lubricant = "[lubricant]\nviscosity = \"30 mPa s\"\n";
  std::string base = planar ? std::string(kPlanarMinimal) + lubricant
                     : contact == contact::roller_flange_contact
                         ? spatial_roller_minimal() + lubricant
                         : spatial("", lubricant + "limiting_shear_coefficient = 0.07\n");
  // The pocket film is a film of cylindrical pockets, whose cage a land guides.
  if (name == "pocket_film" && !planar && contact != contact::roller_flange_contact)
    base = replaced(base, "guidance = \"rolling_element\"\npocket_clearance = \"0.4 mm\"\npocket_shape = \"spherical\"",
                    "guidance = \"outer_land\"\nland_clearance = \"0.3 mm\"\npocket_clearance = \"0.4 mm\"\n"
                    "pocket_shape = \"cylindrical\"");
  const std::string film = name == "ehd" && role == LawRole::traction && contact == contact::roller_race_contact
                               ? "normal = \"moes_ehd\"\n" : "";
  return base + "[contact." + std::string(contact::contact_name(contact)) + "]\n" + film +
         std::string(contact::role_name(role)) + " = \"" + std::string(name) + "\"\n";
}

const ContactSpec& contact_of(const Scene& s, ContactKindBit contact) {
  switch (contact) {
    case contact::roller_race_contact: return s.roller_race;
    case contact::roller_cage_contact: return s.roller_cage;
    case contact::ball_race_contact: return s.ball_race;
    case contact::ball_cage_contact: return s.ball_cage;
    case contact::roller_flange_contact: return s.roller_flange;
    default: return s.cage_land;
  }
}

/// The law of a role in a parsed contact (the scene stores the id; its name comes from the registry).
LawId law_of(const ContactSpec& c, LawRole role) {
  switch (role) {
    case LawRole::normal: return c.normal.id;
    case LawRole::damping: return c.damping.id;
    default: return c.traction.id;
  }
}

/// The laws of `role` that `contact` takes, as the parser must list them.
std::string expected_known(LawRole role, ContactKindBit contact) {
  std::string s;
  for (const Accepted& a : kExpected)
    if (a.role == role && (a.contacts & contact)) s += (s.empty() ? "" : ", ") + std::string(a.name);
  return s;
}

TEST(SceneLaws, AcceptedLawsAreStoredAsTheirIds) {
  for (const ContactKindBit contact : contact::contact_kinds())
    for (const Accepted& a : kExpected) {
      SCOPED_TRACE(std::string(contact::contact_name(contact)) + " " + std::string(a.name));
      const std::string text = scene_with_law(contact, a.role, a.name);
      if (!(a.contacts & contact)) {
        const SceneError e = error_of(text);
        EXPECT_EQ(e.key(), "contact." + std::string(contact::contact_name(contact)) + "." +
                               std::string(contact::role_name(a.role)));
        continue;
      }
      const Scene s = parse(text);
      EXPECT_EQ(law_of(contact_of(s, contact), a.role), a.id);
    }
}

TEST(SceneLaws, UnknownNameListsTheLawsOfThatContact) {
  for (const ContactKindBit contact : contact::contact_kinds())
    for (const LawRole role : kRoles) {
      const std::string role_name(contact::role_name(role));
      SCOPED_TRACE(std::string(contact::contact_name(contact)) + " " + role_name);
      const SceneError e = error_of(scene_with_law(contact, role, "bogus"));
      EXPECT_EQ(e.key(), "contact." + std::string(contact::contact_name(contact)) + "." + role_name);
      EXPECT_EQ(e.reason(),
                "unknown " + role_name + " law 'bogus'; known: " + expected_known(role, contact));
      EXPECT_GT(e.line(), 1);
    }
}

TEST(SceneLaws, MisplacedOrMisspeltNamesGetAHint) {
  EXPECT_EQ(error_of(scene_with_law(contact::ball_cage_contact, LawRole::traction, "limiting_shear")).reason(),
            "unknown traction law 'limiting_shear'; known: tanh, none ('limiting_shear' is for ball_race contacts)");
  EXPECT_EQ(error_of(scene_with_law(contact::roller_race_contact, LawRole::normal, "hertz")).reason(),
            "unknown normal law 'hertz'; known: palmgren, moes_ehd ('hertz' is for point contacts (ball_race, ball_cage, "
            "roller_flange))");
  EXPECT_EQ(error_of(scene_with_law(contact::ball_race_contact, LawRole::damping, "hunt_crosley")).reason(),
            "unknown damping law 'hunt_crosley' (did you mean 'hunt_crossley'?); known: hunt_crossley, none");
  // a name of another role is unknown in this one
  EXPECT_EQ(error_of(scene_with_law(contact::ball_race_contact, LawRole::normal, "none")).reason(),
            "unknown normal law 'none'; known: hertz");
}

// The rib contact is a spatial roller bearing's: refused, naming the section, on a planar roller
// bearing and on a ball bearing.
TEST(SceneLaws, FlangeContactOnlyInSpatialRollerBearings) {
  const std::string flange = "\n[contact.roller_flange]\nfriction_coefficient = 0.05\n";
  const Scene s = parse(spatial_roller_minimal() + flange);
  EXPECT_EQ(s.roller_flange.normal.id, LawId::hertz);
  EXPECT_EQ(s.roller_flange.traction.friction_coefficient, 0.05);
  for (const std::string& text : {std::string(kPlanarMinimal) + flange, spatial("", flange)}) {
    const SceneError e = error_of(text);
    EXPECT_EQ(e.key(), "contact.roller_flange") << e.what();
    EXPECT_NE(e.reason().find("spatial roller bearings"), std::string::npos) << e.what();
  }
}

TEST(SceneLaws, LimitingShearNeedsALubricant) {
  const std::string dry = spatial("", "[contact.ball_race]\ntraction = \"limiting_shear\"\n");
  const SceneError e = error_of(dry);
  EXPECT_EQ(e.key(), "contact.ball_race.traction");
  EXPECT_NE(e.reason().find("needs a lubricant film"), std::string::npos);
  const Scene wet = parse(scene_with_law(contact::ball_race_contact, LawRole::traction, "limiting_shear"));
  EXPECT_EQ(wet.ball_race.traction.id, LawId::limiting_shear);
  EXPECT_TRUE(wet.ball_race.traction.rolling_resistance);  // a film: on by default
}

// The film laws of seed 003 need a viscosity; EHD traction needs the EHD film.
TEST(SceneLaws, FilmLawsNeedALubricantAndEhdTractionTheEhdFilm) {
  const std::string lubricant = "\n[lubricant]\nviscosity = \"20 mPa s\"\npressure_viscosity = \"20 1/GPa\"\n";
  const std::string race = "\n[contact.roller_race]\nnormal = \"moes_ehd\"\ntraction = \"ehd\"\n";
  const std::string cage = "\n[contact.roller_cage]\nnormal = \"hydrodynamic\"\n";
  for (const std::string& contact : {race, cage}) {
    const SceneError e = error_of(std::string(kPlanarMinimal) + contact);
    EXPECT_NE(e.key().find(".normal"), std::string::npos) << e.what();
    EXPECT_NE(e.reason().find("needs a lubricant"), std::string::npos) << e.what();
  }
  const Scene wet = parse(std::string(kPlanarMinimal) + lubricant + race + cage);
  EXPECT_EQ(wet.roller_race.normal.id, LawId::moes_ehd);
  EXPECT_EQ(wet.roller_race.traction.id, LawId::ehd_traction);
  EXPECT_EQ(wet.roller_cage.normal.id, LawId::hydrodynamic);
  const SceneError dry_film = error_of(std::string(kPlanarMinimal) + lubricant +
                                       "\n[contact.roller_race]\ntraction = \"ehd\"\n");
  EXPECT_EQ(dry_film.key(), "contact.roller_race.traction");
  EXPECT_NE(dry_film.reason().find("needs normal = \"moes_ehd\""), std::string::npos) << dry_film.what();
}

// The land film: a cage land with a lubricant, ball or roller bearing; refused without one, naming the key.
TEST(SceneLaws, LandFilmNeedsALubricant) {
  const std::string land = "\n[contact.cage_land]\nnormal = \"short_bearing\"\n";
  const std::string guided = spatial("guidance = \"rolling_element\"", "guidance = \"inner_land\"\nland_clearance = \"0.3 mm\"");
  const SceneError dry = error_of(guided + land);
  EXPECT_EQ(dry.key(), "contact.cage_land.normal") << dry.what();
  EXPECT_NE(dry.reason().find("needs a lubricant"), std::string::npos) << dry.what();
  const Scene wet = parse(guided + "\n[lubricant]\nviscosity = \"20 mPa s\"\n" + land);
  EXPECT_EQ(wet.cage_land.normal.id, LawId::short_bearing);
  const Scene roller = parse(std::string(kPlanarMinimal) + "\n[lubricant]\nviscosity = \"20 mPa s\"\n" + land);
  EXPECT_EQ(roller.cage_land.normal.id, LawId::short_bearing);
  const SceneError roller_dry = error_of(std::string(kPlanarMinimal) + land);
  EXPECT_EQ(roller_dry.key(), "contact.cage_land.normal") << roller_dry.what();
}

// An oil given by its data sheet: the viscosity at its temperature by Walther's equation (ASTM D341),
// times its density; the mistakes refused naming the key.
TEST(SceneLaws, LubricantFromItsDataSheet) {
  const std::string sheet = "\n[lubricant]\nviscosity_40 = \"32 mm^2/s\"\nviscosity_100 = \"5.4 cSt\"\n"
                            "density = \"870 kg/m^3\"\ntemperature = \"80 degC\"\n";
  const Scene wet = parse(spatial() + sheet);
  // ISO VG 32 at 80 degC: 8.533 mm^2/s (the published D341 example: 8.5, test_viscosity.cpp), x 870 kg/m^3.
  EXPECT_NEAR(wet.lubricant.viscosity, 870 * 8.533e-6, 870 * 0.002e-6);
  EXPECT_FALSE(wet.lubricant.roelands);
  const Scene roelands = parse(spatial() + sheet + "pressure_viscosity_law = \"roelands\"\n");
  EXPECT_TRUE(roelands.lubricant.roelands);
  const SceneError both = error_of(spatial() + sheet + "viscosity = \"20 mPa s\"\n");
  EXPECT_EQ(both.key(), "lubricant.viscosity") << both.what();
  const SceneError no_density =
      error_of(spatial() + "\n[lubricant]\nviscosity_40 = \"32 mm^2/s\"\nviscosity_100 = \"5.4 cSt\"\n"
                           "temperature = \"80 degC\"\n");
  EXPECT_EQ(no_density.key(), "lubricant.density") << no_density.what();
  const SceneError thicker = error_of(replaced(spatial() + sheet, "5.4 cSt", "50 cSt"));
  EXPECT_EQ(thicker.key(), "lubricant.viscosity_100") << thicker.what();
  const SceneError alone = error_of(spatial() + "\n[lubricant]\nviscosity = \"20 mPa s\"\nviscosity_100 = \"5.4 cSt\"\n");
  EXPECT_EQ(alone.key(), "lubricant.viscosity_100") << alone.what();
}

// The pocket film: cylindrical pockets with a lubricant; refused without one, and in spherical
// pockets (not modelled), naming the key.
TEST(SceneLaws, PocketFilmNeedsALubricantAndCylindricalPockets) {
  const std::string pocket = "\n[contact.ball_cage]\nnormal = \"pocket_film\"\n";
  const std::string lubricant = "\n[lubricant]\nviscosity = \"20 mPa s\"\n";
  const std::string cylindrical =
      spatial("pocket_shape = \"spherical\"", "pocket_shape = \"cylindrical\"\nguidance = \"outer_land\"\n"
                                               "land_clearance = \"0.3 mm\"");
  const std::string guided = replaced(cylindrical, "guidance = \"rolling_element\"\n", "");
  const SceneError dry = error_of(guided + pocket);
  EXPECT_EQ(dry.key(), "contact.ball_cage.normal") << dry.what();
  EXPECT_NE(dry.reason().find("needs a lubricant"), std::string::npos) << dry.what();
  const Scene wet = parse(guided + lubricant + pocket);
  EXPECT_EQ(wet.ball_cage.normal.id, LawId::pocket_film);
  const SceneError spherical = error_of(spatial() + lubricant + pocket);
  EXPECT_EQ(spherical.key(), "contact.ball_cage.normal") << spherical.what();
  EXPECT_NE(spherical.reason().find("cylindrical pocket"), std::string::npos) << spherical.what();
}

}  // namespace
}  // namespace raceway::scene
