// Flexible cage bridges (seed 003 2.1 and 2.2.1): each bar between two roller pockets is a beam
// clamped in the cage's side rings, loaded by the roller along its length. Its tangential
// deflection is a state in the border (with the cage), not condensed: under the carrier's field a
// pocket force of 10 kN bends a bridge by about 0.1 mm, a quarter of the pocket clearance, at a
// rate comparable to the roller's impact speed, and the squeeze film of the roller/cage contact
// (seed 003 2.2.1) sees that rate; the bridge's first bending mode (about 50 kHz in seed 003's
// bearing) is only a few times faster than an impact. A bridge couples two rollers (the one ahead
// of it and the one behind), so its states cannot live in a roller's block.
#pragma once

#include <vector>

#include "io/scene/scene.hpp"
#include "solver/bearing/model.hpp"

namespace raceway::solver {

/// A bridge as a beam: section, span, material and what follows from them.
struct BridgeBeam {
  double thickness = 0;  ///< m, circumferential (the bending direction)
  double height = 0;     ///< m, radial
  double span = 0;       ///< m, between the cage's side rings (the roller-bar contact length)
  double youngs_modulus = 0;  ///< Pa
  double area_moment = 0;     ///< m^4, height thickness^3 / 12
  double stiffness = 0;       ///< N/m, pocket force over the mean deflection along the span
  double mass = 0;            ///< kg, of the bar
  double modal_mass = 0;      ///< kg, for the mean deflection as coordinate
  double damping = 0;         ///< N s/m
};

/// The beam of the scene's bridges. Clamped at both ends and loaded uniformly along its span (the
/// roller's line contact), a beam bends as w(x) = q x^2 (L - x)^2 / (24 E I); the pocket force
/// F = q L does work on the mean deflection u = F L^3 / (720 E I), hence k = 720 E I / L^3 (or
/// the scene's bridge_stiffness). With that static shape as the mode, the mass for u is 10/7 of
/// the bar's (Rayleigh), which puts the first bending frequency 0.4 % above the exact
/// 22.37 sqrt(E I / (m L^3)). `cage_height`: the cage's radial section.
BridgeBeam bridge_beam(const io::Scene& scene, double cage_height);

/// With [cage] bridges = "flexible": one body per bridge (bridge k lies between pockets k and
/// k + 1), riding on the cage (Body::carrier): its angle and rate relative to the cage's (its
/// bending) are two border states, and the cage keeps its inertia less the bridges' modal inertia.
/// Call right after the cage's states; the bodies follow the rolling elements (Model::bodies).
void add_cage_bridges(Model& m, const io::Scene& scene, double cage_height);

/// The bridge springs (one cage_bridge segment per bridge), after the pocket segments.
void add_cage_bridge_segments(Model& m, const io::Scene& scene, double cage_height);

/// Absolute tolerances of the bridges' bending states. The angle class's (rtol rad) would allow
/// k R rtol of bridge force, 21 N at rtol 1e-6 in seed 003's bearing, the size of the pocket
/// forces without the carrier: the bending angle gets rtol F / (k R), F the largest ring load (at
/// least 1 N), so the bridge force is resolved to rtol F; its rate that times the bending frequency.
void set_bridge_tolerances(const Model& m, std::vector<double>& atol);

/// The body carrying the bar ahead of (side +1) or behind (side -1) pocket k: a bridge, or the cage.
int pocket_bar_body(const Model& m, int k, int side);

}  // namespace raceway::solver
