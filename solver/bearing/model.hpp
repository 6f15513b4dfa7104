// The planar bearing model: bodies, state layout and contact segments built from a scene
// (DESIGN.md 3.1). Model no more than the scene needs: fixed and driven motions are not states, a
// roller's and a ring's angle about their own axes are not states, and a segment exists only where
// the geometry can close it.
//
// State layout: border first (inner ring, outer ring, cage: whichever carry states), then one block
// per roller. Within a body: positions (x, y[, theta]) then velocities (vx, vy[, omega]); a roller
// is (x, y, vx, vy, omega). The Jacobian is then block diagonal with borders.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "contact/segments/roller_segments.hpp"
#include "io/scene/scene.hpp"

namespace raceway::solver {

enum class BodyKind { inner_ring, outer_ring, cage, roller };
enum class VariableClass { position, angle, velocity, angular_velocity };

/// Absolute tolerances per state from physical scales, where the scene's [solver] section gives
/// none: positions rtol times the pitch radius, angles rtol, velocities rtol times the driven ring's
/// surface speed at the pitch radius, angular velocities rtol times a rolling element's rolling spin.
/// Shared by the planar and the spatial model.
std::vector<double> physical_absolute_tolerance(const io::Scene& scene, const std::vector<VariableClass>& state_class,
                                                double pitch_radius, double rolling_element_radius);

/// One rigid body. slot[c] is the state index of kinematic component c (contact::Component), or -1
/// when that component is not a state (then it is prescribed: zero, or the drive speed).
struct Body {
  std::string name;
  BodyKind kind = BodyKind::roller;
  int index = 0;  ///< roller number, 0 for the others
  double mass = 0, inertia = 0;
  std::array<int, 6> slot{-1, -1, -1, -1, -1, -1};
  int offset = 0, size = 0;          ///< contiguous block of this body's states
  const io::RingSpec* ring = nullptr;  ///< rings: motion, drive, loads, support
  bool has_states() const { return size > 0; }
};

enum class SegmentKind { roller_inner_race, roller_outer_race, cage_bar_front, cage_bar_rear, cage_land };
inline constexpr int segment_kind_count = 5;
const char* segment_kind_name(SegmentKind k);

/// A contact segment: two bodies (A, B as in contact/planar_segments.hpp) and the index of its
/// parameters in the model's array for its kind.
struct Segment {
  SegmentKind kind;
  int body_a, body_b;
  int parameters;
  int roller;  ///< roller it belongs to, -1 for cage-land
  std::string name;
};

struct Model {
  const io::Scene* scene = nullptr;
  std::vector<Body> bodies;  ///< inner ring, outer ring, cage, rollers (in that order, always)
  int inner_ring = 0, outer_ring = 1, cage = 2, first_roller = 3;
  int roller_count = 0;
  int state_size = 0;
  int border_size = 0;  ///< states of rings and cage; rollers follow
  std::vector<VariableClass> state_class;
  std::vector<std::string> state_name;
  std::vector<Segment> segments;
  std::vector<contact::RollerRaceSegment> race_segments;
  std::vector<contact::CageBarSegment> bar_segments;
  std::vector<contact::CageLandSegment> land_segments;

  // Geometry, kept for start-up and diagnostics.
  double pitch_radius = 0, roller_radius = 0, inner_race_radius = 0, outer_race_radius = 0;
  double gravity = 0;  ///< m/s^2 along -y

  /// Absolute tolerance per state from the scene, or from physical scales where the scene is silent.
  std::vector<double> absolute_tolerance() const;
  /// Kinematics of body b at (t, z): states from z, the rest prescribed.
  contact::PlanarKinematics kinematics(int b, double t, const double* z) const;
  /// The model explained: bodies, states, segments, laws and the reasons (raceway check).
  std::string describe() const;
  /// Epicyclic (kinematic) cage speed for the rings' speeds at time t [rad/s].
  double epicyclic_cage_speed(double t) const;
};

/// Builds the model. Throws std::runtime_error naming the scene key when something cannot be built.
Model build_model(const io::Scene& scene);

}  // namespace raceway::solver
