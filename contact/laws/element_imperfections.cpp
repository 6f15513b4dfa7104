#include "contact/laws/element_imperfections.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

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

namespace {
/// The longitude about the body's z axis of a direction d (bearing frame) and its rate as d turns
/// at frame_rate and the body at body_rate; valid = false on the axis.
struct Longitude {
  bool valid = false;
  double angle = 0, rate = 0;
};
Longitude longitude_of(const Mat3& rotation, const Vec3& d, const Vec3& frame_rate, const Vec3& body_rate) {
  const Vec3 u = rotation.transpose() * d;
  const double across2 = u.x() * u.x() + u.y() * u.y();
  if (!(across2 > 0)) return {};
  const Vec3 u_rate = rotation.transpose() * (frame_rate - body_rate).cross(d);
  return {true, std::atan2(u.y(), u.x()), (u.x() * u_rate.y() - u.y() * u_rate.x()) / across2};
}
}  // namespace

ElementHeight roller_height(const RaceImperfections& e, const Mat3& roller_rotation, const Vec3& d, double axial,
                            const Vec3& frame_rate, const Vec3& roller_rate) {
  const Longitude phi = longitude_of(roller_rotation, d, frame_rate, roller_rate);
  if (!phi.valid) return {};
  const RaceHeight h = race_height(e, phi.angle, axial);
  return {h.height, h.per_azimuth * phi.rate};
}

double roller_spall_distance(const RaceImperfections& e, const Mat3& roller_rotation, const Vec3& d) {
  const Vec3 u = roller_rotation.transpose() * d;
  return std::abs(std::remainder(std::atan2(u.y(), u.x()) - e.spall.angle, 2.0 * std::numbers::pi));
}

double element_spall_distance(const RaceImperfections& e, const Mat3& ball_rotation, const Vec3& n) {
  const Vec3 centre(std::cos(e.spall.angle), std::sin(e.spall.angle), 0.0);
  return std::acos(std::clamp((ball_rotation * centre).dot(n) / n.norm(), -1.0, 1.0));
}

}  // namespace raceway::contact
