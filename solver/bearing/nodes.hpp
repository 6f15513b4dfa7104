// Nodes: blocks of coordinates that are not a rigid body's: a flexible ring's modal amplitudes, a
// cage bridge's bending angle relative to the cage, later thermal states (first-order, no mass).
// A rigid body's coordinates are its slots (model.hpp) and its rates come from the space's
// BodyDynamics; a node brings its own rates, Jacobian terms, energy, tolerances and start, so the
// equations, the model and the dynamics know no node kind by name.
//
// Forces reach a node through its markers (marker.hpp): an element's wrench on a marker becomes the
// node's generalized forces (J^T f), summed in the canonical element order like every sum, in the
// node's slots of Loads::node.
#pragma once

#include <string>
#include <vector>

#include "contact/segments/ball_segments.hpp"
#include "solver/numerics/bordered_matrix.hpp"

namespace raceway::bearing {

struct Model;

class Node {
 public:
  virtual ~Node() = default;
  /// Name for the model's description ("outer_ring_modes", "cage_bridge[3]").
  virtual std::string name() const = 0;
  /// Its generalized-force slots (summed by the equations from its markers' scatter).
  virtual int force_count() const = 0;
  /// The rates of its states into zdot from its generalized forces `forces`. The rigid bodies'
  /// rates are in zdot already (a relative coordinate may read its carrier's).
  virtual void rates(const Model& m, double t, const double* z, const double* forces, double* zdot) const = 0;
  /// Adds to its rates what the segments' records of the same right-hand side give it (a thermal
  /// network's heat from their power losses), after every node's rates().
  virtual void add_segment_rates(const Model&, double, const double*, const double*, double*) const {}
  /// Its own Jacobian terms (kinematic rows), the contacts' parts come through its markers.
  virtual void add_own_jacobian(const Model& m, double t, numerics::BorderedMatrix& jac) const = 0;
  /// Adds its kinetic (and field) energy to e term by term [J] (the order of the sum is part of the
  /// output's bits); its springs' elastic energy comes from their element records.
  virtual void add_energy(const Model& m, double t, const double* z, double& e) const = 0;
  /// The power its own dampers dissipate at (t, z) [W] (>= 0; its springs' elements report theirs).
  virtual double power_loss(const Model&, double, const double*) const { return 0.0; }
  /// Overrides the class-based absolute tolerances of its states where it knows better.
  virtual void set_tolerances(std::vector<double>&) const {}
  /// Its states at the start of a run.
  virtual void initial_state(std::vector<double>& z) const = 0;
  /// Lines for the model's description (raceway check), in the bodies' format.
  virtual std::string describe(const Model& m) const = 0;
  /// First slot of its generalized forces in Loads::node (set by Model::add_node).
  int force_offset = 0;
};

}  // namespace raceway::bearing
