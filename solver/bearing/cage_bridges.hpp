// Flexible cage bridges (seed 003 2.1 and 2.2.1): each bar between two roller pockets is a beam
// clamped in the cage's side rings, loaded by the roller along its length. Its tangential
// deflection is a state in the border (with the cage), not condensed: under the carrier's field a
// pocket force of 10 kN bends a bridge by about 0.1 mm, a quarter of the pocket clearance, at a
// rate comparable to the roller's impact speed, and the squeeze film of the roller/cage contact
// (seed 003 2.2.1) sees that rate; the bridge's first bending mode (about 50 kHz in seed 003's
// bearing) is only a few times faster than an impact. A bridge couples two rollers (the one ahead
// of it and the one behind), so its states cannot live in a roller's block.
#pragma once

#include <string>
#include <vector>

#include "io/scene/scene.hpp"
#include "solver/bearing/model.hpp"

namespace raceway::bearing {

/// A bridge as a beam: section, span, material and what follows from them.
struct BridgeBeam {
  double thickness = 0;  ///< m, circumferential (the bending direction)
  double height = 0;     ///< m, radial
  double span = 0;       ///< m, between the cage's side rings (the roller-bar contact length)
  double youngs_modulus = 0;  ///< Pa
  double area_moment = 0;     ///< m^4, height thickness^3 / 12
  double shear_modulus = 0;      ///< Pa, E / (2 (1 + nu))
  double shear_coefficient = 0;  ///< Cowper's for a rectangle, 10 (1 + nu) / (12 + 11 nu); 0: no shear
  double stiffness = 0;       ///< N/m, pocket force over the mean deflection along the span
  double mass = 0;            ///< kg, of the bar
  double modal_mass = 0;      ///< kg, for the mean deflection as coordinate
  double damping = 0;         ///< N s/m
};

/// The beam of the scene's bridges. Clamped at both ends and loaded uniformly along its span (the
/// roller's line contact, q = F / L), a beam bends as w_b(x) = q x^2 (L - x)^2 / (24 E I) and, with
/// [cage] bridge_theory = "timoshenko", shears as w_s(x) = q x (L - x) / (2 kappa G A) (the shear
/// force q (L/2 - x) over the shear stiffness; Cowper's kappa for the rectangle). The pocket force
/// does work on the mean deflection u = F L^3 / (720 E I) + F L / (12 kappa G A), hence k = F / u
/// (or the scene's bridge_stiffness): the shear part is 60 E I / (kappa G A L^2) = 5 (E / kappa G)
/// (t / L)^2 of the bending part, 0.7 for seed 003's brass bars (L / t = 4.7). With that static
/// shape as the mode the mass for u follows from Rayleigh's kinetic energy, the bar's translation
/// and (Timoshenko) its sections' rotation w_b' (rotary inertia rho I): 10/7 of the bar's mass for
/// bending alone, which puts the first frequency 0.4 % above the exact 22.37 sqrt(E I / (m L^3)).
/// `cage_height`: the cage's radial section.
BridgeBeam bridge_beam(const scene::Scene& scene, double cage_height);

/// A bridge's bending: its angle and rate relative to the cage (two border states), the moment on it
/// as its generalized force. Its marker (the pocket bars riding on it) translates with the cage and
/// turns by the cage's angle plus its own; the force on it moves the cage.
class CageBridge final : public Node {
 public:
  CageBridge(int index, int count, int cage, int angle_state, const BridgeBeam& beam, double pitch_radius,
             double angle_tolerance);
  int angle_state() const { return angle_; }
  int rate_state() const { return rate_; }
  int cage() const { return cage_; }
  double inertia() const { return inertia_; }
  /// Adds d(bending acceleration)/d(state) from a derivative dm of the moment on the bridge.
  void add_moment_derivative(int state, double dm, numerics::BorderedMatrix& jac) const;

  std::string name() const override;
  int force_count() const override { return 1; }
  void rates(const Model& m, double t, const double* z, const double* forces, double* zdot) const override;
  void add_own_jacobian(const Model& m, double t, numerics::BorderedMatrix& jac) const override;
  void add_energy(const Model& m, double t, const double* z, double& e) const override;
  void set_tolerances(std::vector<double>& atol) const override;
  void initial_state(std::vector<double>& z) const override;
  std::string describe(const Model& m) const override;

 private:
  int index_, count_, cage_, angle_, rate_;
  double mass_, inertia_, angle_tolerance_, rate_tolerance_;
};

/// With [cage] bridges = "flexible": one node per bridge (bridge k lies between pockets k and k + 1)
/// with its marker; the cage keeps its inertia less the bridges' modal inertia. Call right after the
/// cage's states.
void add_cage_bridges(Model& m, const scene::Scene& scene, double cage_height);

/// The bridge springs (one cage_bridge element per bridge), after the pocket elements.
void add_cage_bridge_segments(Model& m, const scene::Scene& scene, double cage_height);

/// The marker of the bar ahead of (side +1) or behind (side -1) pocket k: a bridge's, or -1 (the
/// cage's centre) when the bridges are rigid.
int pocket_bar_marker(const Model& m, int k, int side);

/// The model's bridges (empty when they are rigid).
std::vector<const CageBridge*> cage_bridges_of(const Model& m);
/// The model description's line for the bridge springs.
std::string describe_bridge_segments(const Model& m);

}  // namespace raceway::bearing
