// A roller against one bar of its cage pocket, spatial kinematics: the pocket bar of a spatial
// cylindrical roller bearing. A = cage, B = roller; the roller's axis is its body z.
//
// The pocket is a slot whose walls are planes parallel to the pocket's radial line and to the
// cage's axis, at cage-frame angle `pocket_angle`; its width is roller diameter + clearance, as in
// the planar CageBarSegment (roller_segments.hpp), which this segment is when the roller and the
// cage stay in the bearing plane. The bar's contact is cut into slices along the roller: slice j's
// centre P_j lies on the roller's axis at `slice_position[j]` from the roller's centre; its
// approach is side (P_j - pocket centre) . e_t - half_clearance (e_t the cage's circumferential
// direction at the pocket), so a skewed roller presses one end of the bar harder. Each slice is a
// Palmgren line contact of stiffness `slice_stiffness` (the bar's K shared out equally) with
// Hunt-Crossley damping, its force along -side e_t on the roller at P_j + (R - approach/2) side e_t
// (the planar segment's point); the traction, mu tanh(|s| / s_scale) times the normal force against
// the roller's sliding s on the bar there (both tangent components: radial and axial), acts at the
// same point, so action equals reaction. Slices are summed in index order.
//
// Diagnostics: approach the largest slice approach; normal, traction forces, elastic energy and
// power loss summed; slip and spin at the most loaded slice; circumferential force on the roller as
// the point family defines it. Validity: a slice approach above max_approach is flagged (forces
// still computed); a non-finite input gives valid = false and no force.
#pragma once

#include <vector>

#include "contact/laws/line_contact.hpp"
#include "contact/segments/ball_segments.hpp"

namespace raceway::contact {

struct RollerPocketBarSegment {
  double pitch_radius = 0;    ///< m, radius of the pocket centres in the cage frame
  double pocket_angle = 0;    ///< rad, in the cage frame
  double half_clearance = 0;  ///< m, half the circumferential pocket clearance
  double roller_radius = 0;   ///< m
  int side = +1;              ///< +1 the bar ahead (positive sense of rotation), -1 the one behind
  std::vector<double> slice_position;  ///< m, along the roller's axis from its centre, increasing
  double slice_stiffness = 0;  ///< K_j [N/m^(10/9)], each slice
  double damping_factor = 0;   ///< s/m
  double max_approach = 0;     ///< m
  TractionCurve traction;
};

/// `slices` equal slices over `bar_width` (centred on the roller's middle), sharing Palmgren's K of
/// that width equally. Throws std::invalid_argument for slices < 1 or a non-positive width.
RollerPocketBarSegment make_roller_pocket_bar_segment(double reduced_modulus, double bar_width, int slices,
                                                      double pitch_radius, double pocket_angle, double half_clearance,
                                                      double roller_radius, int side, double damping_factor,
                                                      double max_approach, const TractionCurve& traction);

SpatialSegmentResult evaluate(const RollerPocketBarSegment& s, const SpatialKinematics& cage,
                              const SpatialKinematics& roller);

}  // namespace raceway::contact
