#include "solver/bearing/ring_modes.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "solver/bearing/segment_record.hpp"

namespace raceway::solver {

namespace {
constexpr double pi = std::numbers::pi;
}

double RimRing::frequency(int n) const {
  const auto i = static_cast<std::size_t>(n - 2);
  return std::sqrt(stiffness[i] / mass[i]);
}

RimRing rim_ring(const io::Scene& scene, double race_radius, double ring_mass) {
  const io::RingSpec& spec = scene.outer_ring;
  const auto& g = scene.bearing;
  RimRing r;
  r.thickness = spec.rim_thickness > 0 ? spec.rim_thickness : 0.5 * g.outer_outside_diameter - race_radius;
  r.width = spec.rim_width > 0 ? spec.rim_width : (g.ring_width > 0 ? g.ring_width : g.roller_length);
  if (!(r.thickness > 0))
    throw std::runtime_error(fmt::format("outer_ring.rim_thickness: the outer ring leaves no rim (outside radius - race "
                                         "radius = {:.4g} mm); give rim_thickness",
                                         1e3 * r.thickness));
  r.radius = race_radius + 0.5 * r.thickness;
  r.bending_stiffness = scene.material(g.ring_material).youngs_modulus * r.width * r.thickness * r.thickness *
                        r.thickness / 12.0;
  r.mass_per_length = ring_mass / (2.0 * pi * r.radius);
  r.highest_mode = spec.modes;
  if (r.highest_mode > ModeShapes::max_modes)
    throw std::runtime_error(fmt::format("outer_ring.modes: at most {}", ModeShapes::max_modes));
  for (int n = 2; n <= r.highest_mode; ++n) {
    const double nn = static_cast<double>(n) * n;
    const double k = pi * r.bending_stiffness * (nn - 1) * (nn - 1) / (r.radius * r.radius * r.radius);
    const double mass = pi * r.mass_per_length * r.radius * (1.0 + 1.0 / nn);
    r.stiffness.push_back(k);
    r.mass.push_back(mass);
    r.damping.push_back(2.0 * spec.rim_damping_ratio * std::sqrt(k * mass));
  }
  return r;
}

void add_ring_modes(Model& m, const io::Scene& scene) {
  if (scene.outer_ring.flexibility != io::RingFlexibility::ring_modes) return;
  const Body& ring = m.bodies[static_cast<std::size_t>(m.outer_ring)];
  const RimRing rim = rim_ring(scene, m.outer_race_radius, ring.mass);
  for (int n = 2; n <= rim.highest_mode; ++n) {
    Body b;
    b.name = fmt::format("outer_ring_mode[{}]", n);
    b.kind = BodyKind::ring_mode;
    b.index = n;
    b.mass = rim.mass[static_cast<std::size_t>(n - 2)];
    b.offset = m.state_size;
    add_state(m, b, sx, VariableClass::position, "cos_amplitude");
    add_state(m, b, sy, VariableClass::position, "sin_amplitude");
    add_state(m, b, svx, VariableClass::velocity, "cos_rate");
    add_state(m, b, svy, VariableClass::velocity, "sin_rate");
    b.size = m.state_size - b.offset;
    m.border_bodies_after_elements.push_back(b);
  }
}

void add_ring_mode_segments(Model& m, const io::Scene& scene) {
  if (m.ring_mode_count == 0) return;
  const RimRing rim = rim_ring(scene, m.outer_race_radius, m.bodies[static_cast<std::size_t>(m.outer_ring)].mass);
  for (int k = 0; k < m.ring_mode_count; ++k) {
    const auto i = static_cast<std::size_t>(k);
    m.laws.push_back(contact::RingModeSegment{rim.stiffness[i], rim.damping[i]});
    m.segments.push_back({SegmentKind::outer_ring_mode, m.outer_ring, m.first_ring_mode + k,
                          static_cast<int>(m.laws.size()) - 1, -1, fmt::format("outer_ring_mode[{}]", k + 2)});
  }
}

ModeShapes::ModeShapes(double cos_theta, double sin_theta, int highest) {
  c[0] = 1, s[0] = 0;
  for (int n = 1; n <= highest; ++n) {
    c[n] = c[n - 1] * cos_theta - s[n - 1] * sin_theta;
    s[n] = s[n - 1] * cos_theta + c[n - 1] * sin_theta;
  }
}

RimPoint rim_point(const Model& m, const contact::PlanarKinematics& ring, const contact::PlanarKinematics& roller,
                   const double* z) {
  RimPoint p;
  const double dx = roller.x - ring.x, dy = roller.y - ring.y;
  p.distance = std::hypot(dx, dy);
  p.cos_theta = dx / p.distance, p.sin_theta = dy / p.distance;
  const ModeShapes shape(p.cos_theta, p.sin_theta, m.ring_mode_count + 1);
  double w = 0, v = 0, w_rate = 0, v_rate = 0;
  for (int k = 0; k < m.ring_mode_count; ++k) {
    const auto& sl = m.bodies[static_cast<std::size_t>(m.first_ring_mode + k)].slot;
    const int n = k + 2;
    const double c = shape.c[n], s = shape.s[n], inv_n = 1.0 / n;
    w += z[sl[sx]] * c + z[sl[sy]] * s;
    v += (z[sl[sy]] * c - z[sl[sx]] * s) * inv_n;
    w_rate += z[sl[svx]] * c + z[sl[svy]] * s;
    v_rate += (z[sl[svy]] * c - z[sl[svx]] * s) * inv_n;
  }
  // u = w e_r + v e_t with e_r = (cos, sin), e_t = (-sin, cos).
  p.u[0] = w * p.cos_theta - v * p.sin_theta, p.u[1] = w * p.sin_theta + v * p.cos_theta;
  p.u_rate[0] = w_rate * p.cos_theta - v_rate * p.sin_theta, p.u_rate[1] = w_rate * p.sin_theta + v_rate * p.cos_theta;
  return p;
}

contact::SegmentResult evaluate_on_rim(const contact::RollerRaceSegment& law, const Model& m, const Segment& seg,
                                       double t, const double* z, const double* extra) {
  const contact::PlanarKinematics ring = m.planar_kinematics(seg.body_a, t, z);
  const contact::PlanarKinematics roller = m.planar_kinematics(seg.body_b, t, z);
  const RimPoint p = rim_point(m, ring, roller, z);
  double u[4] = {p.u[0], p.u[1], p.u_rate[0], p.u_rate[1]};
  if (extra)
    for (int i = 0; i < 4; ++i) u[i] += extra[i];
  contact::PlanarKinematics moved = ring;
  moved.x += u[0], moved.y += u[1], moved.vx += u[2], moved.vy += u[3];
  contact::SegmentResult r = contact::evaluate(law, moved, roller);
  r.on_a.mz += u[0] * r.on_a.fy - u[1] * r.on_a.fx;  // about the ring's own centre
  return r;
}

void rim_jacobian_record(const contact::RollerRaceSegment& law, const Model& m, const FiniteDifferenceSteps& step,
                         const Segment& seg, double t, const double* z, std::span<double> rec) {
  const contact::SegmentResult base = evaluate_on_rim(law, m, seg, t, z);
  bool ok = base.valid;
  std::vector<double> zp(z, z + m.state_size);
  const std::vector<SegmentColumn> columns = segment_columns(m, seg);
  // A planar ring has at most 5 states and a roller 5: with the shift columns 14 of the record's 24.
  if (columns.size() + rim_shift_columns > 2 * coordinate_count)
    throw std::logic_error("rim_jacobian_record: more columns than a Jacobian record holds");
  double* out = rec.data() + SegmentRecord::size;
  for (const SegmentColumn& c : columns) {
    const auto j = static_cast<std::size_t>(c.state);
    const double h = step(c.state, z);
    zp[j] = z[j] + h;
    const contact::SegmentResult r = evaluate_on_rim(law, m, seg, t, zp.data());
    zp[j] = z[j];
    ok = ok && r.valid;
    write_difference(r, base, 1.0 / h, out);
    out += SegmentRecord::wrench_rows;
  }
  // The shift columns: steps of a mode's amplitude (position) and rate (velocity) states.
  const auto& mode = m.bodies[static_cast<std::size_t>(m.first_ring_mode)].slot;
  for (int i = 0; i < rim_shift_columns; ++i) {
    double extra[rim_shift_columns] = {};
    const double h = step(i < 2 ? mode[sx] : mode[svx], z);
    extra[i] = h;
    const contact::SegmentResult r = evaluate_on_rim(law, m, seg, t, z, extra);
    ok = ok && r.valid;
    write_difference(r, base, 1.0 / h, out);
    out += SegmentRecord::wrench_rows;
  }
  std::fill(out, rec.data() + rec.size(), 0.0);  // the rest of the record (a task writes its whole record)
  write_result(base, rec);
  rec[SegmentRecord::valid] = ok ? 1.0 : 0.0;
}

void add_modal_forces(const Model& m, const RimPoint& p, const double* on_ring, std::vector<Wrench>& sums) {
  const double radial = on_ring[0] * p.cos_theta + on_ring[1] * p.sin_theta;
  const double tangential = -on_ring[0] * p.sin_theta + on_ring[1] * p.cos_theta;
  const ModeShapes shape(p.cos_theta, p.sin_theta, m.ring_mode_count + 1);
  for (int k = 0; k < m.ring_mode_count; ++k) {
    const int n = k + 2;
    const double c = shape.c[n], s = shape.s[n], inv_n = 1.0 / n;
    Wrench& w = sums[static_cast<std::size_t>(m.first_ring_mode + k)];
    w.force.x() += radial * c - tangential * s * inv_n;  // f . d u / d a_n
    w.force.y() += radial * s + tangential * c * inv_n;  // f . d u / d b_n
  }
}

}  // namespace raceway::solver
