// raceway units: quantities with units in scene files, converted to SI at the io boundary.
//
// A quantity in a scene file is either a bare TOML number, taken as SI, or a string
// "<number> <unit expression>", e.g. "17.462 mm", "3000 rpm", "0.02 1/GPa", "5 N s/m".
//
// Unit expressions: products by spaces or '*', one '/' at most (everything after it is the
// denominator: "N s/m" = N s / m, "J/kg m" = J / (kg m)), integer exponents with '^'
// ("kg/m^3", "m^-1"), and the factor "1" ("1/GPa"). Symbols: see unit_symbols().
//
// Dimensions tracked: mass, length, time and angle. Angle is a dimension of its own, so an angular
// speed (rad/s, rpm, deg/s, Hz) cannot be given where a plain 1/s or a length is expected.
// Note: "Hz" means revolutions per second here (1 Hz = 2 pi rad/s); it is an angular speed, not a
// plain frequency.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

namespace raceway::io {

/// Exponents of mass, length, time and angle.
struct Dimension {
  int mass = 0;
  int length = 0;
  int time = 0;
  int angle = 0;

  friend constexpr bool operator==(const Dimension&, const Dimension&) = default;
  constexpr Dimension operator*(const Dimension& o) const {
    return {mass + o.mass, length + o.length, time + o.time, angle + o.angle};
  }
  constexpr Dimension operator/(const Dimension& o) const {
    return {mass - o.mass, length - o.length, time - o.time, angle - o.angle};
  }
  constexpr Dimension pow(int e) const { return {mass * e, length * e, time * e, angle * e}; }
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
/// Throws UnitError for garbage (no number, unknown unit, dangling operator, ...).
Quantity parse_quantity(std::string_view text);

/// Parses text and checks its dimension; returns the SI value. Throws UnitError, e.g.
/// "'3000 mm' is a length; expected an angular speed (rpm, rad/s, Hz, deg/s)".
double parse_quantity(std::string_view text, Dimension expected);

/// A TOML value: a bare number (SI) or a quantity string. Throws UnitError on a wrong type too.
double parse_quantity(const toml::node& node, Dimension expected);

/// "a length", "an angular speed", or "a quantity in kg m s^-2" for unnamed dimensions.
std::string dimension_name(Dimension d);
/// dimension_name plus typical units: "an angular speed (rpm, rad/s, Hz, deg/s)".
std::string dimension_description(Dimension d);
/// SI unit text of a dimension: "kg m^-1 s^-2", "rad s^-1"; "1" when dimensionless.
std::string si_unit(Dimension d);

/// All unit symbols understood, in table order.
std::vector<std::string_view> unit_symbols();

}  // namespace raceway::io
