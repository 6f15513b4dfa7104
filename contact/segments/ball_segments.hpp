// Spatial contact segments of a ball bearing: ball-groove (one per groove arc:
// two per ring for a four-point bearing), ball-cage pocket, and cage-land guidance.
//
// A segment evaluation is a pure function: (its parameters, the kinematics of its two bodies A and
// B) -> force and moment on each body at the body's centre (bearing frame), and diagnostics. All
// forces of a segment act at one contact point (traction moments about the normal and the rolling
// resistance act as couples), so action equals reaction and angular momentum about any point is
// conserved. No heap allocation; thread-safe.
//
// Frames: bearing frame, z the bearing axis. A body's rotation matrix maps body-frame vectors to
// the bearing frame. Ring frames: z along the ring axis, groove geometry fixed in the ring frame.
//
// Conventions shared by the point contacts (ball-groove, ball-pocket):
//  - body 1 of ContactSliding is A (ring, cage), body 2 is B (the ball); the contact normal n is the
//    unit vector from the ball centre towards A's surface (into body 1); the normal force on the
//    ball is -Q n;
//  - the approach rate used by the damping is the exact d(approach)/dt, n . (v_B - v_A) of the
//    material points at the contact point (so the elastic force does work Q_el d(approach)/dt);
//  - sliding is B's surface velocity relative to A's at the contact point, spin_velocity is
//    (omega_B - omega_A) . n;
//  - validity: approach > max_approach gives valid = false with the forces still computed; a
//    non-finite input gives valid = false and no force at all (never garbage).
#pragma once

#include <cmath>
#include <Eigen/Dense>
#include <memory>
#include <optional>

#include "contact/laws/line_contact.hpp"
#include "contact/laws/pocket_film.hpp"
#include "contact/laws/point_contact.hpp"
#include "contact/laws/race_imperfections.hpp"
#include "contact/laws/short_bearing_film.hpp"
#include "contact/segments/segment_result.hpp"

namespace raceway::contact {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

/// Spatial kinematics of a rigid body: centre, orientation (body -> bearing frame), their rates.
struct SpatialKinematics {
  Vec3 position = Vec3::Zero();
  Mat3 rotation = Mat3::Identity();
  Vec3 velocity = Vec3::Zero();
  Vec3 angular_velocity = Vec3::Zero();  ///< bearing frame
  /// A ring's angle about its own axis, which `rotation` leaves out (its grooves are surfaces of
  /// revolution): read only where the race is not (a spall, waviness). 0 for other bodies.
  double spin_angle = 0;

