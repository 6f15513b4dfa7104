#include "contact/laws/mixture_drag.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace raceway::contact {

OilAirMixture oil_air_mixture(double oil_density, double oil_viscosity, double oil_volume_fraction) {
  return {oil_volume_fraction * oil_density, oil_volume_fraction * oil_viscosity};
}

double sphere_drag_coefficient(double reynolds) {
  const double schiller_naumann = 24.0 / reynolds * (1.0 + 0.15 * std::pow(reynolds, 0.687));
  return std::max(schiller_naumann, 0.44);
}

SphereDrag sphere_drag(const OilAirMixture& mixture, double diameter, const Eigen::Vector3d& relative_velocity) {
  SphereDrag out;
  const double speed = relative_velocity.norm();
  if (!mixture.present() || !(speed > 0)) return out;
  out.reynolds = mixture.density * speed * diameter / mixture.viscosity;
  out.drag_coefficient = sphere_drag_coefficient(out.reynolds);
  const double area = 0.25 * std::numbers::pi * diameter * diameter;
  // 0.5 rho C_D A |v| v: at small Re, C_D |v| -> 24 eta / (rho d), so the force stays smooth through v = 0.
  out.force = -0.5 * mixture.density * out.drag_coefficient * area * speed * relative_velocity;
  out.power_loss = -out.force.dot(relative_velocity);
  return out;
}

double ring_churning_moment(const OilAirMixture& mixture, double r_inner, double r_outer, double relative_spin) {
  if (!mixture.present() || relative_spin == 0) return 0;
  const double nu = mixture.viscosity / mixture.density;
  const double faces = 2.0;
  const double per_face = 0.5 * std::numbers::pi * 0.616 * mixture.density * std::sqrt(nu) *
                          std::pow(std::abs(relative_spin), 1.5) * (std::pow(r_outer, 4) - std::pow(r_inner, 4));
  return -std::copysign(faces * per_face, relative_spin);
}

}  // namespace raceway::contact
