// Drag and churning elements of a ball bearing in an oil-air mixture (contact/laws/mixture_drag.hpp).
// A is the body the mixture moves with as a rigid body (the outer ring: at rest in a fixed housing,
// as Harris & Kotzalas take the mixture), B the body that moves through it (a ball, the cage). Pure
// functions of the two bodies' kinematics; the reaction on A makes the pair's force and moment sum to
// zero about any point, and the power the pair loses is the mixture's dissipation, power_loss >= 0.
#pragma once

#include "contact/laws/mixture_drag.hpp"
#include "contact/segments/ball_segments.hpp"

namespace raceway::contact {

/// A ball's drag force against its motion relative to the mixture at its centre.
/// Diagnostics: slip_velocity = |v relative|, traction_force = |F|, circumferential_force (the drag on
/// the ball along e_theta at its centre, < 0 against the orbit), power_loss; the rest 0.
struct BallDragSegment {
  OilAirMixture mixture;
  double ball_diameter = 0;
};
SpatialSegmentResult evaluate(const BallDragSegment& s, const SpatialKinematics& a, const SpatialKinematics& b);

/// The cage's churning moment about its own axis against its spin relative to the mixture, from its
/// two annular faces (bore and outside radii). Diagnostics: spin_velocity (the relative spin),
/// traction_force = |M| / r_outside (the moment as a force at the outside radius), power_loss.
struct CageChurningSegment {
  OilAirMixture mixture;
  double bore_radius = 0, outside_radius = 0;
};
SpatialSegmentResult evaluate(const CageChurningSegment& s, const SpatialKinematics& a, const SpatialKinematics& b);

}  // namespace raceway::contact
