// raceway units: quantities with units in scene files, converted to SI at the io boundary.
//
// A quantity in a scene file is a string "<number> <unit expression>", e.g. "17.462 mm", "3000 rpm",
// "0.02 1/GPa", "5 N s/m". A bare TOML number is a plain (dimensionless) number: given for a
// dimensional key it is an error that shows the form to write ("3000 rpm" or "3000 rad/s"), except
// 0, which is the same in every unit.
//
// Unit expressions: products by spaces or '*', one '/' at most (everything after it is the
// denominator: "N s/m" = N s / m, "J/kg m" = J / (kg m)), integer exponents with '^'
// ("kg/m^3", "m^-1") from -9 to 9, and the factor "1" ("1/GPa"). Symbols: see unit_symbols(); the
// common spellings r/min, RPM, rev/min, in, ft, lbf, lb, psi are among them. Every result is finite:
// a number that overflows or underflows in its unit ("1e307 h") is an error.
//
// Dimensions tracked: mass, length, time, angle, information (bytes, for output sizes) and temperature
// (K; "degC" or "\u00b0C" alone is an absolute temperature in Celsius, 273.15 K added, and is refused inside
// a compound unit, where K is meant: "W/K"). Angle is a dimension of its own, so an angular
// speed (rad/s, rpm, deg/s, Hz) cannot be given where a plain 1/s or a length is expected.
// Note: "Hz" means revolutions per second here (1 Hz = 2 pi rad/s); it is an angular speed, not a
// plain frequency.
#pragma once

#include <stdexcept>
#include <string>
#include <span>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

namespace raceway::scene {

/// Exponents of mass, length, time, angle, information and temperature. Unit expressions keep them small
/// (exponents -9 to 9 per term, at most max_exponent in all).
struct Dimension {
  int mass = 0;
  int length = 0;
  int time = 0;
  int angle = 0;
  int information = 0;
  int temperature = 0;

