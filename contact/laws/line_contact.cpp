#include "contact/laws/line_contact.hpp"

#include <cmath>
#include <stdexcept>

#include "contact/laws/damping.hpp"

namespace raceway::contact {

double reduced_modulus(double youngs_1, double poisson_1, double youngs_2, double poisson_2) {
  return 1.0 / ((1.0 - poisson_1 * poisson_1) / youngs_1 + (1.0 - poisson_2 * poisson_2) / youngs_2);
}

double palmgren_stiffness(double e_reduced, double length) {
  return palmgren_coefficient * e_reduced * std::pow(length, 8.0 / 9.0);
}

LineContactLaw make_line_contact_law(double e_reduced, double length, int slices, double crown_drop,
                                     double damping_factor, double max_approach) {
  if (slices < 1) throw std::invalid_argument("line contact: slices must be >= 1");
  LineContactLaw law;
  law.stiffness = palmgren_stiffness(e_reduced, length);
  law.damping_factor = damping_factor;
  law.max_approach = max_approach;
  const double width = length / slices;
  for (int j = 0; j < slices; ++j) {
    const double x = -0.5 * length + (j + 0.5) * width;  // slice centre, from the roller middle
    const double r = 2.0 * x / length;                   // -1 .. 1 over the length
    law.slice_stiffness.push_back(law.stiffness / slices);
    law.slice_drop.push_back(crown_drop * r * r);
  }
  return law;
}

NormalForce evaluate_normal(const LineContactLaw& law, double approach, double approach_rate) {
  NormalForce out;
  if (!std::isfinite(approach) || !std::isfinite(approach_rate)) {
    out.valid = false;
    return out;
  }
  if (approach > law.max_approach) out.valid = false;
  constexpr double n = palmgren_exponent;
  for (std::size_t j = 0; j < law.slice_stiffness.size(); ++j) {
    const double d = approach - law.slice_drop[j];
    if (d <= 0) continue;
    const double f = law.slice_stiffness[j] * std::pow(d, n);
    out.elastic_force += f;
    out.elastic_energy += f * d / (n + 1.0);
  }
  const DampedForce damped = hunt_crossley(out.elastic_force, law.damping_factor, approach_rate);
  out.force = damped.force;
  out.damping_power = damped.damping_power;
  return out;
}

double TractionCurve::coefficient(double slip_velocity) const {
  if (friction_coefficient == 0) return 0;
  return friction_coefficient * std::tanh(slip_velocity / slip_velocity_scale);
}

}  // namespace raceway::contact
