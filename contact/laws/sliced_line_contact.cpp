#include "contact/laws/sliced_line_contact.hpp"

#include <cmath>
#include <stdexcept>

namespace raceway::contact {

SlicedLineContact make_sliced_line_contact(double e_reduced, const RollerProfile& profile, int slices,
                                           double damping_factor, double max_approach) {
  if (slices < 1) throw std::invalid_argument("sliced line contact: slices must be >= 1");
  if (const std::string why = validate_profile(profile); !why.empty())
    throw std::invalid_argument("sliced line contact: " + why);
  const auto n = static_cast<std::size_t>(slices);
  const double l_e = effective_length(profile);
  SlicedLineContact c;
  c.slice_width = profile.length / slices;
  c.law.stiffness = palmgren_stiffness(e_reduced, l_e);
  c.law.damping_factor = damping_factor;
  c.law.max_approach = max_approach;
  c.slice_centre.assign(n, 0.0);
  for (std::size_t j = 0; j < n / 2; ++j) {  // mirrored bit for bit; an odd middle slice stays at 0
    c.slice_centre[j] = -0.5 * profile.length + (static_cast<double>(j) + 0.5) * c.slice_width;
    c.slice_centre[n - 1 - j] = -c.slice_centre[j];
  }
  for (std::size_t j = 0; j < n; ++j) {
    c.law.slice_stiffness.push_back(c.law.stiffness * c.slice_width / l_e);
    c.law.slice_drop.push_back(profile_drop(profile, c.slice_centre[j]));
  }
  return c;
}

SliceForce evaluate_slice(const SlicedLineContact& c, std::size_t j, double approach, double rate) {
  SliceForce out;
  if (!(approach > 0)) return out;
  constexpr double n = palmgren_exponent;
  const double k = c.law.slice_stiffness[j];
  const double power = std::pow(approach, n);
  out.elastic_force = k * power;
  out.elastic_energy = out.elastic_force * approach / (n + 1.0);
  const double factor = 1.0 + c.law.damping_factor * rate;
  if (factor <= 0) {  // a fast separation: no tension, the elastic work is dissipated
    out.damping_power = -out.elastic_force * rate;
    return out;
  }
  out.force = out.elastic_force * factor;
  out.damping_power = (out.force - out.elastic_force) * rate;
  out.d_approach = n * k * power / approach * factor;
  out.d_rate = out.elastic_force * c.law.damping_factor;
  return out;
}

TiltedLineForce evaluate_tilted(const SlicedLineContact& c, double approach, double tilt, double approach_rate,
                                double tilt_rate, std::span<double> slice_forces) {
  TiltedLineForce out;
  if (!std::isfinite(approach) || !std::isfinite(tilt) || !std::isfinite(approach_rate) ||
      !std::isfinite(tilt_rate)) {
    out.valid = false;
    return out;
  }
  const std::size_t n = c.slice_centre.size();
  for (std::size_t j = 0; j < n; ++j) {
    const double x = c.slice_centre[j];
    const double d = slice_approach(c, j, approach, tilt);
    if (d > c.law.max_approach) out.valid = false;
    const SliceForce f = evaluate_slice(c, j, d, approach_rate + tilt_rate * x);
    if (!slice_forces.empty()) slice_forces[j] = f.force;
    out.force += f.force;
    out.moment += f.force * x;
    out.elastic_force += f.elastic_force;
    out.elastic_energy += f.elastic_energy;
    out.damping_power += f.damping_power;
    if (f.force > out.max_slice_force) out.max_slice_force = f.force;
    // d(slice approach)/d(approach, tilt) = (1, x); the same for the rate and the tilt rate.
    const std::array<double, 4> d_slice = {f.d_approach, f.d_approach * x, f.d_rate, f.d_rate * x};
    for (std::size_t v = 0; v < 4; ++v) {
      out.d_force[v] += d_slice[v];
      out.d_moment[v] += d_slice[v] * x;
    }
  }
  return out;
}

}  // namespace raceway::contact
