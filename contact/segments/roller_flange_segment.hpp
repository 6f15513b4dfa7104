// The end of a roller against a flange (rib) of its ring: a Hertz point contact with Hunt-Crossley
// damping and traction over the contact ellipse, spatial kinematics. A = ring, B = roller. The
// flanges of NJ, NUP (and N, NU) cylindrical roller bearings guide the rollers axially and carry the
// axial load; in a tapered bearing the cone's large rib carries the rollers' axial component.
//
// Geometry (ring frame, z the ring axis; the roller's axis is its body z):
//  - the rib face is a cone about the ring axis through the circle of radius rib_radius at axial
//    position rib_axial, its normal (pointing from the rib to the roller) n = -side cos(g) e_z +
//    sin(g) e_r in every meridian plane: g the rib angle (0 a flat, radial face; g > 0 opens the face
//    away from the roller at larger radii), side = +1 a rib on the +z side of the roller;
//  - the roller's end at `side` along its axis faces the rib. Spherical end: a sphere of radius R
//    centred on the axis at l/2 - R from the roller's centre. Flat end: a flat face whose edge is
//    rounded by the corner radius r_c: a torus whose core circle (radius roller_radius - r_c) lies at
//    l/2 - r_c from the centre. The point C of the roller's end nearest the face is the sphere's
//    centre, or the core-circle point whose meridian normal n_C satisfies (n_C x axis) . tangent = 0:
//    for a surface of revolution the nearest point lies in the meridian plane of the point, so
//    D = n(C) . (C - face point at C's azimuth) is C's exact distance to the face; for the torus C
//    is found on the core circle, from the point that the face normal at the end's azimuth picks,
//    by secant steps on dD/d(angle) to round-off.
//  - approach = R - D (or r_c - D); the contact point is C - D n on the face; the normal force on the
//    roller is +Q n there.
// Hertz constants (stiffness, ellipse) are computed once, when the segment is made, at the nominal
// geometry: an aligned roller whose axis is at `axis_radius` from the ring axis. Relative curvatures
// there: along the rib's generatrix (y) 1/R or 1/r_c; circumferential (x) 1/R or, for the flat end,
// |sin g| / (rho + r_c |sin g|) of the torus, plus sin(g) / r of the cone at the contact radius r.
// A flat end needs a rib angle (a flat end on a flat rib touches along a whole edge: no Hertz point).
// A tapered roller's large end on the cone's back rib is this contact with the roller's axis leaning
// by axis_angle: a spherical end's curvatures are unchanged (its centre at axis_radius), a flat
// end's are taken in the roller's own meridian frame (roller_flange_segment.cpp).
//
// Traction: integrate_traction of the point contact (curve model) on the ellipse, x the
// circumferential direction at the contact, y = z x x, z = -n (into the ring); sliding of the
// roller's surface relative to the ring's at the contact point, spin (omega_B - omega_A) . z. The
// force and its spin couple act at the contact point, so action equals reaction.
// Validity: approach above max_approach is flagged (forces still computed); a non-finite input, or a
// flat end whose axis becomes normal to the face, gives valid = false and no force.
#pragma once

#include <string>

#include "contact/laws/point_contact.hpp"
#include "contact/laws/tapered_geometry.hpp"
#include "contact/segments/ball_segments.hpp"

namespace raceway::contact {

enum class RollerEndShape { spherical, flat };

struct RollerFlangeGeometry {
  int side = +1;              ///< the rib on the +z (+1) or -z (-1) side of the roller, ring frame
  double rib_axial = 0;       ///< m, axial position of the face at rib_radius
  double rib_radius = 0;      ///< m
  double rib_angle = 0;       ///< rad, |g| < pi/4
  RollerEndShape end = RollerEndShape::spherical;
  double roller_length = 0;   ///< l [m]
  double roller_radius = 0;   ///< m
  double end_radius = 0;      ///< m: the sphere's R (spherical), the corner radius r_c (flat)
  double axis_radius = 0;     ///< m, nominal distance of the end's centre (on the roller's axis) from the ring axis
  /// rad, a tapered roller's axis leaning from the ring axis, its `side` end outwards (0: parallel).
  /// Only the Hertz constants of a flat end read it; the contact itself follows the roller's pose.
  double axis_angle = 0;
};

struct RollerFlangeSegment {
  RollerFlangeGeometry geometry;
  HertzPointContact hertz;     ///< at the nominal geometry
  double damping_factor = 0;   ///< s/m
  double max_approach = 0;     ///< m
  PointTraction traction;      ///< model curve or none
};

/// Relative curvatures (kx circumferential, ky along the rib's generatrix) at the nominal contact,
/// and the nominal contact's distance from the ring axis. Throws std::invalid_argument for a
/// geometry without a Hertz point (flat end without rib angle, non-positive curvature, radii).
struct FlangeCurvatures {
  double kx = 0, ky = 0, contact_radius = 0;
};
FlangeCurvatures flange_curvatures(const RollerFlangeGeometry& g);

/// Empty if flange_curvatures(g) finds a Hertz point, else why not (for the scene's messages).
std::string flange_problem(const RollerFlangeGeometry& g);

/// A tapered roller's large end against the cone's back rib (side +1), the roller at its nominal
/// place: its middle at (pitch_radius, 0, 0) of the ring frame, its axis leaning by t.axis_angle,
/// `length` its whole length; the rib face is normal to the roller's axis, opening by rib_angle, and
/// passes through the end's middle (the caller moves it so that the nominal roller just touches).
RollerFlangeGeometry tapered_back_rib(const TaperedGeometry& t, double pitch_radius, double length,
                                      RollerEndShape end, double end_radius, double rib_angle);

RollerFlangeSegment make_roller_flange_segment(const RollerFlangeGeometry& g, double reduced_modulus,
                                               double damping_factor, double max_approach,
                                               const PointTraction& traction);

SpatialSegmentResult evaluate(const RollerFlangeSegment& s, const SpatialKinematics& ring,
                              const SpatialKinematics& roller);

}  // namespace raceway::contact