  static constexpr int max_exponent = 64;
  friend constexpr bool operator==(const Dimension&, const Dimension&) = default;
  constexpr Dimension operator*(const Dimension& o) const {
    return {mass + o.mass, length + o.length, time + o.time, angle + o.angle, information + o.information,
            temperature + o.temperature};
  }
  constexpr Dimension operator/(const Dimension& o) const {
    return {mass - o.mass, length - o.length, time - o.time, angle - o.angle, information - o.information,
            temperature - o.temperature};
  }
  constexpr Dimension pow(int e) const {
    return {mass * e, length * e, time * e, angle * e, information * e, temperature * e};
  }
};

/// The dimensions the scene schema uses.
namespace dim {
inline constexpr Dimension none{0, 0, 0, 0};
inline constexpr Dimension mass{1, 0, 0, 0};
inline constexpr Dimension length{0, 1, 0, 0};
inline constexpr Dimension time{0, 0, 1, 0};
inline constexpr Dimension angle{0, 0, 0, 1};
inline constexpr Dimension angular_speed{0, 0, -1, 1};
inline constexpr Dimension speed{0, 1, -1, 0};
inline constexpr Dimension force{1, 1, -2, 0};
inline constexpr Dimension moment{1, 2, -2, 0};          ///< N m (same as energy, J)
inline constexpr Dimension power{1, 2, -3, 0};
inline constexpr Dimension pressure{1, -1, -2, 0};
inline constexpr Dimension density{1, -3, 0, 0};
inline constexpr Dimension viscosity{1, -1, -1, 0};      ///< dynamic viscosity, Pa s
inline constexpr Dimension inverse_pressure{-1, 1, 2, 0};
inline constexpr Dimension stiffness{1, 0, -2, 0};       ///< N/m
inline constexpr Dimension damping{1, 0, -1, 0};         ///< N s/m
inline constexpr Dimension inertia{1, 2, 0, 0};          ///< kg m^2
inline constexpr Dimension inverse_speed{0, -1, 1, 0};   ///< s/m
inline constexpr Dimension angular_stiffness{1, 2, -2, -1};  ///< N m/rad (tilt stiffness)
inline constexpr Dimension angular_damping{1, 2, -1, -1};    ///< N m s/rad (tilt damping)
inline constexpr Dimension information{0, 0, 0, 0, 1};       ///< bytes (output sizes)
inline constexpr Dimension temperature{0, 0, 0, 0, 0, 1};    ///< K (absolute; "degC" alone adds 273.15)
inline constexpr Dimension kinematic_viscosity{0, 2, -1, 0}; ///< m^2/s (mm^2/s = cSt)
inline constexpr Dimension thermal_conductance{1, 2, -3, 0, 0, -1};  ///< W/K
inline constexpr Dimension heat_capacity{1, 2, -2, 0, 0, -1};        ///< J/K
inline constexpr Dimension specific_heat{0, 2, -2, 0, 0, -1};        ///< J/(kg K)
inline constexpr Dimension heat_transfer_coefficient{1, 0, -3, 0, 0, -1};  ///< W/(m^2 K)
}  // namespace dim

/// A value in SI units with its dimension.
struct Quantity {
  double value = 0;
  Dimension dimension;
};

/// A malformed quantity or one of the wrong dimension; what() is the human-readable reason.
class UnitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Parses "<number> [unit expression]" to SI. A string without unit is dimensionless.
/// Throws UnitError for garbage (no number, unknown unit, dangling operator, an exponent beyond 9,
/// a value that is not finite in SI or underflows to zero, ...).
Quantity parse_quantity(std::string_view text);

/// Parses text and checks its dimension; returns the SI value. Throws UnitError, e.g.
/// "'3000 mm' is a length; expected an angular speed (rpm, rad/s, Hz, deg/s)".
double parse_quantity(std::string_view text, Dimension expected);

/// A TOML value: a quantity string, or a bare number where a plain number is expected (or 0).
/// Throws UnitError on a wrong type, a non-finite number, and a bare non-zero number for a
/// dimensional quantity (the message shows the form to write, with `example` when given).
double parse_quantity(const toml::node& node, Dimension expected, std::string_view example = {});

/// What the scene knows of a kind of quantity: its name, typical units, its SI spelling, and the
/// range of magnitudes a rolling bearing's value of it can sanely have (zero is always allowed).
struct QuantityKind {
  Dimension dimension;
  std::string_view name;      ///< "an angular speed"
  std::string_view examples;  ///< "rpm, rad/s, Hz, deg/s"
  std::string_view si;        ///< the SI unit as written in a scene: "rad/s"
  std::string_view usual;     ///< a usual unit for bearings: "rpm" (may be the SI one)
  double smallest = 0;        ///< smallest sane non-zero magnitude in SI; 0: no sane range
  double largest = 0;         ///< largest sane magnitude in SI
  std::string_view why{};     ///< where the limits come from, for the docs
};
/// The kind of a dimension, or nullptr for one without a name (e.g. kg m s^-1).
const QuantityKind* quantity_kind(Dimension d);
/// Every named kind, in table order (docs/scene_keys.md prints the sane ranges).
std::span<const QuantityKind> quantity_kinds();
/// Whether |value| is zero or within the kind's sane range (true for kinds without one).
bool within_sane_range(double value, Dimension d);

/// "a length", "an angular speed", or "a quantity in kg m s^-2" for unnamed dimensions.
std::string dimension_name(Dimension d);
/// dimension_name plus typical units: "an angular speed (rpm, rad/s, Hz, deg/s)".
std::string dimension_description(Dimension d);
/// SI unit text of a dimension: "kg m^-1 s^-2", "rad s^-1"; "1" when dimensionless.
std::string si_unit(Dimension d);

/// All unit symbols understood, in table order.
std::vector<std::string_view> unit_symbols();

}  // namespace raceway::scene
