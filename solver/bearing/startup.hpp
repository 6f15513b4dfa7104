// A consistent initial state: rings seated under their loads, rolling elements at the epicyclic
// orbit with their rolling spin, the cage at the epicyclic speed, so the start-up transient is short.
// One entry point; the seating itself differs by bearing kind (roller_startup.cpp, ball_startup.cpp).
#pragma once

#include <string>
#include <vector>

#include "solver/bearing/model.hpp"

namespace raceway::bearing {

class Equations;

struct StartupReport {
  std::vector<double> state;
  int iterations = 0;        ///< Newton (planar) or Levenberg-Marquardt (spatial) iterations
  double residual = 0;       ///< N, largest unbalanced force at the solution
  std::vector<double> inner_contact_force;  ///< N, per rolling element: its inner-race normal forces (spatial)
  std::vector<double> outer_contact_force;  ///< N, per rolling element: its outer-race normal forces (spatial)
  double pocket_force = 0;   ///< N, largest pocket force of the start (spatial: the cage placed on the balls)
  std::string summary;
};

/// The consistent initial state of the model at t0. `azimuth_offset` (spatial ball bearings; a
/// spatial roller bearing starts from its planar seating and takes none) turns the whole
/// ball set and the cage about z (ball k starts at offset + 2 pi k / Z): with the loads turned by
/// the same angle, the same physical state. Throws std::runtime_error when no equilibrium is found.
/// `equations` (spatial): where it has heavy contacts (cut into parts), the seating's contact
/// evaluations go through its executor, spread over the ranks like a right-hand side's
/// (Equations::add_groove_loads_at_rest: the same bits); otherwise, or nullptr: evaluated here.
StartupReport initial_state(const Model& model, double t0, double azimuth_offset = 0.0, Equations* equations = nullptr);

/// Planar roller bearing: ring centres moved until the roller contact forces balance the loads
/// (each roller's radial position balancing its inner and outer contact and its centrifugal force
/// at the epicyclic orbital speed), then velocities set to pure rolling.
StartupReport seat_roller_bearing(const Model& model, double t0);

/// Spatial cylindrical roller bearing: the planar seating of its planar restriction
/// (Model::planar_restriction), its coordinates copied into the spatial state (axial, tilt and skew
/// at zero): aligned and without axial load that is the spatial model's seating as well.
StartupReport seat_spatial_roller_bearing(const Model& model, double t0);

/// Spatial tapered roller bearing (tapered_startup.cpp): quasi-static seating of rings and rollers
/// (each roller's radial and axial place and its lean) with the model's race slices and rib, then
/// rolling about the raceways' common apex at the epicyclic cage speed.
StartupReport seat_tapered_roller_bearing(const Model& model, double t0);

/// Spatial ball bearing, quasi-static seating with the same contact functions the dynamics use:
/// unknowns are the free ring coordinates (translation, tilt) and each ball's radial and axial
/// position in its azimuthal plane; Levenberg-Marquardt on the force balance (robust from open
/// contacts). The cage is centred with its pockets on the balls (axially and in tilt as far as the
/// pockets' play requires), turning at the load-weighted mean of the balls' orbits. Ball spin: least-squares rolling without sliding at its loaded contacts.
StartupReport seat_ball_bearing(const Model& model, double t0, double azimuth_offset, Equations* equations = nullptr);

}  // namespace raceway::bearing
