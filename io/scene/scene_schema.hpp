// The scene schema as a table: one row per key of a scene file (section, key, kind of value,
// dimension, bounds, default, the bearings and contacts that take it, one line of meaning, and
// where the value goes in scene::Scene). One generic reader (scene_parser.cpp) reads every section
// from its rows; docs/scene_keys.md is printed from them (scene_keys_doc). The rules that tie keys
// together (rollers that fit, clearances, ring motions, laws that need a lubricant) are code, in
// scene_rules.cpp, named by the rows that trigger them.
//
// Internal to raceway::scene; the public interface is scene_parser.hpp.
#pragma once

#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "contact/laws/law_registry.hpp"
#include "io/scene/scene.hpp"
#include "io/scene/units.hpp"

namespace raceway::scene::schema {

class Section;  // scene_section.hpp: one TOML table of the scene file

/// What a row's reader binds to: the scene, and the ring, contact or material being read.
struct Bind {
  Scene& scene;
  const Section* info = nullptr;           ///< [scene]: errors about the model name its key
  RingSpec* ring = nullptr;                ///< [inner_ring] or [outer_ring] and their tables
  ContactSpec* contact = nullptr;          ///< [contact.NAME]
  contact::ContactKindBit contact_kind{};  ///< which one (0 outside [contact.NAME])
  Material* material = nullptr;            ///< [materials.NAME]
  bool bearing_known = false;              ///< [bearing] has been read: ball() is the scene's bearing
  bool ball() const { return scene.bearing.is_ball_bearing(); }
  /// A cylindrical roller bearing in the spatial model.
  bool spatial_roller() const { return !ball() && scene.scene.model == ModelKind::spatial; }
};


/// Where a row's value goes.
using Field = std::variant<std::monostate, double*, int*, long*, bool*, std::string*, std::vector<std::string>*,
                           TimeFunction*, ModelKind*,
                           BearingType*, RibArrangement*, RollerEnd*, contact::RollerProfileKind*, CageGuidance*, PocketShape*, CageBridges*, BeamTheory*, RingMotion*, RingTilt*, RingFlexibility*, IntegrationMethod*,
                           LinearSolverKind*, ElementVelocityFrame*, NormalLaw*, DampingLaw*, TractionLaw*, ContactSpec*,
                           contact::SpallEdge*, std::vector<double>*, std::vector<int>*>;

enum class ValueKind {
  number,         ///< a quantity "<number> <unit>" (a bare number if plain, or 0), converted to SI
  integer,        ///< a TOML integer
  boolean,        ///< true or false
  text,           ///< a string
  key_list,       ///< an array of dotted scene keys ("inner_ring.speed")
  choice,         ///< one of the row's options
  material,       ///< the name of a built-in or [materials.NAME] material
  law,            ///< a contact law of the row's role, from the law registry
  time_function,  ///< a quantity, or { time = [...], value = [...] } (piecewise linear, held outside)
  cell_grid,      ///< [nx, ny], two integers from 1 to 50
  table,          ///< a table whose keys are the rows of section `sub`
  number_list,    ///< an array of quantities, each within the row's bounds
  integer_list,   ///< an array of integers, each within the row's bounds
};

/// The bearings that take a key. A scene is a ball bearing (always spatial) or a roller bearing,
/// planar or spatial: its bits (scene_bearing_bits) are ball_bearings, or roller_bearings with
/// planar_rollers or spatial_rollers. A row takes a key where its mask shares a bit with them.
enum BearingBit : unsigned {
  roller_bearings = 1u,   ///< cylindrical roller bearings, planar or spatial
  ball_bearings = 2u,
  any_bearing = 3u,
  spatial_rollers = 4u,   ///< cylindrical roller bearings in the spatial model only
  planar_rollers = 8u,    ///< cylindrical roller bearings in the planar model only
  spatial_bearings = ball_bearings | spatial_rollers,  ///< every spatial scene (axial direction, tilt)
};

/// The BearingBit mask of the scene being read: ball_bearings, or roller_bearings with its space's bit.
inline unsigned scene_bearing_bits(const Bind& b) {
  if (b.ball()) return ball_bearings;
  return roller_bearings | (b.spatial_roller() ? spatial_rollers : planar_rollers);
}

/// Allowed values of a number or integer, in SI. Infinite = no bound; checked on given values only.
struct Bounds {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;
  std::string_view unit{};  ///< unit in which messages and docs show lo and hi ("deg"); empty: SI
  std::string_view note{};  ///< appended to the failure message: " (0.02 to 0.1 for mineral oils)"
  long (*hi_of)(const Bind&) = nullptr;  ///< integers: an upper bound set by another key
  std::string_view hi_text{};            ///< docs: how hi_of is chosen
};
inline constexpr Bounds positive{.lo = 0, .lo_open = true};
inline constexpr Bounds non_negative{.lo = 0};

/// A key's value when it is absent.
struct Default {
  enum class Kind { required, value, derived, absent, registry } kind = Kind::required;
  double number = 0;      ///< value: numbers, integers, booleans (0 or 1), time functions (a constant)
  std::string_view word{};  ///< value: strings, choices, materials
  std::optional<double> (*derive)(const Bind&) = nullptr;  ///< derived from other keys; nullopt: required
  std::string_view text{};  ///< docs: what a derived default is, or what an absent key leaves
};
inline constexpr Default required{};
inline constexpr Default absent{.kind = Default::Kind::absent};       ///< optional; nothing is stored
inline constexpr Default registry{.kind = Default::Kind::registry};   ///< laws: contact::default_law
constexpr Default value(double v) { return {.kind = Default::Kind::value, .number = v}; }
constexpr Default word(std::string_view w) { return {.kind = Default::Kind::value, .word = w}; }
constexpr Default derived(std::optional<double> (*f)(const Bind&), std::string_view text) {
  return {.kind = Default::Kind::derived, .derive = f, .text = text};
}

struct Option {
  std::string_view name;  ///< the scene's spelling
  int value;              ///< the enum value (or 1/0 for a yes/no choice stored in a bool)
};
/// The name of an option value ("fixed" for RingMotion::fixed).
std::string_view option_name(std::span<const Option> options, int value);

inline constexpr Option kModels[] = {{"planar", int(ModelKind::planar)}, {"spatial", int(ModelKind::spatial)}};
inline constexpr Option kBearingTypes[] = {{"cylindrical_roller", int(BearingType::cylindrical_roller)},
                                           {"deep_groove_ball", int(BearingType::deep_groove_ball)},
                                           {"four_point_contact_ball", int(BearingType::four_point_contact_ball)},
                                           {"angular_contact_ball", int(BearingType::angular_contact_ball)},
                                           {"tapered_roller", int(BearingType::tapered_roller)}};
inline constexpr Option kRibArrangements[] = {{"NU", int(RibArrangement::nu)},
                                              {"NJ", int(RibArrangement::nj)},
                                              {"NUP", int(RibArrangement::nup)},
                                              {"N", int(RibArrangement::n)}};
inline constexpr Option kRollerEnds[] = {{"flat", int(RollerEnd::flat)}, {"spherical", int(RollerEnd::spherical)}};
inline constexpr Option kRollerProfiles[] = {{"straight", int(contact::RollerProfileKind::straight)},
                                             {"circular", int(contact::RollerProfileKind::circular)},
                                             {"lundberg", int(contact::RollerProfileKind::lundberg)},
                                             {"johns_gohar", int(contact::RollerProfileKind::johns_gohar)}};
inline constexpr Option kGuidances[] = {{"inner_land", int(CageGuidance::inner_land)},
                                        {"outer_land", int(CageGuidance::outer_land)},
                                        {"rolling_element", int(CageGuidance::rolling_element)}};
inline constexpr Option kPocketShapes[] = {{"cylindrical", int(PocketShape::cylindrical)},
                                           {"spherical", int(PocketShape::spherical)}};
inline constexpr Option kCageBridges[] = {{"rigid", int(CageBridges::rigid)},
                                          {"flexible", int(CageBridges::flexible)}};
inline constexpr Option kBeamTheories[] = {{"timoshenko", int(BeamTheory::timoshenko)},
                                           {"euler_bernoulli", int(BeamTheory::euler_bernoulli)}};
inline constexpr Option kRingMotions[] = {
    {"fixed", int(RingMotion::fixed)}, {"driven", int(RingMotion::driven)}, {"free", int(RingMotion::free)}};
inline constexpr Option kRingFlexibilities[] = {{"rigid", int(RingFlexibility::rigid)},
                                                {"ring_modes", int(RingFlexibility::ring_modes)}};
inline constexpr Option kSpallEdges[] = {{"sharp", int(contact::SpallEdge::sharp)},
                                         {"smooth", int(contact::SpallEdge::smooth)}};
inline constexpr Option kFreeOrFixed[] = {{"free", 1}, {"fixed", 0}};
inline constexpr Option kPressureViscosityLaws[] = {{"barus", 0}, {"roelands", 1}};
inline constexpr Option kRingTilts[] = {
    {"fixed", int(RingTilt::fixed)}, {"free", int(RingTilt::free)}, {"prescribed", int(RingTilt::prescribed)}};
inline constexpr Option kMethods[] = {{"bdf", int(IntegrationMethod::bdf)},
                                     {"adams", int(IntegrationMethod::adams)},
                                     {"erk", int(IntegrationMethod::erk)},
                                     {"ark", int(IntegrationMethod::ark)}};
inline constexpr Option kElementVelocityFrames[] = {{"bearing", int(ElementVelocityFrame::bearing)},
                                                   {"orbital", int(ElementVelocityFrame::orbital)}};
/// "bordered" and "dense" are older names of block elimination and SUNDIALS dense, still accepted.
inline constexpr Option kLinearSolvers[] = {{"auto", int(LinearSolverKind::automatic)},
                                            {"petsc-bordered", int(LinearSolverKind::petsc_bordered)},
                                            {"block-elimination", int(LinearSolverKind::block_elimination)},
                                            {"sundials-dense", int(LinearSolverKind::sundials_dense)},
                                            {"bordered", int(LinearSolverKind::block_elimination)},
                                            {"dense", int(LinearSolverKind::sundials_dense)}};

struct Row;
/// Why a key does not apply in this scene (it is then rejected if given), or nullopt if it does.
using Condition = std::optional<std::string> (*)(const Section&, const Bind&);
/// A rule run after the row's value is read; throws SceneError (Section::fail) when it is broken.
using Check = void (*)(const Row&, const Section&, Bind&);

/// One key of the scene schema. Rows of a section are read in table order.
struct Row {
  std::string_view section{};  ///< "bearing", "cage.support", "*_ring.load", "contact.*", "materials.*"
  std::string_view key{};
  ValueKind kind{};
  Field (*field)(Bind&) = nullptr;  ///< where the value goes
  Dimension dim{};                  ///< numbers and time functions
  Bounds bounds{};
  Default def{};
  unsigned bearings = any_bearing;  ///< BearingBit mask of the bearings that take the key
  unsigned contacts = 0;            ///< contact.* rows: ContactKindBit mask (0: all); [contact] rows: the contact
  std::string_view elsewhere{};     ///< why the key is rejected where the bearing or contact does not take it
  Condition when = nullptr;         ///< further conditions (scene_rules.hpp)
  std::string_view missing{};       ///< reason when required and missing (default: "required key is missing")
  Check then = nullptr;             ///< rule run after the value is read (scene_rules.hpp)
  std::span<const Option> options{};
  std::string_view noun{};          ///< choices: what is chosen, in errors ("bearing type"); default: the key
  contact::LawRole role{};          ///< laws
  std::string_view sub{};           ///< tables: the section of their keys
  std::optional<double> otherwise{};  ///< stored when the key does not apply (numbers, yes/no choices)
  std::string_view example{};       ///< a typical value, for errors and docs ("35 deg")
  std::string_view meaning{};       ///< one line, for docs
};

/// Every row, grouped by section in reading order.
std::span<const Row> scene_rows();
/// The rows of one section ("bearing", "*_ring.load", "contact.*"); empty for an unknown one.
std::span<const Row> rows_of(std::string_view section);
/// The top-level sections of a scene file, in the order of the documentation.
std::span<const std::string_view> top_sections();

/// docs/scene_keys.md: every row and the contact laws of every contact (scene_doc.cpp).
std::string scene_keys_markdown();

}  // namespace raceway::scene::schema
