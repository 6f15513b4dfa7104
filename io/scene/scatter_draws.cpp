#include "io/scene/scatter_draws.hpp"

#include <cmath>
#include <numbers>
#include <random>

namespace raceway::scene {

namespace {

/// A uniform in (0, 1]: the top 53 bits of a 64-bit draw, plus one, over 2^53 (never 0, so the
/// logarithm below is finite). Written by hand for the same reason as the transform
/// (std::generate_canonical's rounding differs between standard libraries).
double unit_interval(std::mt19937_64& engine) {
  return (static_cast<double>(engine() >> 11) + 1.0) * 0x1.0p-53;
}

}  // namespace

std::vector<double> standard_normal_draws(std::uint64_t seed, ScatterStream stream, int count) {
  // The stream is mixed into the seed with an odd 64-bit constant (the golden ratio's), so streams
  // of neighbouring seeds do not coincide.
  std::mt19937_64 engine(seed ^ (static_cast<std::uint64_t>(stream) * 0x9E3779B97F4A7C15ull));
  std::vector<double> draws;
  draws.reserve(static_cast<std::size_t>(count));
  while (static_cast<int>(draws.size()) < count) {
    // Box-Muller: two uniforms give two independent standard normals.
    const double radius = std::sqrt(-2.0 * std::log(unit_interval(engine)));
    const double angle = 2.0 * std::numbers::pi * unit_interval(engine);
    draws.push_back(radius * std::cos(angle));
    if (static_cast<int>(draws.size()) < count) draws.push_back(radius * std::sin(angle));
  }
  return draws;
}

}  // namespace raceway::scene
