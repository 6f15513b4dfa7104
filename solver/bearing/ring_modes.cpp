#include "solver/bearing/ring_modes.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <tuple>
#include <type_traits>

#include "solver/bearing/segment_record.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/thick_ring.hpp"

namespace raceway::bearing {

namespace {
constexpr double pi = std::numbers::pi;
}

double RimRing::frequency(int k) const {
  const auto i = static_cast<std::size_t>(k);
  return std::sqrt(stiffness[i] / mass[i]);
}

namespace {

void add_mode(RimRing& r, int n, double k, double mass, double tangential, double stretch, double damping_ratio) {
  r.order.push_back(n);
  r.stiffness.push_back(k);
  r.mass.push_back(mass);
  r.tangential.push_back(tangential);
  r.stretch.push_back(stretch);
  r.damping.push_back(2.0 * damping_ratio * std::sqrt(k * mass));
}

// Love's thin inextensional ring (ring_modes.hpp).
void add_thin_modes(RimRing& r, double damping_ratio) {
  for (int n = 2; n <= r.highest_mode; ++n) {
    const double nn = static_cast<double>(n) * n;
    const double k = pi * r.bending_stiffness * (nn - 1) * (nn - 1) / (r.radius * r.radius * r.radius);
    const double mass = pi * r.mass_per_length * r.radius * (1.0 + 1.0 / nn);
    add_mode(r, n, k, mass, 1.0 / n, 0.0, damping_ratio);
  }
}

// The thick ring (thick_ring.hpp): the shape's tangential part is -V sin for the cos family.
void add_thick_modes(RimRing& r, const scene::Material& material, double damping_ratio) {
  const ThickRingSection section = rectangular_ring(r.radius, r.thickness, r.width, material.youngs_modulus,
                                                    material.poisson_ratio, r.mass_per_length);
  for (int n = 0; n <= r.highest_mode; ++n) {
    const RingHarmonic h = thick_ring_harmonic(section, n);
    const double tangential = -h.tangential;
    add_mode(r, n, h.stiffness, h.mass, tangential, 1.0 - n * tangential, damping_ratio);
  }
}

}  // namespace

RimRing rim_ring(const scene::Scene& scene, double race_radius, double ring_mass) {
  const scene::RingSpec& spec = scene.outer_ring;
  const auto& g = scene.bearing;
  RimRing r;
  r.thickness = spec.rim_thickness > 0 ? spec.rim_thickness : 0.5 * g.outer_outside_diameter - race_radius;
  r.width = spec.rim_width > 0 ? spec.rim_width : (g.ring_width > 0 ? g.ring_width : g.roller_length);
  if (!(r.thickness > 0))
    throw std::runtime_error(fmt::format("outer_ring.rim_thickness: the outer ring leaves no rim (outside radius - race "
                                         "radius = {:.4g} mm); give rim_thickness",
                                         1e3 * r.thickness));
  r.radius = race_radius + 0.5 * r.thickness;
  const scene::Material& material = scene.material(g.ring_material);
  r.bending_stiffness = material.youngs_modulus * r.width * r.thickness * r.thickness *
                        r.thickness / 12.0;
  r.mass_per_length = ring_mass / (2.0 * pi * r.radius);
  r.highest_mode = spec.modes;
  if (r.highest_mode > ModeShapes::max_modes)
    throw std::runtime_error(fmt::format("outer_ring.modes: at most {}", ModeShapes::max_modes));
  r.theory = spec.rim_theory;
  if (r.theory == scene::BeamTheory::euler_bernoulli)
    add_thin_modes(r, spec.rim_damping_ratio);
  else
    add_thick_modes(r, material, spec.rim_damping_ratio);
  return r;
}

RingModes::RingModes(RimRing rim, int ring_body, int first_state)
    : rim_(std::move(rim)), ring_body_(ring_body), first_state_(first_state) {}

// A mode's amplitudes accelerate by its generalized forces (contacts and its own spring) over the
// modal mass. Neither gravity nor the carrier frame's forces act on a bending mode (their fields
// are uniform or linear across the rim: they project onto n = 0 and 1 only).
void RingModes::rates(const Model&, double, const double* z, const double* forces, double* zdot) const {
  for (int k = 0; k < count(); ++k) {
    const double mass = rim_.mass[static_cast<std::size_t>(k)];
    zdot[state(k, 0)] = z[state(k, 2)];
    zdot[state(k, 1)] = z[state(k, 3)];
    zdot[state(k, 2)] = forces[2 * k] / mass;
    zdot[state(k, 3)] = forces[2 * k + 1] / mass;
  }
}

void RingModes::add_force_derivative(int k, int state_index, double dq_a, double dq_b, numerics::BorderedMatrix& jac) const {
  const double inv_mass = 1.0 / rim_.mass[static_cast<std::size_t>(k)];
  const double ra = dq_a * inv_mass, rb = dq_b * inv_mass;
  if (ra != 0.0) jac.add(state(k, 2), state_index, ra);
  if (rb != 0.0) jac.add(state(k, 3), state_index, rb);
}

void RingModes::add_own_jacobian(const Model&, double, numerics::BorderedMatrix& jac) const {
  for (int k = 0; k < count(); ++k) {
    jac.add(state(k, 0), state(k, 2), 1.0);
    jac.add(state(k, 1), state(k, 3), 1.0);
  }
}

void RingModes::add_energy(const Model&, double, const double* z, double& e) const {
  for (int k = 0; k < count(); ++k) {
    const double va = z[state(k, 2)], vb = z[state(k, 3)];
    e += 0.5 * rim_.mass[static_cast<std::size_t>(k)] * (va * va + vb * vb);
  }
}

void RingModes::initial_state(std::vector<double>& z) const {  // round, at rest
  for (int k = 0; k < count(); ++k)
    for (int i = 0; i < 4; ++i) z[static_cast<std::size_t>(state(k, i))] = 0.0;
}

std::string RingModes::describe(const Model&) const {
  std::string out;
  for (int k = 0; k < count(); ++k) {
    if (k > 0 && k < count() - 1) continue;
    out += fmt::format("  {:<12} mass {:.4g} kg, inertia {:.4g} kg m^2, {} states [{}..{}): {}\n",
                       fmt::format("outer_ring_mode[{}]", rim_.order[static_cast<std::size_t>(k)]), rim_.mass[static_cast<std::size_t>(k)], 0.0, 4,
                       state(k, 0), state(k, 0) + 4, "the outer ring's bending mode: amplitudes and rates, border states");
    if (k == 0 && count() > 2) out += fmt::format("  ... ({} more modes alike)\n", count() - 2);
  }
  return out;
}

namespace {

/// Roller k's outer-race contact on the flexible rim: the ring's kinematics moved by the rim's
/// displacement at the contact's azimuth (which follows the roller: the partner), the moment back
/// about the ring's own centre; its force drives the ring whole and the modes.
class RimPointMarker final : public MarkerKind {
 public:
  explicit RimPointMarker(std::shared_ptr<const RingModes> modes) : modes_(std::move(modes)) {}
  int body() const override { return modes_->ring_body(); }
  int planning_id() const override { return modes_->ring_body(); }
  bool follows_partner() const override { return true; }

