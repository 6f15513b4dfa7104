// The housing: the fixed outer ring of a ball bearing mounted in a housing on a pedestal (a node,
// nodes.hpp). The housing and the ring move together in x and y, one mode per radial direction:
//
//   M u'' = F - k u - c u',   M = housing mass + outer ring mass,
//
// F the contacts' force on the outer ring (its groove contacts and, land-guided, the cage land).
// Its states are the displacement u = (ux, uy) and velocity (vx, vy), border states after the
// rings'. The outer ring's contacts attach to it through a HousingMarker: the ring's kinematics
// moved by u and u' (its spin and tilt stay the ring's), their force goes to the housing's
// generalized forces (and to the ring's force diagnostics). What a sensor on the housing measures
// (displacement, velocity, acceleration) is sampled by the run (solver/run/sensor.hpp).
//
// The housing starts at rest at u = 0; the load it carries then settles it with its damping ratio
// c / (2 sqrt(k M)), a ring-down at its natural frequency sqrt(k / M) / 2 pi.
#pragma once

#include <string>
#include <vector>

#include "io/scene/scene.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/nodes.hpp"

namespace raceway::bearing {

class Housing final : public Node {
 public:
  Housing(double mass, double stiffness, double damping, int ring_body, int first_state, int sensor_samples);
  /// The sensor's samples per output interval ([housing] sensor_interval divides it).
  int sensor_samples() const { return sensor_samples_; }
  /// State i: 0 ux, 1 uy, 2 vx, 3 vy.
  int state(int i) const { return first_state_ + i; }
  double mass() const { return mass_; }
  double stiffness() const { return stiffness_; }
  double damping() const { return damping_; }
  int ring_body() const { return ring_body_; }
  /// Natural frequency [Hz] and damping ratio.
  double natural_frequency() const;
  double damping_ratio() const;

  std::string name() const override { return "housing"; }
  int force_count() const override { return 2; }
  void rates(const Model& m, double t, const double* z, const double* forces, double* zdot) const override;
  void add_own_jacobian(const Model& m, double t, numerics::BorderedMatrix& jac) const override;
  void add_energy(const Model& m, double t, const double* z, double& e) const override;
  double power_loss(const Model& m, double t, const double* z) const override;
  void initial_state(std::vector<double>& z) const override;
  std::string describe(const Model& m) const override;

 private:
  double mass_, stiffness_, damping_;
  int ring_body_, first_state_, sensor_samples_;
};

/// With a [housing] section: the housing node (four border states). Call right after the rings'.
void add_housing(Model& m, const scene::Scene& scene);
/// After the contact elements: attaches every element on the outer ring to the housing's marker.
void attach_outer_ring_to_housing(Model& m);
/// The model's housing, or nullptr.
const Housing* housing_of(const Model& m);

}  // namespace raceway::bearing
