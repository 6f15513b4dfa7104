#include "solver/bearing/marker.hpp"

#include <stdexcept>

#include "solver/bearing/equations.hpp"
#include "solver/bearing/model.hpp"

namespace raceway::bearing {

contact::SpatialKinematics MarkerKind::spatial(const Model&, double, const double*) const {
  throw std::logic_error("this marker kind attaches elements of the line family only");
}

contact::SpatialKinematics marker_spatial(const Model& m, const Marker& marker, double t, const double* z) {
  if (const auto* centre = std::get_if<BodyCentre>(&marker)) return m.kinematics(centre->body, t, z);
  return std::get<std::shared_ptr<const MarkerKind>>(marker)->spatial(m, t, z);
}

contact::PlanarKinematics marker_planar(const Model& m, const Marker& marker, double t, const double* z) {
  if (const auto* centre = std::get_if<BodyCentre>(&marker)) return m.planar_kinematics(centre->body, t, z);
  MarkerPoint point;
  return std::get<std::shared_ptr<const MarkerKind>>(marker)->planar(m, t, z, contact::PlanarKinematics{}, nullptr,
                                                                     point);
}

contact::PlanarKinematics partner_planar(const Model& m, const Segment& seg, bool on_a, double t, const double* z) {
  return marker_planar(m, m.markers[static_cast<std::size_t>(on_a ? seg.marker_b : seg.marker_a)], t, z);
}

void marker_add_rate_derivative(const Model& m, const Marker& marker, const JacobianAssembly& a, int state,
                                const Wrench& dw) {
  if (const auto* centre = std::get_if<BodyCentre>(&marker)) {
    if (m.bodies[static_cast<std::size_t>(centre->body)].has_states()) a.add_body_rate_derivative(centre->body, state, dw);
    return;
  }
  std::get<std::shared_ptr<const MarkerKind>>(marker)->add_rate_derivative(a, state, dw);
}

int marker_body(const Marker& marker) {
  if (const auto* centre = std::get_if<BodyCentre>(&marker)) return centre->body;
  return std::get<std::shared_ptr<const MarkerKind>>(marker)->body();
}

void JacobianAssembly::add_body_rate_derivative(int b, int state, const Wrench& dw) const {
  equations.add_rate_derivative(b, state, z, dw, jac);
}

}  // namespace raceway::bearing