  contact::PlanarKinematics planar(const Model& m, double t, const double* z, const contact::PlanarKinematics& roller,
                                   const double* shift, MarkerPoint& point) const override {
    const contact::PlanarKinematics ring = m.planar_kinematics(body(), t, z);
    const RimPoint p = rim_point(*modes_, ring, roller, z);
    double u[4] = {p.u[0], p.u[1], p.u_rate[0], p.u_rate[1]};
    if (shift)
      for (int i = 0; i < 4; ++i) u[i] += shift[i];
    contact::PlanarKinematics moved = ring;
    moved.x += u[0], moved.y += u[1], moved.vx += u[2], moved.vy += u[3];
    for (int i = 0; i < 4; ++i) point.offset[static_cast<std::size_t>(i)] = u[i];
    return moved;
  }
  void to_reference(const MarkerPoint& point, contact::PlanarWrench& w) const override {
    w.mz += point.offset[0] * w.fy - point.offset[1] * w.fx;  // about the ring's own centre
  }
  void columns(const Model& m, bool on_a, std::vector<SegmentColumn>& out) const override {
    add_body_columns(m, body(), on_a, out);
  }
  /// The shift columns: d/d u x, u y, u' x, u' y, stepped like a mode's amplitude and rate.
  int shift_columns() const override { return 4; }
  double shift_step(const Model&, const FiniteDifferenceSteps& step, int i, const double* z) const override {
    return step(i < 2 ? modes_->state(0, 0) : modes_->state(0, 2), z);
  }
  void scatter(const Model& m, const Segment& seg, bool on_a, const double* w, double t, const double* z,
               Loads& loads) const override {
    add_wrench(loads.body[static_cast<std::size_t>(body())], w);
    const RimPoint p = rim_point(*modes_, m.planar_kinematics(body(), t, z), partner_planar(m, seg, on_a, t, z), z);
    add_modal_forces(*modes_, p, w, loads.node.data() + modes_->force_offset);
  }
  void add_rate_derivative(const JacobianAssembly& a, int state, const Wrench& dw) const override {
    if (a.model.bodies[static_cast<std::size_t>(body())].has_states()) a.add_body_rate_derivative(body(), state, dw);
  }
  void add_jacobian_terms(const JacobianAssembly& a, const Segment& seg, const std::vector<SegmentColumn>& columns,
                          const double* rec) const override;