  bool all_finite() const {
    return position.allFinite() && rotation.allFinite() && velocity.allFinite() && angular_velocity.allFinite() &&
           std::isfinite(spin_angle);
  }
};

/// Coulomb friction smoothed on a slip-velocity scale u: the force -mu tanh(|s|/u) Q s/|s| on the
/// body that slips at s, written -(mu / u) (tanh(x) / x) Q s with x = |s|/u so that it is smooth
/// through zero slip (tanh(x) / x by its series below 1e-4: error under 1e-17).
inline Vec3 tanh_slip_traction(double friction_coefficient, double slip_velocity_scale, double normal_force,
                               const Vec3& slip) {
  if (friction_coefficient == 0) return Vec3::Zero();
  const double x = slip.norm() / slip_velocity_scale;
  const double tanh_ratio = std::abs(x) < 1e-4 ? 1.0 - x * x / 3.0 : std::tanh(x) / x;
  return -(friction_coefficient / slip_velocity_scale) * tanh_ratio * normal_force * slip;
}

/// Force [N] and moment [N m] on a body at its centre, bearing frame.
struct SpatialWrench {
  Vec3 force = Vec3::Zero();
  Vec3 moment = Vec3::Zero();
};

/// What a spatial segment reports besides forces. Fixed size, one record per evaluation.
struct PointDiagnostics {
  double approach = 0;              ///< m, > 0 in contact
  double normal_force = 0;          ///< N, >= 0
  double contact_angle = 0;         ///< rad: ball-groove: angle of the normal to the radial plane
                                    ///< (sign of its axial component along the ring axis), from the
                                    ///< geometry, reported also when apart; others 0
  double max_pressure = 0;          ///< Pa
  double film_thickness = 0;        ///< m, central EHL film (0 dry)
  double slip_velocity = 0;         ///< m/s, magnitude of sliding at the contact centre
                                    ///< (cage-land: at the most loaded station)
  double spin_velocity = 0;         ///< rad/s, relative spin about the normal
  double traction_force = 0;        ///< N, magnitude of the tangential force
  double circumferential_force = 0; ///< N, force on B along the bearing's circumferential direction
                                    ///< at B's centre (e_theta = e_z x e_r, bearing frame): > 0
                                    ///< pushes B forward; 0 for cage-land (B, a ring, is on the axis)
  double elastic_energy = 0;        ///< J
  double power_loss = 0;            ///< W, traction + damping + rolling resistance, >= 0
};
inline constexpr int point_diagnostics_count = 11;

using SpatialSegmentResult = ContactResult<SpatialWrench, PointDiagnostics>;

/// Normal law of a point contact: Hertz, Q = K(s) delta^1.5, with Hunt-Crossley damping
/// Q = K delta^1.5 (1 + damping_factor * d(delta)/dt), clipped at zero (a contact cannot pull).
/// Elastic energy (2/5) K delta^2.5. (Where K depends on the contact angle, that energy is not an
/// exact potential of the normal force; the force is the standard K(s) delta^1.5 along n.)
struct PointNormalLaw {
  HertzTable hertz;
  double reduced_modulus = 0;  ///< E* [Pa] (film and rolling resistance use E' = 2 E*)
  double damping_factor = 0;   ///< s/m
  double max_approach = 0;     ///< m, validity limit (recoverable error beyond)
};

/// A ball in one groove arc of a ring. A = ring, B = ball.
/// The arc's cross-section is a circle of radius `groove_radius` whose centre, in the ring frame,
/// lies on the circle of radius `centre_radius` at axial position `centre_axial` (for a four-point
/// bearing the arcs' centres are offset axially; for a deep-groove ring centre_axial = 0). With d
/// the vector from the arc centre (at the ball's azimuth) to the ball centre, the approach is
/// |d| - (groove_radius - ball_radius) and the contact normal is d/|d|: the contact angle comes from
/// the geometry, never from input. `outer`: the outer ring (race concave in the rolling direction).
/// Hertz parameter s = cos(contact angle); rolling-direction curvature of the race cos(a)/rho
/// (rho: distance of the contact point from the ring axis), convex for inner, concave for outer.
///
/// Contact point: on the groove's undeformed surface, arc centre + groove_radius n (ring frame).
/// Contact frame: x = e_theta of the ring frame at the ball's azimuth (tangent to the race, positive
/// in the ring's positive sense of rotation), y = n x x (transverse), z = n. Relative curvatures for
/// the film: kx = 1/r_b +- cos(a)/rho, ky = 1/r_b - 1/groove_radius; Rx = 1/kx, Ry = 1/ky.
/// Entrainment speed u_e = |u_A + u_B| / 2 of the surfaces' velocities along x relative to the
/// contact point, which moves with the ring plus a rotation about the ring axis at the ball centre's
/// azimuth rate in the ring frame (it follows the ball's orbit). Traction: integrate_traction on the
/// Hertz ellipse (force on the ball at the contact point, spin moment as a couple about n).
/// Rolling resistance (where the film is > 0): a couple -F Rx tanh(Omega Rx / s) e_y on the ball and
/// its opposite on the ring, Omega = (omega_B - omega_A) . e_y the relative rolling rate and s the
/// traction's slip_velocity_scale: the pressure centre shifted towards the inlet by F Rx / Q. It
/// conserves force and angular momentum and dissipates F Rx |Omega| (= F u_e in pure rolling).
/// F = F_R Q / (F_R + Q) with F_R from ehl_rolling_resistance: bounded by Q (a change of order
/// F_R / Q, ~1e-4 under load) so that the couple stays C1 at contact onset (F_R ~ Q^0.47 alone has
/// an unbounded slope there). power_loss = traction + damping + rolling-resistance dissipation.
struct BallGrooveSegment {
  double centre_radius = 0;  ///< m
  double centre_axial = 0;   ///< m
  double groove_radius = 0;  ///< m
  double ball_radius = 0;    ///< m
  bool outer = false;
  PointNormalLaw normal;
  PointTraction traction;
  PointLubricant lubricant;
  bool rolling_resistance = true;  ///< add EHL rolling resistance where there is a film
  /// The groove's extent: 0 a full groove (deep groove, four-point); +1 or -1 an angular contact
  /// bearing's groove, which runs from its bottom (contact angle 0) up its high shoulder on the +z
  /// or -z side only: a ball pushed past the bottom towards the low shoulder leaves the groove (no
  /// force), as it lifts off a real counterbored ring instead of finding a mirrored contact.
  int groove_side = 0;
  /// The race's spall and waviness (contact/laws/race_imperfections.hpp); null: a perfect race.
  /// They add a height to the approach at the contact's azimuth in the ring frame (and its rate to
  /// the approach rate); the normal stays the groove's.
  std::shared_ptr<const RaceImperfections> imperfections;
  /// The ball's own spall and waviness (element_imperfections.hpp: round the ball's equator, in its
  /// own frame, race_radius = ball_radius = the ball's); null: a perfect ball. Its height at the
  /// contact adds to the approach (and its rate to the approach rate), as the race's.
  std::shared_ptr<const RaceImperfections> element_imperfections;
};
SpatialSegmentResult evaluate(const BallGrooveSegment& s, const SpatialKinematics& ring,
                              const SpatialKinematics& ball);

/// The contact frame of a ball in a groove: the normal n (bearing frame, from the ball's centre
/// towards the groove's contact point, apart or not) and the frame's angular velocity (the ring's
/// plus the ball centre's azimuth rate about the ring's axis). Not valid on the axis or the arc centre.
struct GrooveContactFrame {
  Vec3 n = Vec3::Zero(), rate = Vec3::Zero();
  bool valid = false;
};
GrooveContactFrame groove_contact_frame(const BallGrooveSegment& s, const SpatialKinematics& ring,
                                        const SpatialKinematics& ball);

/// evaluate(BallGrooveSegment) in parts, for a contact whose traction grid is shared out between
/// processes: block k of the traction (integrate_traction_block at this contact's load, ellipse,
/// film and sliding; zero when apart); the contact prepared up to its traction (geometry, normal
/// force, film, sliding, the rolling-resistance couple: the laws' work besides the traction, as a
/// fixed number of doubles that a process can send on); and the whole result from the prepared
/// contact and the traction summed over the blocks in block order (sum_traction_blocks), a few
/// dozen flops. finish_groove_contact(prepare_groove_contact(...), sum of the blocks) gives the same
/// bits as evaluate: evaluate runs the same arithmetic on the same blocks in the same order.
struct PreparedGrooveContact {
  static constexpr int size = 32;  ///< doubles in write() / read()
  bool in_contact = false;         ///< false: apart or invalid input, the result has no force
  bool valid = true;
  bool rolling = false;            ///< the rolling-resistance couple applies (there is a film)
  double approach = 0, contact_angle = 0;
  Vec3 n = Vec3::Zero(), ex = Vec3::Zero(), ey = Vec3::Zero(), point = Vec3::Zero();
  Vec3 ring_position = Vec3::Zero(), ball_position = Vec3::Zero();
  double normal_force = 0, max_pressure = 0, film_thickness = 0, slip_velocity = 0, spin_velocity = 0;
  double elastic_energy = 0, damping_power = 0, rolling_moment = 0, rolling_loss = 0;
  void write(double* out) const;
  static PreparedGrooveContact read(const double* in);
};
int traction_block_count(const BallGrooveSegment& s);
/// Block `block` of the traction; with `prepared`, also the contact up to its traction.
TractionResult evaluate_traction_block(const BallGrooveSegment& s, const SpatialKinematics& ring,
                                       const SpatialKinematics& ball, int block,
                                       PreparedGrooveContact* prepared = nullptr);
SpatialSegmentResult finish_groove_contact(const PreparedGrooveContact& prepared, const TractionResult& traction);

/// A ball in its cage pocket. A = cage, B = ball. Pocket centre in the cage frame at
/// (pitch_radius cos(pocket_angle), pitch_radius sin(pocket_angle), 0). Spherical pocket: contact
/// when the ball centre is off the pocket centre by more than half the clearance; cylindrical: the
/// same, measured perpendicular to the pocket's (radial) axis. Elastic Hertz contact of the ball in
/// the concave pocket, Hunt-Crossley damping, lubricated friction as a regularised Coulomb curve.
/// Normal n: from the pocket centre (cylindrical: its axis) through the ball centre; contact point on
/// the ball's surface, x_B + r_b n. Friction: mu(|s|) Q against the tangential sliding s of the ball
/// on the cage at the contact point (smooth through s = 0). traction_force = mu Q, film 0.
enum class PocketShape { spherical, cylindrical };
struct BallPocketSegment {
  double pitch_radius = 0;    ///< m
  double pocket_angle = 0;    ///< rad, cage frame
  double clearance = 0;       ///< m, pocket diameter - ball diameter
  double ball_radius = 0;     ///< m
  PocketShape shape = PocketShape::cylindrical;
  PointNormalLaw normal;      ///< Hertz table constant in s
  TractionCurve friction;
  /// Lubricated pocket (normal = "reynolds_film", cylindrical pockets): the ball's film in the pocket
  /// (pocket_film.hpp), apart as well as in contact, its pressure and shear on both bodies (at the ball's
  /// centre), its pressure's resultant in normal_force, its work rate in power_loss, its minimum film in
  /// film_thickness; the dry Hertz contact and its friction above add where the surfaces overlap.
  std::optional<PocketFilm> film;
};
SpatialSegmentResult evaluate(const BallPocketSegment& s, const SpatialKinematics& cage,
                              const SpatialKinematics& ball);
/// evaluate(s, cage, ball).diagnostics.approach alone, the same bits: of the cage's kinematics it
/// reads the position and rotation, of the ball's the position.
double pocket_approach(const BallPocketSegment& s, const SpatialKinematics& cage, const Vec3& ball_position);

/// Cage guided on a ring land. A = cage, B = ring. The guiding surfaces are coaxial cylinders in
/// their bodies' frames (the cage's bore on an inner-ring land, or the cage's outside in an outer-
/// ring land bore) of axial width `width`, radial clearance `clearance` when centred. Evaluated at
/// `stations` points along the cage axis (>= 2 gives tilt moments), each a line contact of width
/// width/stations (Palmgren law), with regularised Coulomb friction on the sliding.
///
/// Station j sits on the cage axis at zeta_j = axial_offset + (j + 1/2) width/stations - width/2
/// (cage frame); its eccentricity e_j from the ring axis (measured perpendicular to it, in the ring
/// frame, direction u_j) gives the approach e_j - clearance (tilt of the cage's cylinder to second
/// order neglected). Inner land: the cage bore meets the land opposite to u_j; outer land: the
/// cage's outside meets the land bore on the side of u_j. The normal force pushes the ring along
/// +u_j and the cage back along -u_j, at the point midway between the two surfaces on that radial
/// line. Friction acts against the whole tangential sliding there (circumferential and axial).
/// Diagnostics: approach = the largest station approach, normal_force, elastic_energy and
/// power_loss summed, traction_force = |sum of friction forces|, slip and spin at the most loaded
/// station, max_pressure = Hertz line-contact estimate sqrt(q E* / (pi R)) at that station (E* from
/// the law's Palmgren K), contact_angle and circumferential_force 0. stations < 1: invalid.
struct CageLandSegment3 {
  double land_radius = 0;  ///< m, radius of the ring's land surface
  double clearance = 0;    ///< m, radial clearance
  double width = 0;        ///< m, axial width of the guiding contact
  double axial_offset = 0; ///< m, axial position of the land's centre in the cage frame
  int stations = 2;
  bool outer_land = false;
  LineContactLaw law;      ///< for one station (width / stations)
  TractionCurve friction;
  /// Lubricated land (normal = "short_bearing"): each station also carries its strip of the land's
  /// short journal-bearing film (land_film.hpp), apart as well as in contact, its force and power
  /// in the diagnostics (normal_force, power_loss; film_thickness the smallest station film); the
  /// dry law above adds where the surfaces overlap.
  std::optional<ShortBearingFilm> film;
};
SpatialSegmentResult evaluate(const CageLandSegment3& s, const SpatialKinematics& cage,
                              const SpatialKinematics& ring);

}  // namespace raceway::contact
