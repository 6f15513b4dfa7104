// Units: conversions to SI, dimension checks, rejected garbage; TimeFunction evaluation.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "io/scene/scene.hpp"
#include "io/scene/units.hpp"

namespace raceway::scene {
namespace {

constexpr double pi = std::numbers::pi;

double si(const char* text, Dimension d) { return parse_quantity(std::string_view(text), d); }

TEST(Units, ConvertsToSI) {
  EXPECT_NEAR(si("17.462 mm", dim::length), 0.017462, 1e-15);
  EXPECT_NEAR(si("3000 rpm", dim::angular_speed), 3000.0 * 2.0 * pi / 60.0, 1e-12);
  EXPECT_NEAR(si("3000 rpm", dim::angular_speed), 314.159265358979, 1e-9);
  EXPECT_DOUBLE_EQ(si("1 kN", dim::force), 1000.0);
  EXPECT_DOUBLE_EQ(si("208 GPa", dim::pressure), 208e9);
  EXPECT_NEAR(si("0.1 ms", dim::time), 1e-4, 1e-18);
  EXPECT_NEAR(si("40 Hz", dim::angular_speed), 251.327412287183, 1e-9);  // Hz = rev/s
  EXPECT_DOUBLE_EQ(si("5 N s/m", dim::damping), 5.0);
  EXPECT_NEAR(si("0.02 1/GPa", dim::inverse_pressure), 2e-11, 1e-24);
  EXPECT_NEAR(si("1/GPa", dim::inverse_pressure), 1e-9, 1e-22);
  EXPECT_NEAR(si("2e-8 m^2/N", dim::inverse_pressure), 2e-8, 1e-22);
  EXPECT_NEAR(si("40 mPa s", dim::viscosity), 0.04, 1e-15);
  EXPECT_NEAR(si("40 cP", dim::viscosity), 0.04, 1e-15);
  EXPECT_NEAR(si("0.4 P", dim::viscosity), 0.04, 1e-15);
  EXPECT_DOUBLE_EQ(si("7850 kg/m^3", dim::density), 7850.0);
  EXPECT_NEAR(si("7.85 g/cm^3", dim::density), 7850.0, 1e-9);
  EXPECT_DOUBLE_EQ(si("2 N/mm", dim::stiffness), 2000.0);
  EXPECT_NEAR(si("3 um", dim::length), 3e-6, 1e-20);
  EXPECT_NEAR(si("3 \xC2\xB5m", dim::length), 3e-6, 1e-20);  // MICRO SIGN
  EXPECT_NEAR(si("3 \xCE\xBCm", dim::length), 3e-6, 1e-20);  // GREEK SMALL LETTER MU
  EXPECT_NEAR(si("90 deg", dim::angle), pi / 2, 1e-15);
  EXPECT_NEAR(si("180 deg/s", dim::angular_speed), pi, 1e-15);
  EXPECT_NEAR(si("1 rev/min", dim::angular_speed), si("1 rpm", dim::angular_speed), 1e-15);
  EXPECT_NEAR(si("2 rad/s", dim::angular_speed), 2.0, 1e-15);
  EXPECT_DOUBLE_EQ(si("3 N*m", dim::moment), 3.0);
  EXPECT_DOUBLE_EQ(si("3 J", dim::moment), 3.0);
  EXPECT_DOUBLE_EQ(si("2 kg m^2", dim::inertia), 2.0);
  EXPECT_DOUBLE_EQ(si("  -4.5e3   N  ", dim::force), -4500.0);
  EXPECT_DOUBLE_EQ(si("0.3", dim::none), 0.3);
  EXPECT_DOUBLE_EQ(si("1 h", dim::time), 3600.0);
  EXPECT_NEAR(si("1 W", dim::power), 1.0, 0);
  EXPECT_NEAR(si("3 m s^-1", dim::speed), 3.0, 0);
  EXPECT_NEAR(si("1.42 mrad", dim::angle), 1.42e-3, 1e-18);
  EXPECT_NEAR(si("50 urad", dim::angle), 5e-5, 1e-19);
  EXPECT_DOUBLE_EQ(si("5e4 N m/rad", dim::angular_stiffness), 5e4);
  EXPECT_NEAR(si("5 N m/mrad", dim::angular_stiffness), 5e3, 1e-9);
  EXPECT_DOUBLE_EQ(si("2.5 N m s/rad", dim::angular_damping), 2.5);
}

std::string node_error(const toml::node& n, Dimension d, std::string_view example = {}) {
  try {
    (void)parse_quantity(n, d, example);
  } catch (const UnitError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Units, TomlNodes) {
  const toml::value<double> f(2.5);
  const toml::value<int64_t> i(3000);
  const toml::value<std::string> s(std::string("2.5 mm"));
  const toml::value<bool> b(true);
  EXPECT_DOUBLE_EQ(parse_quantity(f, dim::none), 2.5);  // a bare number is a plain number
  EXPECT_DOUBLE_EQ(parse_quantity(i, dim::none), 3000.0);
  EXPECT_DOUBLE_EQ(parse_quantity(s, dim::length), 2.5e-3);
  EXPECT_THROW(parse_quantity(b, dim::length), UnitError);
  // 0 is 0 in every unit; any other bare number for a dimensional quantity shows the form to write.
  EXPECT_DOUBLE_EQ(parse_quantity(toml::value<int64_t>(0), dim::length), 0.0);
  EXPECT_DOUBLE_EQ(parse_quantity(toml::value<double>(0.0), dim::force), 0.0);
  EXPECT_EQ(node_error(i, dim::angular_speed),
            "3000 has no unit: an angular speed needs one, e.g. \"3000 rad/s\" or \"3000 rpm\"; units: rpm, rad/s, Hz, "
            "deg/s");
  EXPECT_EQ(node_error(f, dim::length), "2.5 has no unit: a length needs one, e.g. \"2.5 m\" or \"2.5 mm\"; units: m, mm, um");
  EXPECT_EQ(node_error(f, dim::time), "2.5 has no unit: a time needs one, e.g. \"2.5 s\"; units: s, ms, min");
  EXPECT_NE(node_error(f, dim::angle, "1.42 mrad").find("(like \"1.42 mrad\")"), std::string::npos);
  EXPECT_NE(node_error(toml::value<double>(std::numeric_limits<double>::infinity()), dim::none).find("not a finite"),
            std::string::npos);
  EXPECT_NE(node_error(toml::value<double>(std::nan("")), dim::none).find("not a finite"), std::string::npos);
}

TEST(Units, CommonSpellings) {
  const double rpm = 2.0 * pi / 60.0;
  for (const char* text : {"3000 rpm", "3000 RPM", "3000 r/min", "3000 rev/min", "50 rev/s", "50 Hz"})
    EXPECT_NEAR(si(text, dim::angular_speed), 3000 * rpm, 1e-9) << text;
  EXPECT_DOUBLE_EQ(si("1 in", dim::length), 0.0254);
  EXPECT_DOUBLE_EQ(si("2 ft", dim::length), 0.6096);
  EXPECT_NEAR(si("1 thou", dim::length), 25.4e-6, 1e-20);
  EXPECT_NEAR(si("1 lbf", dim::force), 4.4482216152605, 1e-12);  // 0.45359237 kg x 9.80665 m/s^2
  EXPECT_DOUBLE_EQ(si("1 lb", dim::mass), 0.45359237);
  EXPECT_NEAR(si("1 psi", dim::pressure), 6894.757293168, 1e-8);
  EXPECT_NEAR(si("30e3 ksi", dim::pressure), 206.8427e9, 1e5);
  EXPECT_NEAR(si("10 lbf in", dim::moment), 1.12985, 1e-5);
  EXPECT_DOUBLE_EQ(si("3 Nm", dim::moment), 3.0);
  EXPECT_DOUBLE_EQ(si("2 MN", dim::force), 2e6);
  EXPECT_NEAR(si("90 \xC2\xB0", dim::angle), pi / 2, 1e-15);  // DEGREE SIGN
  EXPECT_DOUBLE_EQ(si("4 GB", dim::information), 4e9);
  EXPECT_DOUBLE_EQ(si("1 GiB", dim::information), 1073741824.0);
}

TEST(Units, SaneRanges) {
  EXPECT_TRUE(within_sane_range(0.0, dim::time));
  EXPECT_TRUE(within_sane_range(0.1, dim::time));
  EXPECT_FALSE(within_sane_range(1e-300, dim::time));
  EXPECT_FALSE(within_sane_range(1e300, dim::time));
  EXPECT_FALSE(within_sane_range(si("1e12 rpm", dim::angular_speed), dim::angular_speed));
  EXPECT_TRUE(within_sane_range(si("300000 rpm", dim::angular_speed), dim::angular_speed));
  EXPECT_FALSE(within_sane_range(1e39, dim::pressure));
  EXPECT_TRUE(within_sane_range(208e9, dim::pressure));
  EXPECT_TRUE(within_sane_range(-5e4, dim::force));
  EXPECT_TRUE(within_sane_range(1e300, dim::none));  // plain numbers have their keys' own bounds
  for (const QuantityKind& k : quantity_kinds()) {
    if (k.smallest <= 0) continue;
    EXPECT_LT(k.smallest, k.largest) << k.name;
    EXPECT_FALSE(k.why.empty()) << k.name;
    EXPECT_EQ(parse_quantity(std::string_view("1 " + std::string(k.si))).dimension, k.dimension) << k.name;
    EXPECT_EQ(parse_quantity(std::string_view("1 " + std::string(k.usual))).dimension, k.dimension) << k.name;
  }
}

std::string error_of(const char* text, Dimension d) {
  try {
    (void)parse_quantity(std::string_view(text), d);
  } catch (const UnitError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Units, WrongDimensionSaysWhatWasFoundAndExpected) {
  EXPECT_EQ(error_of("3000 mm", dim::angular_speed),
            "'3000 mm' is a length; expected an angular speed (rpm, rad/s, Hz, deg/s)");
  EXPECT_EQ(error_of("3000 rpm", dim::length), "'3000 rpm' is an angular speed; expected a length (m, mm, um)");
  EXPECT_NE(error_of("5 N s", dim::damping).find("is a quantity in kg m s^-1; expected a damping coefficient"),
            std::string::npos);
  EXPECT_NE(error_of("40 Hz", Dimension{0, 0, -1, 0}).find("is an angular speed"), std::string::npos);
  EXPECT_NE(error_of("3 mm", dim::none).find("expected a plain number"), std::string::npos);
  EXPECT_NE(error_of("1", dim::length).find("is a plain number; expected a length"), std::string::npos);
}

TEST(Units, RejectsGarbage) {
  for (const char* bad : {"12 parsecs", "mm", "", "   ", "1e3 m m/", "3 mm^", "3 m^x", "3 m2", "3 kg/m/s", "3 * m",
                          "3 m**2", "abc", "nan m", "inf", "3 m^0", "+-3 m", "3 1 m 2"}) {
    EXPECT_THROW(parse_quantity(std::string_view(bad)), UnitError) << "'" << bad << "'";
  }
  EXPECT_NE(error_of("12 parsecs", dim::length).find("unknown unit 'parsecs'"), std::string::npos);
  EXPECT_NE(error_of("mm", dim::length).find("does not start with a number"), std::string::npos);
  EXPECT_NE(error_of("", dim::length).find("empty"), std::string::npos);
  EXPECT_NE(error_of("1e3 m m/", dim::length).find("ends with an operator"), std::string::npos);
}

TEST(Units, ExponentsAndMagnitudesAreBounded) {
  // Exponents beyond 9 (a 2^31 exponent once overflowed an int) and results that overflow or
  // underflow in SI are errors, never inf or 0.
  for (const char* bad : {"1 m^2147483648", "1 m^2147483647", "1 m^-2147483648", "1 m^10", "1 s^-10",
                          "1 m^99999999999999999999", "1e307 h", "1e308 km", "1e-320 nm", "1e300 GPa^2",
                          "1 m^9 m^9 m^9 m^9 m^9 m^9 m^9 m^9"})
    EXPECT_THROW(parse_quantity(std::string_view(bad)), UnitError) << bad;
  EXPECT_NE(error_of("1 m^2147483648", dim::length).find("bad exponent"), std::string::npos);
  EXPECT_NE(error_of("1 m^12", dim::length).find("exponent 12 after 'm^' is out of range (-9 to 9)"), std::string::npos);
  EXPECT_NE(error_of("1e307 h", dim::time).find("overflows"), std::string::npos);
  EXPECT_NE(error_of("1e-320 nm", dim::length).find("underflows"), std::string::npos);
  EXPECT_NEAR(si("1 m^9/m^8", dim::length), 1.0, 1e-15);
}

// Temperatures: kelvin, and Celsius as an absolute temperature where it stands alone; kinematic
// viscosities in mm^2/s or cSt.
TEST(Units, TemperaturesAndKinematicViscosities) {
  EXPECT_DOUBLE_EQ(si("313.15 K", dim::temperature), 313.15);
  EXPECT_NEAR(si("40 degC", dim::temperature), 313.15, 1e-12);
  EXPECT_NEAR(si("-20 \xC2\xB0" "C", dim::temperature), 253.15, 1e-12);
  EXPECT_NEAR(si("68 mm^2/s", dim::kinematic_viscosity), 68e-6, 1e-18);
  EXPECT_NEAR(si("68 cSt", dim::kinematic_viscosity), 68e-6, 1e-18);
  EXPECT_DOUBLE_EQ(si("2 W/K", Dimension{1, 2, -3, 0, 0, -1}), 2.0);
  EXPECT_NE(error_of("2 W/degC", Dimension{1, 2, -3, 0, 0, -1}).find("stands alone"), std::string::npos);
  EXPECT_NE(error_of("40 degC", dim::length).find("is a temperature; expected a length"), std::string::npos);
}

TEST(Units, DimensionNames) {
  EXPECT_EQ(si_unit(dim::pressure), "kg m^-1 s^-2");
  EXPECT_EQ(si_unit(dim::angular_speed), "s^-1 rad");
  EXPECT_EQ(si_unit(dim::none), "1");
  EXPECT_EQ(dimension_name(dim::length), "a length");
  EXPECT_EQ(dimension_description(dim::angular_speed), "an angular speed (rpm, rad/s, Hz, deg/s)");
  EXPECT_EQ(dimension_description(dim::angular_stiffness), "a tilt stiffness (N m/rad)");
  EXPECT_EQ(dimension_name(dim::angular_damping), "a tilt damping coefficient");
  EXPECT_NE(error_of("5e4 N m", dim::angular_stiffness).find("is a moment; expected a tilt stiffness"),
            std::string::npos);
}

TEST(TimeFunction, ConstantAndEmpty) {
  const auto c = TimeFunction::constant(3.5);
  EXPECT_DOUBLE_EQ(c(-1.0), 3.5);
  EXPECT_DOUBLE_EQ(c(1e9), 3.5);
  EXPECT_DOUBLE_EQ(c.derivative(0.3), 0.0);
  EXPECT_FALSE(c.is_zero());
  EXPECT_TRUE(TimeFunction::constant(0.0).is_zero());
  EXPECT_TRUE(TimeFunction{}.is_zero());
  EXPECT_DOUBLE_EQ(TimeFunction{}(1.0), 0.0);
}

TEST(TimeFunction, InterpolatesAndHolds) {
  const TimeFunction f{{0.0, 0.05, 0.1}, {0.0, 100.0, 40.0}};
  EXPECT_DOUBLE_EQ(f(-1.0), 0.0);        // held before the first point
  EXPECT_DOUBLE_EQ(f(0.0), 0.0);
  EXPECT_DOUBLE_EQ(f(0.025), 50.0);
  EXPECT_DOUBLE_EQ(f(0.05), 100.0);
  EXPECT_NEAR(f(0.075), 70.0, 1e-12);
  EXPECT_DOUBLE_EQ(f(0.1), 40.0);
  EXPECT_DOUBLE_EQ(f(5.0), 40.0);         // held after the last point
  EXPECT_DOUBLE_EQ(f.derivative(-1.0), 0.0);
  EXPECT_DOUBLE_EQ(f.derivative(0.01), 2000.0);
  EXPECT_DOUBLE_EQ(f.derivative(0.05), -1200.0);  // right-hand slope at a knot
  EXPECT_DOUBLE_EQ(f.derivative(0.07), -1200.0);
  EXPECT_DOUBLE_EQ(f.derivative(0.1), 0.0);
  EXPECT_DOUBLE_EQ(f.derivative(2.0), 0.0);
  EXPECT_FALSE(f.is_zero());
  EXPECT_TRUE((TimeFunction{{0.0, 1.0}, {0.0, 0.0}}).is_zero());
}

}  // namespace
}  // namespace raceway::scene
