#include "solver/bearing/power_terms.hpp"

#include "solver/bearing/element_traits.hpp"
#include "solver/bearing/nodes.hpp"

namespace raceway::bearing {

namespace {

int power_loss_field(const SegmentLaw& law) {
  return std::visit([](const auto& l) { return diagnostic_index<std::decay_t<decltype(l)>>("power_loss"); }, law);
}

}  // namespace

PowerTerms::PowerTerms(const Model& m) : m_(m) {
  int column[segment_kind_count];
  for (int& c : column) c = -1;
  for (const Segment& seg : m.segments) column[static_cast<int>(seg.kind)] = 0;
  for (int k = 0; k < segment_kind_count; ++k) {
    if (column[k] < 0) continue;
    column[k] = static_cast<int>(loss_names_.size());
    loss_names_.emplace_back(segment_kind_name(static_cast<SegmentKind>(k)));
  }
  loss_names_.emplace_back("supports");
  loss_names_.emplace_back("nodes");
  for (const Segment& seg : m.segments) {
    loss_column_.push_back(column[static_cast<int>(seg.kind)]);
    loss_field_.push_back(power_loss_field(m.laws[static_cast<std::size_t>(seg.law)]));
  }
}

/// The contacts' power on the rings that their states do not take up: minus it is what the
/// prescribed motions deliver. The states' part is the contact wrench on the coordinates the ring's
/// equations use (planar: x, y, spin; spatial: x, y, z, the small-tilt rates, spin).
double PowerTerms::drive(const Equations& eq, double t, const double* z) const {
  double p = 0;
  for (const int b : {m_.inner_ring, m_.outer_ring}) {
    const Body& body = m_.bodies[static_cast<std::size_t>(b)];
    const Wrench& w = eq.contact_loads()[static_cast<std::size_t>(b)];
    auto state = [&](Coordinate c) { return body.slot[c] >= 0 ? z[body.slot[c]] : 0.0; };
    double total = 0;
    if (m_.kind == scene::ModelKind::planar) {
      const contact::PlanarKinematics k = m_.planar_kinematics(b, t, z);
      total = w.force.x() * k.vx + w.force.y() * k.vy + w.moment.z() * k.omega;
    } else {
      const contact::SpatialKinematics k = m_.kinematics(b, t, z);
      total = w.force.dot(k.velocity) + w.moment.dot(k.angular_velocity);
    }
    double states = w.force.x() * state(svx) + w.force.y() * state(svy) + w.force.z() * state(svz);
    states += w.moment.x() * state(swx) + w.moment.y() * state(swy) + w.moment.z() * state(swz);
    p -= total - states;
  }
  return p;
}

void PowerTerms::evaluate(const Equations& eq, double t, const double* z, double* out) const {
  for (std::size_t i = 0; i < size(); ++i) out[i] = 0.0;
  out[0] = drive(eq, t, z);
  double* loss = out + input_count;
  const std::size_t supports = loss_names_.size() - 2, nodes = loss_names_.size() - 1;
  for (std::size_t b = 0; b < m_.bodies.size(); ++b) {
    const ExternalPower p = eq.dynamics().external_power(static_cast<int>(b), t, z);
    out[1] += p.loads, out[2] += p.frame, out[3] += p.unbalance;
    loss[supports] += p.support_loss;
  }
  for (std::size_t s = 0; s < m_.segments.size(); ++s) loss[loss_column_[s]] += eq.diagnostic(s, loss_field_[s]);
  for (const auto& node : m_.nodes) loss[nodes] += node->power_loss(m_, t, z);
}

double PowerTerms::stored_energy(const Equations& eq, double t, const double* z, double energy) {
  // A body without a ring's load has no load potential (0.0, and energy - 0.0 is energy's bits).
  for (std::size_t b = 0; b < eq.model().bodies.size(); ++b)
    if (eq.model().bodies[b].ring) energy -= eq.dynamics().load_potential(static_cast<int>(b), t, z);
  return energy;
}

}  // namespace raceway::bearing
