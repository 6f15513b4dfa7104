#include "contact/laws/element_imperfections.hpp"

#include <algorithm>
#include <cmath>

namespace raceway::contact {

ElementHeight element_height(const RaceImperfections& e, const Mat3& ball_rotation, const Vec3& n,
                             const Vec3& frame_rate, const Vec3& ball_rate) {
  const Vec3 u = ball_rotation.transpose() * n;
  const double across = std::sqrt(u.x() * u.x() + u.y() * u.y());
  if (!(across > 0)) return {};  // at a pole: no longitude (and off any equatorial defect)
  const double longitude = std::atan2(u.y(), u.x());
  const double latitude = std::atan2(u.z(), across);
  const RaceHeight h = race_height(e, longitude, e.race_radius * latitude);
  const Vec3 u_rate = ball_rotation.transpose() * (frame_rate - ball_rate).cross(n);
  const double longitude_rate = (u.x() * u_rate.y() - u.y() * u_rate.x()) / (across * across);
  return {h.height, h.per_azimuth * longitude_rate};
}

double element_spall_distance(const RaceImperfections& e, const Mat3& ball_rotation, const Vec3& n) {
  const Vec3 centre(std::cos(e.spall.angle), std::sin(e.spall.angle), 0.0);
  return std::acos(std::clamp((ball_rotation * centre).dot(n) / n.norm(), -1.0, 1.0));
}

}  // namespace raceway::contact
