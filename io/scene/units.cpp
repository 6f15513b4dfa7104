// raceway units: table-driven parsing of "<number> <unit expression>" to SI.
#include "io/scene/units.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <optional>

#include <fmt/format.h>

namespace raceway::scene {
namespace {

constexpr double pi = std::numbers::pi;

struct UnitDef {
  std::string_view symbol;
  double factor;  ///< SI value of one unit
  Dimension dimension;
};

// "\xC2\xB5" is MICRO SIGN (U+00B5), "\xCE\xBC" GREEK SMALL LETTER MU (U+03BC); both are accepted.
// Imperial units by their exact definitions (1 in = 25.4 mm, 1 lb = 0.45359237 kg, standard
// gravity 9.80665 m/s^2 for lbf).
constexpr double kInch = 0.0254, kPound = 0.45359237, kPoundForce = kPound * 9.80665;
constexpr UnitDef kUnits[] = {
    {"m", 1.0, dim::length},
    {"mm", 1e-3, dim::length},
    {"um", 1e-6, dim::length},
    {"\xC2\xB5" "m", 1e-6, dim::length},
    {"\xCE\xBC" "m", 1e-6, dim::length},
    {"nm", 1e-9, dim::length},
    {"cm", 1e-2, dim::length},
    {"km", 1e3, dim::length},
    {"in", kInch, dim::length},
    {"ft", 12 * kInch, dim::length},
    {"thou", 1e-3 * kInch, dim::length},  // a thousandth of an inch (clearances)
    {"kg", 1.0, dim::mass},
    {"g", 1e-3, dim::mass},
    {"lb", kPound, dim::mass},
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
    {"MN", 1e6, dim::force},
    {"lbf", kPoundForce, dim::force},
    {"Nm", 1.0, dim::moment},  // N m written as one word
    {"Pa", 1.0, dim::pressure},
    {"mPa", 1e-3, dim::pressure},
    {"kPa", 1e3, dim::pressure},
    {"MPa", 1e6, dim::pressure},
    {"GPa", 1e9, dim::pressure},
    {"psi", kPoundForce / (kInch * kInch), dim::pressure},
    {"ksi", 1e3 * kPoundForce / (kInch * kInch), dim::pressure},
    {"rad", 1.0, dim::angle},
    {"mrad", 1e-3, dim::angle},
    {"urad", 1e-6, dim::angle},
    {"deg", pi / 180.0, dim::angle},
    {"\xC2\xB0", pi / 180.0, dim::angle},  // DEGREE SIGN (U+00B0)
    {"rev", 2.0 * pi, dim::angle},
    {"r", 2.0 * pi, dim::angle},  // a revolution, as in r/min
    {"rpm", 2.0 * pi / 60.0, dim::angular_speed},  // rev/min
    {"RPM", 2.0 * pi / 60.0, dim::angular_speed},
    {"Hz", 2.0 * pi, dim::angular_speed},          // rev/s: angular speeds only
    {"J", 1.0, dim::moment},
    {"W", 1.0, dim::power},
    {"kW", 1e3, dim::power},
    {"P", 0.1, dim::viscosity},   // poise
    {"cP", 1e-3, dim::viscosity}, // centipoise = mPa s
    {"K", 1.0, dim::temperature},
    {"degC", 1.0, dim::temperature},  // alone: an absolute temperature, 273.15 K added (parse_quantity)
    {"\xC2\xB0" "C", 1.0, dim::temperature},
    {"cSt", 1e-6, dim::kinematic_viscosity},  // centistokes = mm^2/s
    {"B", 1.0, dim::information},  // bytes: decimal and binary multiples
    {"kB", 1e3, dim::information},
    {"MB", 1e6, dim::information},
    {"GB", 1e9, dim::information},
    {"TB", 1e12, dim::information},
    {"KiB", 1024.0, dim::information},
    {"MiB", 1024.0 * 1024.0, dim::information},
    {"GiB", 1024.0 * 1024.0 * 1024.0, dim::information},
};

// The sane ranges: generous bounds on what any rolling bearing (a miniature bearing to a 10 m
// slewing ring) and its simulation can mean; a value outside is a unit slip or a typo. A scene that
// means it names the key in [scene] allow_out_of_range.
constexpr QuantityKind kKinds[] = {
    {dim::none, "a plain number", "no unit", "", ""},
    {dim::mass, "a mass", "kg, g", "kg", "g", 1e-9, 1e5, "a microgram ball to a 100 t ring"},
    {dim::length, "a length", "m, mm, um", "m", "mm", 1e-12, 10, "tolerances and crown drops to a 10 m ring"},
    {dim::time, "a time", "s, ms, min", "s", "s", 1e-12, 1e5, "a picosecond step to a day of simulated time"},
    {dim::angle, "an angle", "rad, mrad, deg, rev", "rad", "deg", 1e-12, 1e3, "tolerances to 160 revolutions"},
    {dim::angular_speed, "an angular speed", "rpm, rad/s, Hz, deg/s", "rad/s", "rpm", 1e-9, 1e5,
     "up to 955,000 rpm, beyond the fastest spindle bearings"},
    {dim::speed, "a speed", "m/s, mm/s", "m/s", "m/s", 1e-12, 1e3, "surface speeds below 1 km/s"},
    {dim::force, "a force", "N, kN", "N", "kN", 1e-9, 1e9, "up to 1 GN"},
    {dim::moment, "a moment", "N m, J", "N m", "N m", 1e-12, 1e9, "up to 1 GN m"},
    {dim::power, "a power", "W, kW", "W", "kW", 1e-9, 1e9, "up to 1 GW"},
    {dim::pressure, "a pressure", "Pa, MPa, GPa", "Pa", "GPa", 1e3, 1e13, "moduli of soft elastomers to beyond diamond"},
    {dim::density, "a density", "kg/m^3, g/cm^3", "kg/m^3", "kg/m^3", 1, 1e5, "foams to beyond osmium"},
    {dim::viscosity, "a dynamic viscosity", "Pa s, mPa s, cP", "Pa s", "mPa s", 1e-6, 1e6, "gases to greases"},
    {dim::inverse_pressure, "a pressure-viscosity coefficient", "1/Pa, 1/GPa, m^2/N", "1/Pa", "1/GPa", 1e-12, 1e-6,
     "lubricants are 5 to 40 1/GPa"},
    {dim::stiffness, "a stiffness", "N/m, N/mm", "N/m", "N/mm", 1e-3, 1e13, "up to 10 GN/mm"},
    {dim::damping, "a damping coefficient", "N s/m", "N s/m", "N s/m", 1e-9, 1e9, "up to 1 GN s/m"},
    {dim::inertia, "a moment of inertia", "kg m^2", "kg m^2", "kg m^2", 1e-15, 1e5, "a microgram ball to a 10 m ring"},
    {dim::inverse_speed, "an inverse speed", "s/m", "s/m", "s/m", 1e-9, 1e3, "damping factors are about 0.1 to 5 s/m"},
    {dim::angular_stiffness, "a tilt stiffness", "N m/rad", "N m/rad", "N m/rad", 1e-6, 1e12, "up to 1 TN m/rad"},
    {dim::angular_damping, "a tilt damping coefficient", "N m s/rad", "N m s/rad", "N m s/rad", 1e-12, 1e9,
     "up to 1 GN m s/rad"},
    {dim::information, "a size in bytes", "B, MB, GB, GiB", "B", "GB", 1, 1e15, "up to a petabyte"},
    {dim::temperature, "a temperature", "K, degC", "K", "degC", 150, 1000, "from -120 to 730 degC"},
    {dim::kinematic_viscosity, "a kinematic viscosity", "mm^2/s, cSt", "m^2/s", "mm^2/s", 1e-8, 1e-1,
     "solvents to greases' base oils"},
    {dim::thermal_conductance, "a thermal conductance", "W/K", "W/K", "W/K", 1e-9, 1e9, "up to 1 GW/K"},
    {dim::heat_capacity, "a heat capacity", "J/K, kJ/K", "J/K", "J/K", 1e-9, 1e12, "up to 1 TJ/K"},
    {dim::specific_heat, "a specific heat", "J/kg K", "J/kg K", "J/kg K", 1, 1e5,
     "metals about 400-900, oils about 2000 J/kg K"},
    {dim::heat_transfer_coefficient, "a heat transfer coefficient", "W/m^2 K", "W/m^2 K", "W/m^2 K", 1e-3, 1e8,
     "free convection in air about 10, oil flows 100-1000, fits 1e3-1e5 W/m^2 K"},
    {Dimension{0, 0, 0, 0, 0, -1}, "an inverse temperature", "1/K", "1/K", "1/K"},
    {Dimension{0, 0, -2, 1}, "an angular acceleration", "rad/s^2", "rad/s^2", "rad/s^2"},
    {Dimension{0, 1, -2, 0}, "an acceleration", "m/s^2", "m/s^2", "m/s^2"},
    {Dimension{0, 0, -1, 0}, "a rate without angle", "1/s", "1/s", "1/s"},
};

const UnitDef* find_unit(std::string_view symbol) {
  for (const auto& u : kUnits)
    if (u.symbol == symbol) return &u;
  return nullptr;
}

// Exponents of one term; every unit needs at most ^4.
constexpr int kMaxTermExponent = 9;

bool within_exponent_limit(Dimension d) {
  for (const int e : {d.mass, d.length, d.time, d.angle, d.information, d.temperature})
    if (e < -Dimension::max_exponent || e > Dimension::max_exponent) return false;
  return true;
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
      if (exponent < -kMaxTermExponent || exponent > kMaxTermExponent)
        garbage(text, fmt::format("exponent {} after '{}^' is out of range (-{} to {})", exponent,
                                  expr.substr(start, i - 1 - start), kMaxTermExponent, kMaxTermExponent));
      i += static_cast<std::size_t>(ptr - first);
    }
    if (i < expr.size() && !is_space(expr[i]) && expr[i] != '*' && expr[i] != '/')
      garbage(text, fmt::format("unexpected '{}' in unit '{}' (exponents are written m^2)", expr.substr(i, 1), expr));
    if (in_denominator) exponent = -exponent;
    q.value *= std::pow(factor, exponent);
    q.dimension = q.dimension * d.pow(exponent);
    if (!within_exponent_limit(q.dimension))
      garbage(text, fmt::format("the unit '{}' has exponents beyond {}", expr, Dimension::max_exponent));
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
  const double unit = q.value;
  q.value *= number;
  // Celsius: an absolute temperature only where it stands alone (a compound unit means a difference: K).
  std::string_view symbol = t.substr(i);
  while (!symbol.empty() && is_space(symbol.front())) symbol.remove_prefix(1);
  const bool celsius = symbol == "degC" || symbol == "\xC2\xB0" "C";
  if (celsius) q.value += 273.15;
  else if (symbol.find("degC") != std::string_view::npos || symbol.find("\xC2\xB0" "C") != std::string_view::npos)
    garbage(text, "degC is an absolute temperature and stands alone; in a compound unit write K (e.g. \"W/K\")");
  if (!std::isfinite(q.value))
    garbage(text, fmt::format("it overflows: {:g} times {:g} (the unit in SI) is beyond any finite number", number,
                              unit));
  if (number != 0 && !std::isnormal(q.value))
    garbage(text, fmt::format("it underflows: {:g} times {:g} (the unit in SI) is too small to represent", number,
                              unit));
  return q;
}

double parse_quantity(std::string_view text, Dimension expected) {
  const Quantity q = parse_quantity(text);
  if (q.dimension != expected)
    throw UnitError(fmt::format("'{}' is {}; expected {}", text, dimension_name(q.dimension),
                                dimension_description(expected)));
  return q.value;
}

namespace {

/// "3000 has no unit: an angular speed needs one, e.g. "3000 rad/s" or "3000 rpm"; units: rpm, rad/s, ...".
/// The forms: the number in SI (what a bare number once meant), in the kind's usual unit, and the
/// key's example when it uses yet another unit ("1.42 mrad").
std::string bare_number_message(std::string_view shown, Dimension expected, std::string_view example) {
  const QuantityKind* kind = quantity_kind(expected);
  std::vector<std::string> units{kind ? std::string(kind->si) : si_unit(expected)};
  if (kind && kind->usual != kind->si) units.emplace_back(kind->usual);
  std::string forms;
  for (const std::string& u : units) forms += fmt::format("{}\"{} {}\"", forms.empty() ? "" : " or ", shown, u);
  const auto space = example.find(' ');
  if (space != std::string_view::npos &&
      std::find(units.begin(), units.end(), example.substr(space + 1)) == units.end())
    forms += fmt::format(" (like \"{}\")", example);
  return fmt::format("{} has no unit: {} needs one, e.g. {}; units: {}", shown, dimension_name(expected), forms,
                     kind ? kind->examples : units[0]);
}

}  // namespace

double parse_quantity(const toml::node& node, Dimension expected, std::string_view example) {
  std::string shown;
  double v = 0;
  if (const auto* i = node.as_integer()) {
    v = static_cast<double>(i->get()), shown = fmt::format("{}", i->get());
  } else if (const auto* f = node.as_floating_point()) {
    v = f->get(), shown = fmt::format("{}", v);
    if (!std::isfinite(v)) throw UnitError(fmt::format("{} is not a finite number", v));
  } else if (const auto* s = node.as_string()) {
    return parse_quantity(std::string_view(s->get()), expected);
  } else {
    throw UnitError(fmt::format("expected {} as a string such as \"{}\"", dimension_description(expected),
                                expected == dim::none ? "0.3" : example.empty() ? "3 mm" : example));
  }
  // A bare number is a plain number; 0 is 0 in every unit.
  if (expected != dim::none && v != 0) throw UnitError(bare_number_message(shown, expected, example));
  return v;
}

const QuantityKind* quantity_kind(Dimension d) {
  for (const auto& k : kKinds)
    if (k.dimension == d) return &k;
  return nullptr;
}

std::span<const QuantityKind> quantity_kinds() { return kKinds; }

bool within_sane_range(double value, Dimension d) {
  const QuantityKind* kind = quantity_kind(d);
  if (!kind || kind->smallest <= 0 || value == 0) return true;
  const double magnitude = std::abs(value);
  return magnitude >= kind->smallest && magnitude <= kind->largest;
}

std::string si_unit(Dimension d) {
  struct Base {
    int Dimension::*member;
    std::string_view symbol;
  };
  constexpr Base bases[] = {{&Dimension::mass, "kg"}, {&Dimension::length, "m"},
                            {&Dimension::time, "s"}, {&Dimension::angle, "rad"},
                            {&Dimension::information, "B"}, {&Dimension::temperature, "K"}};
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
  if (const auto* n = quantity_kind(d)) return std::string(n->name);
  return fmt::format("a quantity in {}", si_unit(d));
}

std::string dimension_description(Dimension d) {
  if (const auto* n = quantity_kind(d)) return fmt::format("{} ({})", n->name, n->examples);
  return fmt::format("a quantity in {}", si_unit(d));
}

std::vector<std::string_view> unit_symbols() {
  std::vector<std::string_view> v;
  for (const auto& u : kUnits) v.push_back(u.symbol);
  return v;
}

}  // namespace raceway::scene
