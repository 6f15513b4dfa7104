// raceway units: table-driven parsing of "<number> <unit expression>" to SI.
#include "io/scene/units.hpp"

#include <charconv>
#include <cmath>
#include <numbers>
#include <optional>

#include <fmt/format.h>

namespace raceway::io {
namespace {

constexpr double pi = std::numbers::pi;

struct UnitDef {
  std::string_view symbol;
  double factor;  ///< SI value of one unit
  Dimension dimension;
};

// "\xC2\xB5" is MICRO SIGN (U+00B5), "\xCE\xBC" GREEK SMALL LETTER MU (U+03BC); both are accepted.
constexpr UnitDef kUnits[] = {
    {"m", 1.0, dim::length},
    {"mm", 1e-3, dim::length},
    {"um", 1e-6, dim::length},
    {"\xC2\xB5" "m", 1e-6, dim::length},
    {"\xCE\xBC" "m", 1e-6, dim::length},
    {"nm", 1e-9, dim::length},
    {"cm", 1e-2, dim::length},
    {"km", 1e3, dim::length},
    {"kg", 1.0, dim::mass},
    {"g", 1e-3, dim::mass},
    {"s", 1.0, dim::time},
    {"ms", 1e-3, dim::time},
    {"us", 1e-6, dim::time},
    {"\xC2\xB5" "s", 1e-6, dim::time},
    {"\xCE\xBC" "s", 1e-6, dim::time},
    {"ns", 1e-9, dim::time},
    {"min", 60.0, dim::time},
    {"h", 3600.0, dim::time},
    {"N", 1.0, dim::force},
    {"kN", 1e3, dim::force},
    {"mN", 1e-3, dim::force},
    {"Pa", 1.0, dim::pressure},
    {"mPa", 1e-3, dim::pressure},
    {"kPa", 1e3, dim::pressure},
    {"MPa", 1e6, dim::pressure},
    {"GPa", 1e9, dim::pressure},
    {"rad", 1.0, dim::angle},
    {"mrad", 1e-3, dim::angle},
    {"urad", 1e-6, dim::angle},
    {"deg", pi / 180.0, dim::angle},
    {"rev", 2.0 * pi, dim::angle},
    {"rpm", 2.0 * pi / 60.0, dim::angular_speed},  // rev/min
    {"Hz", 2.0 * pi, dim::angular_speed},          // rev/s: angular speeds only
    {"J", 1.0, dim::moment},
    {"W", 1.0, dim::power},
    {"kW", 1e3, dim::power},
    {"P", 0.1, dim::viscosity},   // poise
    {"cP", 1e-3, dim::viscosity}, // centipoise = mPa s
};

struct NamedDimension {
  Dimension dimension;
  std::string_view name;
  std::string_view examples;
};

constexpr NamedDimension kNamed[] = {
    {dim::none, "a plain number", "no unit"},
    {dim::mass, "a mass", "kg, g"},
    {dim::length, "a length", "m, mm, um"},
    {dim::time, "a time", "s, ms, min"},
    {dim::angle, "an angle", "rad, mrad, deg, rev"},
    {dim::angular_speed, "an angular speed", "rpm, rad/s, Hz, deg/s"},
    {dim::speed, "a speed", "m/s, mm/s"},
    {dim::force, "a force", "N, kN"},
    {dim::moment, "a moment", "N m, J"},
    {dim::power, "a power", "W, kW"},
    {dim::pressure, "a pressure", "Pa, MPa, GPa"},
    {dim::density, "a density", "kg/m^3, g/cm^3"},
    {dim::viscosity, "a dynamic viscosity", "Pa s, mPa s, cP"},
    {dim::inverse_pressure, "a pressure-viscosity coefficient", "1/Pa, 1/GPa, m^2/N"},
    {dim::stiffness, "a stiffness", "N/m, N/mm"},
    {dim::damping, "a damping coefficient", "N s/m"},
    {dim::inertia, "a moment of inertia", "kg m^2"},
    {dim::inverse_speed, "an inverse speed", "s/m"},
    {dim::angular_stiffness, "a tilt stiffness", "N m/rad"},
    {dim::angular_damping, "a tilt damping coefficient", "N m s/rad"},
    {Dimension{0, 0, -2, 1}, "an angular acceleration", "rad/s^2"},
    {Dimension{0, 1, -2, 0}, "an acceleration", "m/s^2"},
    {Dimension{0, 0, -1, 0}, "a rate without angle", "1/s"},
};

const NamedDimension* find_named(Dimension d) {
  for (const auto& n : kNamed)
    if (n.dimension == d) return &n;
  return nullptr;
}

const UnitDef* find_unit(std::string_view symbol) {
  for (const auto& u : kUnits)
    if (u.symbol == symbol) return &u;
  return nullptr;
}

bool is_space(char c) { return c == ' ' || c == '\t'; }
bool is_symbol_char(char c) {
  const auto u = static_cast<unsigned char>(c);
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || u >= 0x80;
}
bool is_digit(char c) { return c >= '0' && c <= '9'; }

[[noreturn]] void garbage(std::string_view text, std::string_view why) {
  throw UnitError(fmt::format("'{}' is not a quantity: {}", text, why));
}

std::string known_units() {
  std::string s;
  for (const auto& u : kUnits) {
    if (!s.empty()) s += ' ';
    s += u.symbol;
  }
  return s;
}

/// Parses a unit expression (the part after the number) into factor and dimension.
Quantity parse_unit_expression(std::string_view text, std::string_view expr) {
  Quantity q{1.0, dim::none};
  std::size_t i = 0;
  bool in_denominator = false;
  bool need_term = false;  // an operator was just read
  bool have_term = false;
  while (true) {
    while (i < expr.size() && is_space(expr[i])) ++i;
    if (i == expr.size()) break;
    const char c = expr[i];
    if (c == '*' || c == '/') {
      if (need_term) garbage(text, fmt::format("two operators in a row in '{}'", expr));
      if (c == '*' && !have_term) garbage(text, fmt::format("'{}' starts with '*'", expr));
      if (c == '/') {
        if (in_denominator)
          garbage(text, fmt::format("more than one '/' in '{}' is ambiguous (write e.g. 'kg/m s' or 'm^-1')", expr));
        in_denominator = true;
      }
      need_term = true;
      ++i;
      continue;
    }
    // a term: a unit symbol or the factor 1, then an optional exponent
    const std::size_t start = i;
    double factor = 1.0;
    Dimension d = dim::none;
    if (is_symbol_char(c)) {
      while (i < expr.size() && is_symbol_char(expr[i])) ++i;
      const std::string_view symbol = expr.substr(start, i - start);
      const UnitDef* u = find_unit(symbol);
      if (!u) garbage(text, fmt::format("unknown unit '{}' (known: {})", symbol, known_units()));
      factor = u->factor;
      d = u->dimension;
    } else if (c == '1' && (i + 1 == expr.size() || !is_digit(expr[i + 1]))) {
      ++i;
    } else {
      garbage(text, fmt::format("unexpected '{}' in unit '{}' (exponents are written m^2)", expr.substr(i, 1), expr));
    }
    int exponent = 1;
    if (i < expr.size() && expr[i] == '^') {
      ++i;
      const char* first = expr.data() + i;
      const char* last = expr.data() + expr.size();
      const auto [ptr, ec] = std::from_chars(first, last, exponent);
      if (ec != std::errc() || exponent == 0)
        garbage(text, fmt::format("bad exponent after '{}^'", expr.substr(start, i - 1 - start)));
      i += static_cast<std::size_t>(ptr - first);
    }
    if (i < expr.size() && !is_space(expr[i]) && expr[i] != '*' && expr[i] != '/')
      garbage(text, fmt::format("unexpected '{}' in unit '{}' (exponents are written m^2)", expr.substr(i, 1), expr));
    if (in_denominator) exponent = -exponent;
    q.value *= std::pow(factor, exponent);
    q.dimension = q.dimension * d.pow(exponent);
    have_term = true;
    need_term = false;
  }
  if (need_term) garbage(text, fmt::format("'{}' ends with an operator", expr));
  return q;
}

}  // namespace

Quantity parse_quantity(std::string_view text) {
  std::size_t b = 0, e = text.size();
  while (b < e && is_space(text[b])) ++b;
  while (e > b && is_space(text[e - 1])) --e;
  const std::string_view t = text.substr(b, e - b);
  if (t.empty()) garbage(text, "it is empty (write a number and a unit, e.g. \"3 mm\")");
  std::size_t i = (t[0] == '+') ? 1 : 0;
  double number = 0;
  const auto [ptr, ec] = std::from_chars(t.data() + i, t.data() + t.size(), number);
  if (ec == std::errc::result_out_of_range) garbage(text, "the number is out of range");
  if (ec != std::errc() || (i == 1 && t.size() > 1 && t[1] == '-'))
    garbage(text, "it does not start with a number (write e.g. \"3 mm\")");
  if (!std::isfinite(number)) garbage(text, "the number is not finite");
  i = static_cast<std::size_t>(ptr - t.data());
  Quantity q = parse_unit_expression(text, t.substr(i));
  q.value *= number;
  return q;
}

double parse_quantity(std::string_view text, Dimension expected) {
  const Quantity q = parse_quantity(text);
  if (q.dimension != expected)
    throw UnitError(fmt::format("'{}' is {}; expected {}", text, dimension_name(q.dimension),
                                dimension_description(expected)));
  return q.value;
}

double parse_quantity(const toml::node& node, Dimension expected) {
  if (const auto* i = node.as_integer()) return static_cast<double>(i->get());
  if (const auto* f = node.as_floating_point()) {
    if (!std::isfinite(f->get())) throw UnitError(fmt::format("{} is not a finite number", f->get()));
    return f->get();
  }
  if (const auto* s = node.as_string()) return parse_quantity(std::string_view(s->get()), expected);
  throw UnitError(fmt::format("expected {} as a number in SI units or a string such as \"{}\"",
                              dimension_description(expected),
                              expected == dim::none ? "0.3" : "3 mm"));
}

std::string si_unit(Dimension d) {
  struct Base {
    int Dimension::*member;
    std::string_view symbol;
  };
  constexpr Base bases[] = {{&Dimension::mass, "kg"}, {&Dimension::length, "m"},
                            {&Dimension::time, "s"}, {&Dimension::angle, "rad"}};
  std::string s;
  for (const auto& b : bases) {
    const int e = d.*(b.member);
    if (e == 0) continue;
    if (!s.empty()) s += ' ';
    s += b.symbol;
    if (e != 1) s += fmt::format("^{}", e);
  }
  return s.empty() ? "1" : s;
}

std::string dimension_name(Dimension d) {
  if (const auto* n = find_named(d)) return std::string(n->name);
  return fmt::format("a quantity in {}", si_unit(d));
}

std::string dimension_description(Dimension d) {
  if (const auto* n = find_named(d)) return fmt::format("{} ({})", n->name, n->examples);
  return fmt::format("a quantity in {}", si_unit(d));
}

std::vector<std::string_view> unit_symbols() {
  std::vector<std::string_view> v;
  for (const auto& u : kUnits) v.push_back(u.symbol);
  return v;
}

}  // namespace raceway::io
