// One slice of a roller on a cylindrical raceway, spatial kinematics: the element a spatial
// cylindrical roller bearing cuts each roller-race line contact into (one segment per slice, the
// slices of a roller summed in the model's fixed segment order). A = ring, B = roller; the roller's
// axis is its body z.
//
// The slice's centre S lies on the roller's axis at `position` from the roller's centre. With rho
// S's distance from the ring axis (ring frame), the approach is race_radius + (roller_radius - drop)
// - rho on an inner race (the roller outside the race) and rho - (race_radius - roller_radius +
// drop) on an outer one: a function of S alone, so a tilted roller loads its slices by their
// distance from the race (tilt and edge loading follow), and skew (a turn about the radial line)
// moves the slice's rolling direction, not its approach, to first order. The normal force, the
// slice's Palmgren law with Hunt-Crossley damping (sliced_line_contact.hpp: K_j and drop_j of its
// slice), acts along the ring's radial line through S (outwards on the roller on an inner race), at
// the race's surface; the traction, mu_max tanh(|s| / s_scale) times the normal force against the
// roller's sliding s relative to the race there (its components in the race's tangent plane), acts
// at the same point: action equals reaction. Approach rate: -n . (v_B - v_A) at that point.
// Validity: approach above max_approach flagged (forces still computed); a non-finite input, or S
// on the ring axis, gives valid = false and no force.
//
// A conical raceway (a tapered roller bearing's cup or cone: race_angle alpha != 0) is the same
// slice on a race whose radius grows along the ring's axis, r(z) = race_radius + z tan(alpha) in
// the ring frame. In S's meridian plane the race is a straight line of unit normal n_r = cos(alpha)
// e_r - sin(alpha) e_z (outwards); with d = (rho - race_radius) cos(alpha) - z sin(alpha) S's signed
// distance from it, the approach is reach - d on an inner race and reach + d on an outer one, the
// normal force acts along +n_r (inner) or -n_r (outer) on the roller at S's foot S - d n_r on the
// race, and everything else is as above. roller_radius is then the distance from the roller's axis
// to its surface measured along that normal, r(x) cos(gamma) for a roller cone of half angle gamma.
// The contact_angle diagnostic is alpha (the normal's angle to the radial plane, in the ring frame).
// alpha = 0 keeps the cylindrical arithmetic above, bit for bit.
//
// A race's imperfections (a spall, waviness: contact/laws/race_imperfections.hpp) move its surface
// along the normal by a height at S's azimuth in the ring's own frame, the spall acting on the
// slices whose centres lie within half its width of the race's middle (axial 0 in the ring frame);
// the approach grows by the height and its rate by the height's change as S moves round the race.
// The roller's radius limits its drop into a short spall as a ball's does (the rolling direction's
// curvature). Without imperfections nothing changes, bit for bit.
//
// The roller's own imperfections (a spall, waviness on it: contact/laws/element_imperfections.hpp)
// stand out of the roller at the contact's direction from its axis in the roller's frame (its
// orientation then carries its angle about its axis) and at the slice's place along it: the approach
// grows by that height and its rate by the height's change as the roller turns relative to the
// contact's normal (which turns with S's azimuth about the ring's axis).
//
// Lubricated (`ehd` set: normal = "moes_ehd"), the slice is an EHD line contact of the slice's width
// (lubricated_line_contact.hpp): Palmgren's K_j carries the Moes film's load at the slice's own gap
// (minus its approach) and entrainment speed, so the slices share a roller's load by their own
// film and deflection as the dry slices do by their approach; the film carries load up to its cutoff
// gap, apart as well. The film's reduced radius is the slice's: 1/R = 1/roller_radius +- 1/race_radius.
// With `ehd->traction` the Couette friction of the film acts against the slice's sliding (its
// tangent-plane slip, rolling and axial, as the dry curve's) and the Poiseuille force of its width
// against the rolling, both at the contact point; else the traction curve on the film's force. The
// entrainment speed u_m is the mean of the two surfaces' speeds along the rolling direction
// t = e_z x e_r of the ring frame relative to the contact point, which follows S about the ring's
// axis: the ring's -race_radius * (S's azimuth rate in the ring frame), the roller's that plus the
// slip along t. Cylindrical races only (race_angle = 0). Restricted to the plane this is the planar
// roller-race film (roller_segments.hpp) of a line contact as long as the slice is wide.
#pragma once

#include <memory>
#include <optional>

#include "contact/laws/race_imperfections.hpp"
#include "contact/laws/sliced_line_contact.hpp"
#include "contact/segments/ball_segments.hpp"
#include "contact/segments/roller_segments.hpp"

namespace raceway::contact {

struct RollerSliceSegment {
  double race_radius = 0;     ///< m
  double roller_radius = 0;   ///< m
  bool outer = false;         ///< the outer race (roller inside its bore)
  double race_angle = 0;      ///< rad, the raceway's generatrix from the ring axis (0: a cylinder)
  double position = 0;        ///< m, the slice centre along the roller's axis from its centre
  double drop = 0;            ///< m, the profile drop at the slice centre
  double stiffness = 0;       ///< K_j [N/m^(10/9)]
  double damping_factor = 0;  ///< s/m
  double max_approach = 0;    ///< m
  TractionCurve traction;
  std::shared_ptr<const RaceImperfections> imperfections;  ///< the race's spall and waviness; null: perfect
  std::shared_ptr<const RaceImperfections> roller_imperfections;  ///< the roller's own; null: a perfect roller
  /// The EHD film of the slice (its length the slice's width, K the slice's); null: dry. The
  /// film's reduced_radius is taken from the radii above when evaluated.
  std::optional<EhdRaceFilm> ehd;
};

/// Slice j of a sliced roller-race contact.
RollerSliceSegment make_roller_slice_segment(const SlicedLineContact& contact, std::size_t slice,
                                             double race_radius, double roller_radius, bool outer,
                                             const TractionCurve& traction);

SpatialSegmentResult evaluate(const RollerSliceSegment& s, const SpatialKinematics& ring,
                              const SpatialKinematics& roller);

}  // namespace raceway::contact
