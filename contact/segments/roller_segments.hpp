// Planar contact segments of a cylindrical roller bearing: roller-race, roller-cage bar and
// cage-land line contacts (README.md, "What is modelled (planar cylindrical roller bearing)").
//
// A segment is a place where contact can happen between two bodies A and B. Evaluating it is a pure
// function: (its parameters, the kinematics of A and B) -> the force and moment on each body at the
// body's centre, and diagnostics. Forces act at one common contact point, so action equals reaction
// and angular momentum about any point is conserved exactly.
//
// Frames: bearing frame, z the bearing axis (out of the plane), angles counter-clockwise.
#pragma once

#include <optional>

#include "contact/laws/line_contact.hpp"
#include "contact/laws/lubricated_line_contact.hpp"
#include "contact/laws/short_bearing_film.hpp"
#include "contact/segments/segment_result.hpp"

namespace raceway::contact {

/// Planar kinematics of a rigid body: centre, rotation about z, and their rates. SI.
struct PlanarKinematics {
  double x = 0, y = 0, theta = 0;
  double vx = 0, vy = 0, omega = 0;
};

/// Index of a kinematic component of PlanarKinematics (in declaration order); a segment Jacobian
/// has A's six columns, then B's six.
enum Component : int { px = 0, py, theta, vx, vy, omega };
inline constexpr int kinematic_components = 6;

/// Force [N] and moment about z [N m] on a body, at the body's centre.
struct PlanarWrench {
  double fx = 0, fy = 0, mz = 0;
};

/// What a segment reports besides forces. Fixed size: one record per segment and evaluation.
struct SegmentDiagnostics {
  double approach = 0;        ///< m, > 0 in contact (elastic approach or penetration)
  double normal_force = 0;    ///< N, >= 0
  double traction_force = 0;  ///< N, tangential force on body B along the segment tangent
  double slip_velocity = 0;   ///< m/s, sliding velocity of B's surface relative to A's
  double elastic_energy = 0;  ///< J
  double power_loss = 0;      ///< W, friction plus damping dissipation, >= 0
};
inline constexpr int diagnostics_count = 6;

using SegmentResult = ContactResult<PlanarWrench, SegmentDiagnostics>;

/// The EHD film of a roller-race contact (seed 003 2.2.2): its force replaces the dry normal law
/// (Hunt-Crossley damping, if on, multiplies it). With `traction` Couette friction replaces the
/// segment's traction curve and the Poiseuille force resists the rolling; else the curve applies.
struct EhdRaceFilm {
  EhdLineLaw law;
  double damping_factor = 0;  ///< s/m
  bool traction = false;
  CouetteTraction couette;
};

/// Roller on a raceway. A = ring, B = roller. `internal`: outer race (roller inside a bore).
struct RollerRaceSegment {
  double race_radius = 0;    ///< m
  double roller_radius = 0;  ///< m
  bool internal = false;
  LineContactLaw law;
  TractionCurve traction;
  std::optional<EhdRaceFilm> ehd;  ///< lubricated (normal = "moes_ehd"); else the dry law
};
SegmentResult evaluate(const RollerRaceSegment& s, const PlanarKinematics& ring,
                       const PlanarKinematics& roller);

/// Roller against one bar of its cage pocket. A = cage, B = roller.
/// The pocket is a straight slot with walls parallel to the pocket's radial line at cage-frame
/// angle `pocket_angle`; its width is roller diameter + clearance. `side` = +1 is the bar ahead in
/// the positive sense of rotation ("front" for a bearing turning counter-clockwise), -1 the one behind.
struct CageBarSegment {
  double pitch_radius = 0;     ///< m, radius of the pocket centres in the cage frame
  double pocket_angle = 0;     ///< rad, in the cage frame
  double half_clearance = 0;   ///< m, half the circumferential pocket clearance
  double roller_radius = 0;    ///< m
  int side = +1;
  LineContactLaw law;
  TractionCurve traction;
  /// Lubricated (normal = "hydrodynamic", seed 003 2.2.1): the film with its dry contact (film->dry
  /// is `law`), the viscous Couette drag of the film plus the traction curve on the dry force.
  std::optional<HydrodynamicLineLaw> film;
};
SegmentResult evaluate(const CageBarSegment& s, const PlanarKinematics& cage,
                       const PlanarKinematics& roller);
/// evaluate(s, cage, roller).diagnostics.approach alone, the same bits (the pocket tolerance asks it
/// at every step): of the cage's kinematics it reads the position and angle, of the roller's the
/// centre (roller_x, roller_y).
double bar_approach(const CageBarSegment& s, const PlanarKinematics& cage, double roller_x, double roller_y);

/// Cage guided on a ring land. A = cage, B = ring. Contact when the centres' eccentricity exceeds
/// the land clearance. Inner-land guidance: the cage bore rides on the ring's land (land_radius is the
/// land's); outer-land guidance: the cage's outside rides in the ring's land bore.
struct CageLandSegment {
  double land_radius = 0;  ///< m, radius of the ring land surface
  double clearance = 0;    ///< m, radial land clearance
  bool outer_land = false;
  LineContactLaw law;
  TractionCurve traction;
  /// Lubricated land (normal = "short_bearing"): the land's short journal-bearing film over its whole
  /// width (short_bearing_film.hpp), apart as well as in contact: its pressure midway between the two
  /// centres (equal and opposite), its Couette torque on both bodies, its force and power in
  /// normal_force and power_loss; the dry law above adds where the surfaces overlap (inner land: the
  /// ring is the journal in the cage's bore; outer land: the cage in the ring's land bore).
  std::optional<ShortBearingFilm> film;
};
SegmentResult evaluate(const CageLandSegment& s, const PlanarKinematics& cage,
                       const PlanarKinematics& ring);

}  // namespace raceway::contact
