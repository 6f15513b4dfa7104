// The spatial ball-bearing model (DESIGN.md 3.1): rings, cage and balls as rigid bodies in three
// dimensions, and the contact segments between them, built from a scene.
//
// Model no more than the scene needs:
//  - a ball carries position, velocity and angular velocity only (9 states): a sphere's contact
//    geometry does not depend on its orientation;
//  - a ring's angle about its own axis is not a state (its grooves are surfaces of revolution); its
//    translation (x, y, z), tilt (about x and y) and spin are states only where the scene leaves them
//    free; fixed and driven motions and prescribed misalignments are functions of time;
//  - the cage keeps its full pose (x, y, z, Cardan angles about x, y, z) and its angular velocity in
//    its own frame (12 states): its pockets are not symmetric.
//
// State layout: border first (inner ring, outer ring, cage: whichever carry states), then one
// 9-state block per ball (x, y, z, vx, vy, vz, wx, wy, wz). The Jacobian is block diagonal with
// borders (seed 000 fig. 2).
//
// Orientation: R = Rx(ax) Ry(ay) Rz(az) maps body-frame vectors to the bearing frame. Ring tilts are
// small (mrad): a ring's angular velocity is spin * (R e_z) + tilt rates, and its rotational
// equations are the small-tilt rotor equations with the gyroscopic coupling of its spin
// (I_t dwx/dt = Mx - I_z spin wy, I_t dwy/dt = My + I_z spin wx). The cage uses Euler's equations
// in its principal frame (I = diag(I_t, I_t, I_z)), exact for any tilt short of 90 degrees.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "contact/segments/ball_segments.hpp"
#include "io/scene/scene.hpp"
#include "solver/bearing/model.hpp"

namespace raceway::solver {

/// Index of a generalized coordinate of a spatial body; slot[c] is its state index or -1.
/// Balls and rings: (wx, wy, wz) in the bearing frame for balls; for rings (wx, wy) are tilt rates
/// and wz the spin about the ring's axis. Cage: (wx, wy, wz) in the cage frame.
enum SpatialComponent : int { sx = 0, sy, sz, sax, say, saz, svx, svy, svz, swx, swy, swz };
inline constexpr int spatial_components = 12;

enum class SpatialBodyKind { inner_ring, outer_ring, cage, ball };

struct SpatialBody {
  std::string name;
  SpatialBodyKind kind = SpatialBodyKind::ball;
  int index = 0;                 ///< ball number, 0 for the others
  double mass = 0;               ///< kg
  double axial_inertia = 0;      ///< kg m^2 about the body's z axis
  double transverse_inertia = 0; ///< kg m^2 about a diameter (equal to axial for a ball)
  std::array<int, spatial_components> slot;
  int offset = 0, size = 0;      ///< contiguous block of this body's states
  const io::RingSpec* ring = nullptr;  ///< rings
  SpatialBody() { slot.fill(-1); }
  bool has_states() const { return size > 0; }
};

enum class SpatialSegmentKind { ball_inner_groove, ball_outer_groove, ball_pocket, cage_land };
inline constexpr int spatial_segment_kind_count = 4;
const char* spatial_segment_kind_name(SpatialSegmentKind k);

struct SpatialSegment {
  SpatialSegmentKind kind;
  int body_a, body_b;
  int parameters;  ///< index into the model's array for its kind
  int ball;        ///< ball it belongs to, -1 for cage-land
  std::string name;
};

struct SpatialModel {
  const io::Scene* scene = nullptr;
  std::vector<SpatialBody> bodies;  ///< inner ring, outer ring, cage, balls (in that order, always)
  int inner_ring = 0, outer_ring = 1, cage = 2, first_ball = 3;
  int ball_count = 0;
  int state_size = 0, border_size = 0;
  static constexpr int ball_block_size = 9;
  std::vector<VariableClass> state_class;
  std::vector<std::string> state_name;
  std::vector<SpatialSegment> segments;
  std::vector<contact::BallGrooveSegment> groove_segments;
  std::vector<contact::BallPocketSegment> pocket_segments;
  std::vector<contact::CageLandSegment3> land_segments;

  // Geometry, kept for start-up, output and diagnostics.
  double pitch_radius = 0, ball_radius = 0;
  double nominal_contact_angle = 0;  ///< rad: 0 deep groove, the arc angle for four-point
  double gravity = 0;                ///< m/s^2 along -y
  int arcs_per_ring = 1;             ///< 2 for a four-point bearing

  std::vector<double> absolute_tolerance() const;
  /// Kinematics of body b at (t, z): states from z, the rest prescribed.
  contact::SpatialKinematics kinematics(int b, double t, const double* z) const;
  /// The model explained: bodies, states, segments, laws and the reasons (raceway check).
  std::string describe() const;
  /// Kinematic cage speed (seed 001 eq. 5-6) from the rings' speeds at t, at the nominal angle.
  double epicyclic_cage_speed(double t) const;
  /// The same at a given contact angle (seed 001 eq. 5 with cos(alpha)): the kinematic cage speed of
  /// balls rolling at that angle.
  double epicyclic_cage_speed(double t, double contact_angle) const;
  /// Spin of a ring about its own axis at (t, z) [rad/s].
  double ring_spin(int b, double t, const double* z) const;
};

/// Builds the model. Throws std::runtime_error naming the scene key when something cannot be built.
SpatialModel build_spatial_model(const io::Scene& scene);

/// R = Rx(ax) Ry(ay) Rz(az).
contact::Mat3 cardan_rotation(double ax, double ay, double az);
/// Rates of the Cardan x-y-z angles from a body-frame angular velocity (singular at ay = +-90 deg,
/// far beyond any cage tilt).
contact::Vec3 cardan_rates(double ay, double az, const contact::Vec3& body_angular_velocity);

}  // namespace raceway::solver
