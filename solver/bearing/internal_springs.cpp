#include "solver/bearing/internal_springs.hpp"

#include <cmath>

namespace raceway::bearing {

contact::SegmentResult evaluate(const CageBridgeSpring& s, const contact::PlanarKinematics& cage,
                                const contact::PlanarKinematics& bridge) {
  contact::SegmentResult r;
  const double deflection = s.radius * (bridge.theta - cage.theta);
  const double rate = s.radius * (bridge.omega - cage.omega);
  r.valid = std::isfinite(deflection) && std::isfinite(rate);
  const double force = -(s.stiffness * deflection + s.damping * rate);  // tangential, on the bridge
  r.on_b = {0.0, 0.0, s.radius * force};
  r.on_a = {0.0, 0.0, -s.radius * force};
  r.diagnostics.approach = deflection;
  r.diagnostics.normal_force = s.stiffness * deflection;
  r.diagnostics.traction_force = force;
  r.diagnostics.slip_velocity = rate;
  r.diagnostics.elastic_energy = 0.5 * s.stiffness * deflection * deflection;
  r.diagnostics.power_loss = s.damping * rate * rate;
  return r;
}

contact::SegmentResult evaluate(const RingModeSpring& s, const contact::PlanarKinematics&,
                                const contact::PlanarKinematics& mode) {
  contact::SegmentResult r;
  const double amplitude = std::hypot(mode.x, mode.y);
  r.valid = std::isfinite(amplitude) && std::isfinite(mode.vx) && std::isfinite(mode.vy);
  r.on_b = {-(s.stiffness * mode.x + s.damping * mode.vx), -(s.stiffness * mode.y + s.damping * mode.vy), 0.0};
  r.diagnostics.approach = amplitude;
  r.diagnostics.normal_force = s.stiffness * amplitude;
  r.diagnostics.elastic_energy = 0.5 * s.stiffness * amplitude * amplitude;
  r.diagnostics.power_loss = s.damping * (mode.vx * mode.vx + mode.vy * mode.vy);
  return r;
}

}  // namespace raceway::bearing
