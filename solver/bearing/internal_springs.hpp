// Internal springs: elements of the flexible parts that are not contacts. They use the planar
// element interface (two markers' planar kinematics in, the wrench on each and the line family's
// diagnostics out), so the equations, the output and the diagnostics treat them like any element;
// they live here, beside the nodes they load, not among the contact laws of contact/.
#pragma once

#include "contact/segments/roller_segments.hpp"

namespace raceway::bearing {

/// A flexible cage bridge's bending (the bar between two pockets): A = the cage's centre, B = the
/// bridge's marker, which translates with the cage and turns on its own: its angle less the cage's
/// is the bridge's deflection angle, `radius` times it the tangential deflection u at the pocket
/// force. The bending is a linear spring-damper, k u + c u' (on the bridge, against u; on the cage,
/// the reaction), both as moments about the common centre (a beam model, seed 003 2.2.1).
/// Diagnostics: approach = u [m] and normal_force = k u [N], both signed (+: deflected in the
/// positive sense of rotation); elastic_energy k u^2 / 2; power_loss c u'^2.
struct CageBridgeSpring {
  double radius = 0;     ///< m, where the pocket force acts on the bridge (the pitch radius)
  double stiffness = 0;  ///< N/m, tangential
  double damping = 0;    ///< N s/m, tangential
};
contact::SegmentResult evaluate(const CageBridgeSpring& s, const contact::PlanarKinematics& cage,
                                const contact::PlanarKinematics& bridge);

/// One bending mode n of a flexible outer ring (the rim of a planet gear): A = the ring's centre,
/// B = the mode's marker, whose x and y are the amplitudes a, b of the rim's radial displacement
/// w = a cos(n theta) + b sin(n theta) (solver/bearing/ring_modes.hpp) and vx, vy their rates. The
/// rim's elasticity in that mode is a linear spring-damper on the amplitudes: -(k a + c a', k b + c b')
/// on B. It is internal to the ring: a bending mode (n >= 2) has no resultant, so nothing acts on A.
/// Diagnostics: approach = sqrt(a^2 + b^2) [m], normal_force = k sqrt(a^2 + b^2) [N] (the modal
/// force), elastic_energy k (a^2 + b^2) / 2; power_loss c (a'^2 + b'^2).
struct RingModeSpring {
  double stiffness = 0;  ///< N/m, modal
  double damping = 0;    ///< N s/m, modal
};
contact::SegmentResult evaluate(const RingModeSpring& s, const contact::PlanarKinematics& ring,
                                const contact::PlanarKinematics& mode);

}  // namespace raceway::bearing
