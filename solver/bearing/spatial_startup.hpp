// A consistent initial state for the spatial ball bearing: rings displaced and balls seated so
// that contact forces balance the loads, supports, gravity and the balls' centrifugal force at the
// epicyclic orbital speed; then velocities for rolling without sliding.
#pragma once

#include <string>
#include <vector>

#include "solver/bearing/spatial_model.hpp"

namespace raceway::solver {

struct SpatialStartupReport {
  std::vector<double> state;
  int iterations = 0;
  double residual = 0;  ///< N, largest unbalanced force (ring or ball) at the solution
  std::vector<double> inner_contact_force;  ///< N, per ball: sum of its inner-groove normal forces
  std::vector<double> outer_contact_force;  ///< N, per ball: sum of its outer-groove normal forces
  std::string summary;
};

/// Quasi-static seating at t0 (Jones-Harris style, but with the same contact functions the dynamics
/// use): unknowns are the free ring coordinates (translation, tilt) and each ball's radial and axial
/// position in its azimuthal plane; Levenberg-Marquardt on the force balance (robust from open
/// contacts). The cage is centred with its pockets on the balls, turning at the epicyclic speed.
/// Ball spin: least-squares rolling without sliding at its loaded contacts.
/// Throws std::runtime_error when no equilibrium is found.
/// `azimuth_offset` turns the whole ball set and the cage about z (ball k starts at
/// offset + 2 pi k / Z): with the loads turned by the same angle, the same physical state.
SpatialStartupReport spatial_initial_state(const SpatialModel& model, double t0, double azimuth_offset = 0.0);

}  // namespace raceway::solver
