// Test support shared by the roller (planar) and ball (spatial) segment cases: where a test puts the
// two bodies of a segment, and what it expects of the contact there.
#pragma once

#include "contact/segments/ball_segments.hpp"

namespace raceway::contact::test {

/// The two bodies of a segment as a test placed them, with the test's own statement of the contact
/// (written independently of contact/, so that the two can disagree). Planar vectors have z = 0.
template <class Kinematics>
struct Placed {
  Kinematics a, b;
  Vec3 normal_on_b = Vec3::Zero();  ///< unit direction of the normal force on B
  Vec3 point = Vec3::Zero();        ///< a point on the line of action of the normal force
  double contact_angle = 0;         ///< ball-groove: the placed contact angle; others 0
};

}  // namespace raceway::contact::test