 private:
  std::shared_ptr<const RingModes> modes_;
};

/// Mode k's amplitudes as a marker (its spring's B): x, y the amplitudes a, b, vx, vy their rates.
class ModeMarker final : public MarkerKind {
 public:
  ModeMarker(std::shared_ptr<const RingModes> modes, int k, int planning_id)
      : modes_(std::move(modes)), k_(k), planning_id_(planning_id) {}
  int body() const override { return -1; }
  int planning_id() const override { return planning_id_; }
  contact::PlanarKinematics planar(const Model&, double, const double* z, const contact::PlanarKinematics&,
                                   const double*, MarkerPoint&) const override {
    return {z[modes_->state(k_, 0)], z[modes_->state(k_, 1)], 0.0, z[modes_->state(k_, 2)], z[modes_->state(k_, 3)], 0.0};
  }
  void columns(const Model&, bool on_a, std::vector<SegmentColumn>& out) const override {
    const Coordinate coordinate[4] = {sx, sy, svx, svy};
    for (int i = 0; i < 4; ++i) out.push_back({-1, coordinate[i], modes_->state(k_, i), on_a});
  }
  void scatter(const Model&, const Segment&, bool, const double* w, double, const double*, Loads& loads) const override {
    double* q = loads.node.data() + modes_->force_offset + 2 * k_;
    q[0] += w[0];
    q[1] += w[1];
  }
  void add_rate_derivative(const JacobianAssembly& a, int state, const Wrench& dw) const override {
    modes_->add_force_derivative(k_, state, dw.force.x(), dw.force.y(), a.jac);
  }

