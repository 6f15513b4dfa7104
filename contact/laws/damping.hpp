// Hunt-Crossley contact damping, shared by the line-contact law (line_contact.cpp) and the Hertz
// point contacts of the ball segments (segments/ball_segments.cpp).
//
// The damping force is proportional to the elastic force: F = F_el (1 + c d(delta)/dt), with c the
// damping factor [s/m] and d(delta)/dt the approach rate (> 0 closing). It vanishes with the elastic
// force at contact onset, so the total force stays continuous there (no jump, unlike a linear damper).
#pragma once

namespace raceway::contact {

/// Force of a Hunt-Crossley contact and the power its damping part dissipates.
struct DampedForce {
  double force = 0;          ///< N, >= 0: elastic + damping, clipped at zero
  double damping_power = 0;  ///< W, (force - elastic force) * approach rate, >= 0 in both branches
};

/// Hunt-Crossley damping of an elastic contact force [N] at the given approach rate [m/s].
/// A fast separation (1 + c rate < 0) would give tension, which a contact cannot carry: the force
/// is clipped at zero, and the elastic force's work is then the dissipated power.
inline DampedForce hunt_crossley(double elastic_force, double damping_factor, double approach_rate) {
  const double total = elastic_force * (1.0 + damping_factor * approach_rate);
  DampedForce out;
  out.force = total > 0 ? total : 0.0;
  out.damping_power = (out.force - elastic_force) * approach_rate;
  return out;
}

}  // namespace raceway::contact
