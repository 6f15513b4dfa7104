// The housing: the fixed outer ring of a ball bearing mounted in a housing on a pedestal (a node,
// nodes.hpp). The housing and the ring move together in x and y. With one mode per radial direction
//
//   M u'' = F - k u - c u',   M = housing mass + outer ring mass,
//
// F the contacts' force on the outer ring (its groove contacts and, land-guided, the cage land).
// Further modes ([housing.modes]) describe the housing as its receptance at the bearing seat sees
// it: the seat moves by the sum of the modes' displacements, u = sum_j q_j, each mode a modal mass,
// stiffness and damping driven by the force the ring puts on the seat, F_h:
//
//   m_j q_j'' = F_h - r_j,   r_j = k_j q_j + c_j q_j',   m_r u'' = F - F_h   (m_r: the outer ring),
//
// which gives u'' = sum_j (F - r_j) / m_j / (1 + m_r sum_j 1/m_j) in closed form (one mode: the
// equation above, computed as before). Statically the modes' compliances add: u = F sum_j 1/k_j.
// Its states are, per mode, the displacement q = (qx, qy) and velocity (vx, vy), border states after
// the rings'. The outer ring's contacts attach to it through a HousingMarker: the ring's kinematics
// moved by u and u' (its spin and tilt stay the ring's), their force goes to the housing's
// generalized forces (and to the ring's force diagnostics). A sensor on the housing reads
// sum_j psi_j q_j (psi_j: its participation in mode j, 1 at the seat), sampled by the run
// (solver/run/housing_sensor.hpp).
//
// The housing starts at rest at u = 0; the load it carries then settles it with its modes' damping.
#pragma once

#include <string>
#include <vector>

#include "io/scene/scene.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/nodes.hpp"

namespace raceway::bearing {

class Housing final : public Node {
 public:
  /// One mode of the housing at the seat (per radial direction).
  struct Mode {
    double mass, stiffness, damping;  ///< kg, N/m, N s/m (the first mode's mass includes the ring's)
    double sensor;                    ///< the sensor's displacement per unit of the mode's
  };
  /// `modes` the first mode's with the ring's mass in it when it is the only one; with more,
  /// `ring_mass` is the outer ring's and every mode's mass the housing's own.
  Housing(std::vector<Mode> modes, double ring_mass, int ring_body, int first_state, int sensor_samples);
  /// The sensor's samples per output interval ([housing] sensor_interval divides it).
  int sensor_samples() const { return sensor_samples_; }
  int mode_count() const { return static_cast<int>(modes_.size()); }
  const std::vector<Mode>& modes() const { return modes_; }
  /// State i of mode j: 0 qx, 1 qy, 2 vx, 3 vy.
  int state(int i, int mode = 0) const { return first_state_ + 4 * mode + i; }
  /// The first mode's mass (with the ring's where it is the only mode), stiffness, damping.
  double mass() const { return modes_[0].mass; }
  double stiffness() const { return modes_[0].stiffness; }
  double damping() const { return modes_[0].damping; }
  double ring_mass() const { return ring_mass_; }
  int ring_body() const { return ring_body_; }
  /// The first mode's natural frequency [Hz] and damping ratio (with the ring's mass).
  double natural_frequency() const;
  double damping_ratio() const;
  /// The undamped natural frequencies [Hz] of the housing with the ring on its seat, ascending (one
  /// mode: natural_frequency()).
  std::vector<double> frequencies() const;
  /// The seat's (and the ring's) displacement (i = 0, 1) or velocity (i = 2, 3) from the states z.
  double seat(const double* z, int i) const;
  /// The sensor's reading of state component i (0, 1 displacement; 2, 3 velocity) from z, or of
  /// the acceleration from the rates zdot with i = 2, 3.
  double sensor(const double* z, int i) const;
  /// d(mode j's acceleration) / d(the force on the seat), per unit force.
  double acceleration_per_force(int mode) const { return per_force_[static_cast<std::size_t>(mode)]; }

  std::string name() const override { return "housing"; }
  int force_count() const override { return 2; }
  void rates(const Model& m, double t, const double* z, const double* forces, double* zdot) const override;
  void add_own_jacobian(const Model& m, double t, numerics::BorderedMatrix& jac) const override;
  void add_energy(const Model& m, double t, const double* z, double& e) const override;
  double power_loss(const Model& m, double t, const double* z) const override;
  void initial_state(std::vector<double>& z) const override;
  std::string describe(const Model& m) const override;

 private:
  std::vector<Mode> modes_;
  double ring_mass_;
  int ring_body_, first_state_, sensor_samples_;
  double coupling_ = 1;  ///< 1 + m_r sum_j 1/m_j (more than one mode)
  std::vector<double> per_force_;
};

/// With a [housing] section: the housing node (four border states). Call right after the rings'.
void add_housing(Model& m, const scene::Scene& scene);
/// After the contact elements: attaches every element on the outer ring to the housing's marker.
void attach_outer_ring_to_housing(Model& m);
/// The model's housing, or nullptr.
const Housing* housing_of(const Model& m);

}  // namespace raceway::bearing