 private:
  std::shared_ptr<const RingModes> modes_;
  int k_ = 0, planning_id_ = -1;
};

// A rim contact: its force on the ring drives the modes through Q = f . phi_n(theta), theta the
// contact's azimuth. Rows of the modes: dQ/dz = (df/dz) . phi_n + f . phi_n'(theta) dtheta/dz, with
// phi_a' = -(n - 1/n) sin(n theta) e_r and phi_b' = (n - 1/n) cos(n theta) e_r (e_r' = e_t,
// e_t' = -e_r). Columns of the modes: the contact depends on them through the rim's displacement
// u = sum phi_n a_n at the contact, so d(wrench)/d a_n = d(wrench)/d u . phi_n from the record's
// shift columns, for the ring's, the roller's and the modes' own rows.
void RimPointMarker::add_jacobian_terms(const JacobianAssembly& a, const Segment& seg,
                                        const std::vector<SegmentColumn>& columns, const double* rec) const {
  const Model& m = a.model;
  const RingModes& modes = *modes_;
  const auto* kind = std::get_if<std::shared_ptr<const MarkerKind>>(&m.markers[static_cast<std::size_t>(seg.marker_a)]);
  if (!kind || kind->get() != this) throw std::logic_error("a rim point is marker A of its contact (the ring's side)");
  const RimPoint p = rim_point(modes, m.planar_kinematics(body(), a.t, a.z), partner_planar(m, seg, true, a.t, a.z), a.z);
  const double co = p.cos_theta, si = p.sin_theta;
  const RimRing& rim = modes.rim();
  const ModeShapes shape(co, si, rim.highest_mode);
  const double radial = rec[SegmentRecord::on_a] * co + rec[SegmentRecord::on_a + 1] * si;
  const double tangential = -rec[SegmentRecord::on_a] * si + rec[SegmentRecord::on_a + 1] * co;
  // The modes' rows from a column: d (force on the ring) and d theta.
  auto add_mode_rows = [&](int state, const double* d, double dtheta) {
    const double dr = d[0] * co + d[1] * si, dt = -d[0] * si + d[1] * co;
    for (int k = 0; k < modes.count(); ++k) {
      const auto i = static_cast<std::size_t>(k);
      const int n = rim.order[i];
      const double c = shape.c[n], s = shape.s[n], inv_n = rim.tangential[i], turn = (n - inv_n) * radial * dtheta;
      double dq_a = dr * c - dt * s * inv_n - turn * s, dq_b = dr * s + dt * c * inv_n + turn * c;
      if (rim.stretch[i] != 0.0) {  // an extensible shape turns its tangential part too
        const double twist = rim.stretch[i] * tangential * dtheta;
        dq_a += twist * c, dq_b += twist * s;
      }
      modes.add_force_derivative(k, state, dq_a, dq_b, a.jac);
    }
  };
  for (std::size_t i = 0; i < columns.size(); ++i) {
    const SegmentColumn& c = columns[i];
    const double side = c.on_a ? -1.0 : 1.0;  // theta is the roller's azimuth about the ring's centre
    const double dtheta = c.coordinate == sx ? -side * si / p.distance : c.coordinate == sy ? side * co / p.distance : 0.0;
    add_mode_rows(c.state, rec + SegmentRecord::size + SegmentRecord::wrench_rows * i, dtheta);
  }
  const double* shift = rec + SegmentRecord::size + SegmentRecord::wrench_rows * columns.size();
  for (int k = 0; k < modes.count(); ++k) {
    const int n = rim.order[static_cast<std::size_t>(k)];
    const double c = shape.c[n], s = shape.s[n], inv_n = rim.tangential[static_cast<std::size_t>(k)];
    // phi_a = c e_r - (s / n) e_t, phi_b = s e_r + (c / n) e_t, as x, y components.
    const double phi[2][2] = {{c * co + s * inv_n * si, c * si - s * inv_n * co},
                              {s * co - c * inv_n * si, s * si + c * inv_n * co}};
    for (const auto& [state, shape_index, rate] : {std::tuple{modes.state(k, 0), 0, 0}, std::tuple{modes.state(k, 1), 1, 0},
                                                   std::tuple{modes.state(k, 2), 0, 1}, std::tuple{modes.state(k, 3), 1, 1}}) {
      double d[SegmentRecord::wrench_rows];
      const double* dx = shift + SegmentRecord::wrench_rows * (2 * rate);
      const double* dy = dx + SegmentRecord::wrench_rows;
      for (int r = 0; r < SegmentRecord::wrench_rows; ++r) d[r] = dx[r] * phi[shape_index][0] + dy[r] * phi[shape_index][1];
      for (int target = 0; target < 2; ++target) {
        Wrench dw;
        for (int i = 0; i < 3; ++i) dw.force[i] = d[6 * target + i], dw.moment[i] = d[6 * target + 3 + i];
        marker_add_rate_derivative(m, m.markers[static_cast<std::size_t>(target == 0 ? seg.marker_a : seg.marker_b)], a,
                                   state, dw);
      }
      add_mode_rows(state, d, 0.0);
    }
  }
}

}  // namespace

void add_ring_modes(Model& m, const scene::Scene& scene) {
  if (scene.outer_ring.flexibility != scene::RingFlexibility::ring_modes) return;
  const Body& ring = m.bodies[static_cast<std::size_t>(m.outer_ring)];
  RimRing rim = rim_ring(scene, m.outer_race_radius, ring.mass);
  const int first = m.state_size;
  for (const int n : rim.order) {
    const std::string name = fmt::format("outer_ring_mode[{}]", n);
    add_state(m, VariableClass::position, name + ".cos_amplitude");
    add_state(m, VariableClass::position, name + ".sin_amplitude");
    add_state(m, VariableClass::velocity, name + ".cos_rate");
    add_state(m, VariableClass::velocity, name + ".sin_rate");
  }
  m.add_node(std::make_shared<RingModes>(std::move(rim), m.outer_ring, first));
}

const RingModes* ring_modes_of(const Model& m) {
  for (const auto& n : m.nodes)
    if (const auto* modes = dynamic_cast<const RingModes*>(n.get())) return modes;
  return nullptr;
}

namespace {
std::shared_ptr<const RingModes> shared_ring_modes(const Model& m, int* index = nullptr) {
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    if (auto modes = std::dynamic_pointer_cast<const RingModes>(m.nodes[i])) {
      if (index) *index = static_cast<int>(i);
      return modes;
    }
  return nullptr;
}
}  // namespace

int outer_race_marker(Model& m) {
  auto modes = shared_ring_modes(m);
  if (!modes) return -1;
  static_assert(std::is_base_of_v<MarkerKind, RimPointMarker>);
  return m.add_marker(std::shared_ptr<const MarkerKind>(std::make_shared<RimPointMarker>(modes)));
}

void add_ring_mode_segments(Model& m) {
  int node = -1;
  auto modes = shared_ring_modes(m, &node);
  if (!modes) return;
  const RimRing& rim = modes->rim();
  for (int k = 0; k < modes->count(); ++k) {
    const auto i = static_cast<std::size_t>(k);
    m.laws.push_back(RingModeSpring{rim.stiffness[i], rim.damping[i]});
    const int marker =
        m.add_marker(std::shared_ptr<const MarkerKind>(std::make_shared<ModeMarker>(modes, k, m.node_planning_id(node))));
    Segment seg{SegmentKind::outer_ring_mode, m.outer_ring, m.outer_ring, static_cast<int>(m.laws.size()) - 1, -1,
                fmt::format("outer_ring_mode[{}]", rim.order[i])};
    seg.marker_b = marker;
    m.segments.push_back(seg);
  }
}

std::string describe_ring_mode_segments(const Model& m) {
  const RingModes* modes = ring_modes_of(m);
  if (!modes) return "";
  const RimRing& rim = modes->rim();
  const bool thick = rim.theory == scene::BeamTheory::timoshenko;
  const int second = thick ? 2 : 0, last = modes->count() - 1;  // the indices of n = 2 and the highest
  const auto i2 = static_cast<std::size_t>(second);
  return fmt::format("  outer_ring_mode x{}: flexible outer ring, {} rim of mean radius {:.4g} mm, section {:.4g} x "
                     "{:.4g} mm, E I = {:.4g} N m^2, {:.4g} kg/m; modes n = {}..{}: k_2 = {:.4g} N/m, f_2 = {:.4g} Hz, "
                     "f_{} = {:.4g} Hz; the outer-race contacts see the rim's displacement\n",
                     modes->count(), thick ? "thick (bending, extension, shear)" : "thin", 1e3 * rim.radius,
                     1e3 * rim.thickness, 1e3 * rim.width, rim.bending_stiffness, rim.mass_per_length, rim.order[0],
                     rim.highest_mode, rim.stiffness[i2], rim.frequency(second) / (2 * pi), rim.highest_mode,
                     rim.frequency(last) / (2 * pi));
}

ModeShapes::ModeShapes(double cos_theta, double sin_theta, int highest) {
  c[0] = 1, s[0] = 0;
  for (int n = 1; n <= highest; ++n) {
    c[n] = c[n - 1] * cos_theta - s[n - 1] * sin_theta;
    s[n] = s[n - 1] * cos_theta + c[n - 1] * sin_theta;
  }
}

RimPoint rim_point(const RingModes& modes, const contact::PlanarKinematics& ring,
                   const contact::PlanarKinematics& roller, const double* z) {
  RimPoint p;
  const double dx = roller.x - ring.x, dy = roller.y - ring.y;
  p.distance = std::hypot(dx, dy);
  p.cos_theta = dx / p.distance, p.sin_theta = dy / p.distance;
  const RimRing& rim = modes.rim();
  const ModeShapes shape(p.cos_theta, p.sin_theta, rim.highest_mode);
  double w = 0, v = 0, w_rate = 0, v_rate = 0;
  for (int k = 0; k < modes.count(); ++k) {
    const int n = rim.order[static_cast<std::size_t>(k)];
    const double c = shape.c[n], s = shape.s[n], inv_n = rim.tangential[static_cast<std::size_t>(k)];
    const double a = z[modes.state(k, 0)], b = z[modes.state(k, 1)];
    const double a_rate = z[modes.state(k, 2)], b_rate = z[modes.state(k, 3)];
    w += a * c + b * s;
    v += (b * c - a * s) * inv_n;
    w_rate += a_rate * c + b_rate * s;
    v_rate += (b_rate * c - a_rate * s) * inv_n;
  }
  // u = w e_r + v e_t with e_r = (cos, sin), e_t = (-sin, cos).
  p.u[0] = w * p.cos_theta - v * p.sin_theta, p.u[1] = w * p.sin_theta + v * p.cos_theta;
  p.u_rate[0] = w_rate * p.cos_theta - v_rate * p.sin_theta, p.u_rate[1] = w_rate * p.sin_theta + v_rate * p.cos_theta;
  return p;
}

void add_modal_forces(const RingModes& modes, const RimPoint& p, const double* on_ring, double* forces) {
  const double radial = on_ring[0] * p.cos_theta + on_ring[1] * p.sin_theta;
  const double tangential = -on_ring[0] * p.sin_theta + on_ring[1] * p.cos_theta;
  const RimRing& rim = modes.rim();
  const ModeShapes shape(p.cos_theta, p.sin_theta, rim.highest_mode);
  for (int k = 0; k < modes.count(); ++k) {
    const int n = rim.order[static_cast<std::size_t>(k)];
    const double c = shape.c[n], s = shape.s[n], inv_n = rim.tangential[static_cast<std::size_t>(k)];
    forces[2 * k] += radial * c - tangential * s * inv_n;      // f . d u / d a_n
    forces[2 * k + 1] += radial * s + tangential * c * inv_n;  // f . d u / d b_n
  }
}

}  // namespace raceway::bearing
