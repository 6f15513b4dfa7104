// What differs between bearing kinds in the equations of motion: how a body's state rates follow
// from the forces on it. The equations (solver/bearing/equations.hpp) sum the contact wrenches of
// all segments; a BodyDynamics adds loads, supports and gravity and turns the net wrench into
// rates, one body at a time (a virtual call per body, none per contact).
//
//  - planar (PlanarDynamics): Newton in x, y and Euler about z in the inertial bearing frame;
//    centrifugal effects come out of the Cartesian equations;
//  - spatial (SpatialDynamics): Newton in x, y, z; balls are spheres (I dw/dt = M); the cage uses
//    Euler's equations in its principal frame with the gyroscopic term; rings the small-tilt rotor
//    equations with the gyroscopic coupling of their spin
//    (I_t dwx/dt = Mx - I_z spin wy, I_t dwy/dt = My + I_z spin wx).
#pragma once

#include <memory>
#include <vector>

#include "solver/bearing/model.hpp"
#include "solver/numerics/bordered_matrix.hpp"

namespace raceway::bearing {

using Wrench = contact::SpatialWrench;

/// Finite-difference increments per state. Positions and angles: a contact sees differences of
/// positions, not their size, and its approach may be a few nm (an outer contact carrying only the
/// centrifugal force), so the step is absolute: rel * 1e-3 * the tolerance scale (2.3e-12 m for a
/// 22.9 mm pitch radius at rel = 1e-7), far below any closed contact's approach and far above
/// round-off. Velocities: relative to the value, with the tolerance scale as a floor.
class FiniteDifferenceSteps {
 public:
  explicit FiniteDifferenceSteps(const Model& model);
  double operator()(int state, const double* z) const;

 private:
  double relative_ = 0;
  std::vector<double> scale_;          ///< physical scale per state
  std::vector<double> position_step_;  ///< absolute step (positions, angles), else 0
};

/// The power of a body's external forces (loads, supports, gravity, the carrier frame's inertial
/// forces, the cage's unbalance) on its states that is not the rate of a potential kept in
/// body_energy, by origin [W] (solver/bearing/power_terms.hpp).
struct ExternalPower {
  double loads = 0;         ///< the applied loads (their potential is left out of the stored energy)
  double support_loss = 0;  ///< dissipated in the support's dampers (>= 0)
  double frame = 0;         ///< carrier frame: Euler force and moment, the centrifugal potential's change in time
  double unbalance = 0;     ///< the cage's unbalance force (not a potential)
};

class BodyDynamics {
 public:
  virtual ~BodyDynamics() = default;
  /// The net wrench on body b (contacts + loads + supports + gravity) and, if b has states, the
  /// rates of its states into zdot.
  virtual void rates(int b, double t, const double* z, const Wrench& contacts, Wrench& net, double* zdot) const = 0;
  /// The rates of body b's velocity-type coordinates caused by a contact wrench dw (linear in dw):
  /// rates[c] for c in svx..swz, zero elsewhere. Used to assemble the contact part of the Jacobian.
  virtual void contact_rate_derivative(int b, const double* z, const Wrench& dw,
                                       double rates[coordinate_count]) const = 0;
  /// Each body's own Jacobian terms (kinematic rows, supports, gyroscopic terms), contacts frozen.
  virtual void add_body_jacobian(double t, const double* z, const std::vector<Wrench>& contacts,
                                 const FiniteDifferenceSteps& step, numerics::BorderedMatrix& jac) const = 0;
  /// Kinetic energy + support springs + potential of the current loads and gravity [J] (the
  /// contacts' elastic energy comes from the segment records).
  virtual double body_energy(double t, const double* z) const = 0;
  /// Body b's external power (ExternalPower) at (t, z).
  virtual ExternalPower external_power(int b, double t, const double* z) const = 0;
  /// The part of body_energy that is the potential of body b's applied loads [J].
  virtual double load_potential(int b, double t, const double* z) const = 0;
};

/// The dynamics of the model's kind.
std::unique_ptr<BodyDynamics> make_body_dynamics(const Model& model);

}  // namespace raceway::bearing
