// A rolling element's imperfections (a spall, waviness on a ball): the race's description
// (race_imperfections.hpp) laid on the ball's surface, which turns with the ball.
//
// The ball's own frame (its orientation R maps it to the bearing frame) holds the defect: its
// equator is the plane normal to the ball's z axis, and a point of the surface in direction u
// (ball frame) has longitude phi = atan2(u_y, u_x) about that axis and latitude lambda = asin(u_z).
// The imperfections are those of a "race" of radius r (the ball's) round that equator: a spall
// centred at longitude `angle` on the equator, `length` along it, `width` across (|r lambda| <=
// width / 2), with the ball's own radius limiting how far the mating race reaches into it (the
// same path as a ball into a race's spall: a flat race rolling over a pit of the ball pivots on its
// edges exactly as a ball rolling over a pit of a flat race); waviness sum A_k cos(n_k phi +
// phase_k), the ball's radius deviation in the direction u (lobes round the equator, constant
// along each meridian).
//
// At a contact with the normal n (bearing frame, from the ball's centre towards the contact) the
// surface stands out by h(R^T n): the approach grows by h, as for a race's imperfection. Its rate:
// the contact point moves over the ball as the contact frame turns at Omega_n and the ball at w,
// d(R^T n)/dt = R^T ((Omega_n - w) x n).
//
// A roller's imperfections are the same description round its circumference: the roller's frame has
// its z axis along the roller's axis, the longitude phi about that axis places the spall (`angle`,
// `length` along the circumference), and the spall's `width` runs along the axis, centred on the
// roller's middle: a race slice at `axial` from the middle sees it where |axial| <= width / 2.
// Waviness: the roller's radius deviation sum A_k cos(n_k phi + phase_k), the same along its length.
#pragma once

#include "contact/laws/race_imperfections.hpp"
#include "contact/segments/ball_segments.hpp"

namespace raceway::contact {

/// The surface's height on the ball at a contact and its rate of change.
struct ElementHeight {
  double height = 0;  ///< m, + out of the ball (adds to the approach)
  double rate = 0;    ///< m/s, d(height)/dt as the contact point moves over the ball
};

/// The height of the ball's surface (imperfections `e`, race_radius = ball_radius = the ball's
/// radius) at the contact of normal n; ball_rotation: the ball's orientation; frame_rate: the
/// angular velocity of the contact frame (bearing frame); ball_rate: the ball's.
ElementHeight element_height(const RaceImperfections& e, const Mat3& ball_rotation, const Vec3& n,
                             const Vec3& frame_rate, const Vec3& ball_rate);

/// The height of a roller's surface (imperfections `e`, race_radius = ball_radius = the roller's
/// radius) at a contact in the direction d (bearing frame, from the roller's axis towards the
/// contact) at `axial` from the roller's middle along its axis; roller_rotation: its orientation
/// (body z the axis); frame_rate, roller_rate: the angular velocities of d and of the roller.
ElementHeight roller_height(const RaceImperfections& e, const Mat3& roller_rotation, const Vec3& d, double axial,
                            const Vec3& frame_rate, const Vec3& roller_rate);

/// The angle [rad] about the roller's axis between its spall's centre and the contact direction d.
double roller_spall_distance(const RaceImperfections& e, const Mat3& roller_rotation, const Vec3& d);

/// The angle [rad] between the spall's centre on the ball and the contact normal n (bearing frame).
double element_spall_distance(const RaceImperfections& e, const Mat3& ball_rotation, const Vec3& n);

}  // namespace raceway::contact
