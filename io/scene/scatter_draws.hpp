// Seeded scatter of the rolling elements' diameters and the cage's pocket clearances: standard normal
// draws that are the same on every machine, compiler and rank.
//
// std::mt19937_64 is specified bit for bit by the C++ standard, but std::normal_distribution (and
// every other std distribution) is not: libstdc++, libc++ and MSVC turn the same engine output into
// different numbers. So the transform is written here: Box-Muller on two 53-bit uniforms. The draws
// are drawn once while the scene is read (on every rank alike) and then stored in the scene, so
// nothing later depends on a generator's state.
#pragma once

#include <cstdint>
#include <vector>

namespace raceway::scene {

/// Independent streams of one seed: the balls' diameters and the pockets' clearances draw from
/// different engines, so giving one list explicitly does not shift the other's draws.
enum class ScatterStream : std::uint64_t { element_diameter = 1, pocket_clearance = 2 };

/// `count` standard normal deviates (mean 0, standard deviation 1) of `seed` and `stream`.
std::vector<double> standard_normal_draws(std::uint64_t seed, ScatterStream stream, int count);

}  // namespace raceway::scene
