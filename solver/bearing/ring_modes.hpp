// A flexible outer ring (seed 003 2.3): the rim of a planet gear, whose bending widens the loaded
// zone. Seed 003 condenses a finite-element model of the rim onto the raceway's nodes and balances
// the roller forces against that compliance quasi-statically. Here the rim is a thin circular ring
// and its deflection is a sum of in-plane inextensional bending modes n = 2..N,
//
//   w(theta) = sum_n a_n cos(n theta) + b_n sin(n theta)          (radial, outward)
//   v(theta) = sum_n (b_n cos(n theta) - a_n sin(n theta)) / n    (tangential: dv/dtheta = -w, no stretch)
//
// whose amplitudes and rates are border states (one body per mode, BodyKind::ring_mode, the
// amplitudes as its x and y): a ring's radial compliance is spread over all azimuths, so every
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
// Contacts: roller k's outer-race contact sees the rim displaced by u = w e_r + v e_t (and moving
// at u') at its azimuth theta_k about the ring's centre: the ring's centre is moved by u for that
// contact (the same gap, to first order, as the raceway bent outward by w), and the contact's force
// f on the ring goes to the ring body whole (n = 1) and to the modes as their generalized forces
// f . d u / d a_n (virtual work: action equals reaction, and the modes' power is what the contacts
// give them).
#pragma once

#include <vector>

#include "contact/segments/roller_segments.hpp"
#include "io/scene/scene.hpp"
#include "solver/bearing/body_dynamics.hpp"
#include "solver/bearing/model.hpp"

namespace raceway::solver {

/// The rim as a thin ring: section, what follows from it, and its modes n = 2..highest_mode.
struct RimRing {
  double radius = 0;           ///< m, mean radius of the bending section
  double thickness = 0, width = 0;  ///< m, radial and axial, of the section
  double bending_stiffness = 0;     ///< N m^2, E I
  double mass_per_length = 0;       ///< kg/m, the ring's mass spread round the rim
  int highest_mode = 0;
  std::vector<double> stiffness, mass, damping;  ///< per mode n = 2..highest_mode (index n - 2)
  /// Natural frequency of mode n [rad/s].
  double frequency(int n) const;
};

/// The rim of the scene's outer ring (flexibility = "ring_modes"); `ring_mass` its body's mass.
RimRing rim_ring(const io::Scene& scene, double race_radius, double ring_mass);

/// With [outer_ring] flexibility = "ring_modes": one body per bending mode (amplitudes a_n, b_n as
/// x and y, their rates as vx, vy: four border states). Call right after the outer ring's states.
void add_ring_modes(Model& m, const io::Scene& scene);
/// The modes' elasticity (one outer_ring_mode segment per mode), after the contact segments.
void add_ring_mode_segments(Model& m, const io::Scene& scene);

/// The mode shapes at an azimuth: cos(n theta) and sin(n theta) for n = 2..highest, by the
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
RimPoint rim_point(const Model& m, const contact::PlanarKinematics& ring, const contact::PlanarKinematics& roller,
                   const double* z);

/// A flexible outer-race contact (a roller_outer_race segment of a model with ring modes): the
/// ring's kinematics moved by the rim's displacement at the contact, plus `extra` (d u x, d u y,
/// d u' x, d u' y, for the Jacobian's differences; null: none); the moment on the ring is about its
/// own centre.
contact::SegmentResult evaluate_on_rim(const contact::RollerRaceSegment& law, const Model& m, const Segment& seg,
                                       double t, const double* z, const double* extra = nullptr);
/// Whether segment `seg` of model m is a contact on a flexible rim.
inline bool on_rim(const Model& m, const Segment& seg) {
  return m.ring_mode_count > 0 && seg.kind == SegmentKind::roller_outer_race;
}
/// Columns of a rim contact's Jacobian record after its bodies' (segment_columns): d/d u x, u y, u' x, u' y.
inline constexpr int rim_shift_columns = 4;
/// The Jacobian task's record of a rim contact: the result, one column per state of the ring and
/// the roller (both sides' kinematics re-evaluated: the rim's displacement follows the roller's
/// azimuth), then the rim_shift_columns.
void rim_jacobian_record(const contact::RollerRaceSegment& law, const Model& m, const FiniteDifferenceSteps& step,
                         const Segment& seg, double t, const double* z, std::span<double> rec);

/// The generalized forces on the modes of a rim contact's force `on_ring` (force x, y on the ring):
/// adds (Q_a, Q_b) of mode n to sums[mode body].force x, y.
void add_modal_forces(const Model& m, const RimPoint& p, const double* on_ring, std::vector<Wrench>& sums);

}  // namespace raceway::solver
