// A flexible outer ring (seed 003 2.3): the rim of a planet gear, whose bending widens the loaded
// zone. Seed 003 condenses a finite-element model of the rim onto the raceway's nodes and balances
// the roller forces against that compliance quasi-statically. Here the rim's deflection is a sum of
// in-plane modes. With [outer_ring] rim_theory = "timoshenko" (the default) the rim is a thick ring
// that bends, stretches and shears (thick_ring.hpp: modes n = 0, 1, 2..N, each with its own shape,
// RimRing below); a seed 003 rim is 13 mm thick at a 63.5 mm radius, and the roller loads stretch
// it by more than the bearing's radial play. With "euler_bernoulli" it is the thin inextensional
// ring described next, the model the rest of this comment derives (modes n = 2..N),
//
//   w(theta) = sum_n a_n cos(n theta) + b_n sin(n theta)          (radial, outward)
//   v(theta) = sum_n (b_n cos(n theta) - a_n sin(n theta)) / n    (tangential: dv/dtheta = -w, no stretch)
//
// whose amplitudes and rates are border states (a node, RingModes: four states per mode): a ring's
// radial compliance is spread over all azimuths, so every
// roller's outer-race contact sees every mode. The rigid modes are the ring body's own (n = 1 its
// translation; the extensional n = 0 is stiff and left out). A dynamic rim rather than seed 003's
// quasi-static compliance: the rim's lowest bending mode (about 1 kHz in seed 003's bearing) is near
// the rollers' passing frequency, so the quasi-static assumption does not hold there, and states
// keep the right-hand side explicit (a compliance would make every roller's contact force an
// implicit function of all the others').
//
// Modal stiffness and mass of a thin ring of mean radius R, bending stiffness E I and mass per
// length mu (Love's inextensional ring, as in Soedel, docs/references.md: the ring's
// inextensional modes): the strain energy (E I / 2) int ((d2w/dtheta2 + w) / R^2)^2 R dtheta and the kinetic
// energy (mu / 2) int ((dw/dt)^2 + (dv/dt)^2) R dtheta of w = a cos(n theta) give
//
//   k_n = pi E I (n^2 - 1)^2 / R^3,   m_n = pi mu R (1 + 1 / n^2),
//   omega_n^2 = E I n^2 (n^2 - 1)^2 / (mu R^4 (n^2 + 1))           (the classic ring frequency).
//
// The section (rim thickness and width) sets E I; the ring's mass (the gear body, teeth included)
// spread evenly round the rim sets mu: teeth add mass, little bending stiffness.
//
// Frame: the modes are written in the bearing frame (the carrier's), not in the spinning gear: the
// mesh load and the carrier's field are fixed in the carrier frame, so the rim's deflection is
// steady there and its amplitudes stay nearly constant, while in the gear's frame they would swing
// at n times the gear speed and the integrator would have to follow them. The price: a spinning
// ring's gyroscopic and hoop-tension terms are left out, of relative size Omega / omega_2 (0.2 at
// 10000 rpm and omega_2 / 2 pi = 0.9 kHz) on the modes' dynamics and (Omega / omega_2)^2 on the
// quasi-static deflection; docs/planetary.md says more. The carrier frame's inertial forces on the
// rim's mass project onto n = 0 and 1 only (a uniform field and a field linear in position), so
// the bending modes see none of them.
//
// Contacts: roller k's outer-race contact attaches to the ring at a rim point (RimPointMarker): it
// sees the rim displaced by u = w e_r + v e_t (and moving at u') at its azimuth theta_k about the
// ring's centre: the ring's centre is moved by u for that contact (the same gap, to first order, as
// the raceway bent outward by w), and the contact's force f on the ring goes to the ring body whole
// (n = 1) and to the modes as their generalized forces f . d u / d a_n (virtual work: action equals
// reaction, and the modes' power is what the contacts give them). Each mode's spring (an
// outer_ring_mode element, internal_springs.hpp) attaches to the mode's amplitudes (ModeMarker).
#pragma once

#include <memory>
#include <vector>

#include "contact/segments/roller_segments.hpp"
#include "io/scene/scene.hpp"
#include "solver/bearing/body_dynamics.hpp"
#include "solver/bearing/model.hpp"

namespace raceway::bearing {

/// The rim's section and its modes: with [outer_ring] rim_theory = "euler_bernoulli" a thin
/// inextensional ring, modes n = 2..highest_mode; with "timoshenko" a thick ring (thick_ring.hpp),
/// modes n = 0, 1, 2..highest_mode. Mode k's shapes, as radial and tangential displacement:
/// phi_a = cos(n theta) e_r - tangential_k sin(n theta) e_t, phi_b = sin(n theta) e_r +
/// tangential_k cos(n theta) e_t (Love's ring: tangential = 1/n; n = 0's phi_b vanishes, a rigid
/// rotation being the ring body's: its sin states stay at rest).
struct RimRing {
  double radius = 0;           ///< m, mean radius of the bending section
  double thickness = 0, width = 0;  ///< m, radial and axial, of the section
  double bending_stiffness = 0;     ///< N m^2, E I
  double mass_per_length = 0;       ///< kg/m, the ring's mass spread round the rim
  int highest_mode = 0;
  scene::BeamTheory theory = scene::BeamTheory::euler_bernoulli;
  std::vector<int> order;                        ///< per mode: its n
  std::vector<double> stiffness, mass, damping;  ///< per mode
  std::vector<double> tangential;  ///< per mode: the shape's tangential over radial amplitude
  std::vector<double> stretch;     ///< per mode: 1 - n tangential, exactly 0 for Love's ring
  /// Natural frequency of mode index k [rad/s].
  double frequency(int k) const;
};

/// The rim of the scene's outer ring (flexibility = "ring_modes"); `ring_mass` its body's mass.
RimRing rim_ring(const scene::Scene& scene, double race_radius, double ring_mass);

/// The node of a flexible ring's bending modes n = 2..N: per mode the amplitudes a_n, b_n and their
/// rates (four border states, in that order); per mode two generalized forces (Q_a, Q_b).
class RingModes final : public Node {
 public:
  RingModes(RimRing rim, int ring_body, int first_state);
  int count() const { return static_cast<int>(rim_.mass.size()); }
  /// State i (0: a, 1: b, 2: a', 3: b') of mode index k (n = rim().order[k]).
  int state(int k, int i) const { return first_state_ + 4 * k + i; }
  const RimRing& rim() const { return rim_; }
  int ring_body() const { return ring_body_; }
  /// Adds d(rates of mode k)/d(state) from a derivative (dq_a, dq_b) of its generalized forces.
  void add_force_derivative(int k, int state, double dq_a, double dq_b, numerics::BorderedMatrix& jac) const;

  std::string name() const override { return "outer_ring_modes"; }
  int force_count() const override { return 2 * count(); }
  void rates(const Model& m, double t, const double* z, const double* forces, double* zdot) const override;
  void add_own_jacobian(const Model& m, double t, numerics::BorderedMatrix& jac) const override;
  void add_energy(const Model& m, double t, const double* z, double& e) const override;
  void initial_state(std::vector<double>& z) const override;
  std::string describe(const Model& m) const override;

 private:
  RimRing rim_;
  int ring_body_ = 0, first_state_ = 0;
};

/// With [outer_ring] flexibility = "ring_modes": the node of the outer ring's bending modes (four
/// border states per mode). Call right after the outer ring's states.
void add_ring_modes(Model& m, const scene::Scene& scene);
/// The modes' elasticity (one outer_ring_mode element per mode, on the mode's marker), after the
/// contact elements.
void add_ring_mode_segments(Model& m);
/// The marker of a roller's outer-race contact: a rim point when the outer ring is flexible, or -1
/// (the ring's centre).
int outer_race_marker(Model& m);
/// The model's ring-modes node, or nullptr.
const RingModes* ring_modes_of(const Model& m);
/// The model description's line for the modes' elements.
std::string describe_ring_mode_segments(const Model& m);

/// The mode shapes at an azimuth: cos(n theta) and sin(n theta) for n = 0..highest, by the
/// angle-sum recurrence from cos(theta), sin(theta) (no trigonometric call per mode).
struct ModeShapes {
  static constexpr int max_modes = 40;
  double c[max_modes + 1] = {}, s[max_modes + 1] = {};  ///< index n
  ModeShapes(double cos_theta, double sin_theta, int highest);
};

/// Where a roller's outer-race contact sits on the rim, and the rim's displacement there.
struct RimPoint {
  double cos_theta = 1, sin_theta = 0;  ///< the contact's azimuth about the ring's centre
  double distance = 0;                  ///< m, from the ring's centre to the roller's
  double u[2] = {}, u_rate[2] = {};     ///< m, m/s: displacement w e_r + v e_t and its rate
};
RimPoint rim_point(const RingModes& modes, const contact::PlanarKinematics& ring,
                   const contact::PlanarKinematics& roller, const double* z);

/// The generalized forces on the modes of a rim contact's force `on_ring` (force x, y on the ring):
/// adds (Q_a, Q_b) of mode k to forces[2 k], forces[2 k + 1].
void add_modal_forces(const RingModes& modes, const RimPoint& p, const double* on_ring, double* forces);

}  // namespace raceway::bearing
