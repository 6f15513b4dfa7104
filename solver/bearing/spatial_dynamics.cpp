// Spatial body dynamics: Newton for translation in the inertial bearing frame (centrifugal forces
// come out of the equations); balls are spheres (I dw/dt = M); rollers are bodies of revolution
// whose axis a = R e_z (R = Rx(ax) Ry(ay)) turns with their angular velocity w (bearing frame):
// Euler's equations in the bearing frame, I dw/dt = M - w x (I w) with I = I_t (1 - a a^T) + I_a a a^T,
// and the angles' rates from w (their angle about their own axis is no state unless a roller's own
// defect, which turns with it, is in the scene); the cage uses Euler's equations in
// its principal frame (I = diag(I_t, I_t, I_z)), exact for any tilt short of 90 degrees; rings the
// small-tilt rotor equations with the gyroscopic coupling of their spin.
#include <cmath>
#include <memory>

#include "solver/bearing/body_dynamics.hpp"
#include "solver/bearing/orbital_frame.hpp"

namespace raceway::bearing {

using contact::Mat3;
using contact::Vec3;

namespace {

class SpatialDynamics final : public BodyDynamics {
 public:
  explicit SpatialDynamics(const Model& model) : m_(model) {}

  void rates(int b, double t, const double* z, const Wrench& contacts, Wrench& net, double* zdot) const override {
    net = external_wrench(b, t, z);
    net.force += contacts.force;
    net.moment += contacts.moment;
    const Body& body = m_.bodies[static_cast<std::size_t>(b)];
    if (!body.has_states()) return;
    double r[coordinate_count];
    contact_rate_derivative(b, z, net, r);
    const auto& sl = body.slot;
    if (m_.has_orbital_velocity(body))
      orbital_translation_rates(body, z, r, zdot);
    else
      for (int d = 0; d < 3; ++d)
        if (sl[sx + d] >= 0) zdot[sl[sx + d]] = z[sl[svx + d]], zdot[sl[svx + d]] = r[svx + d];
    switch (body.kind) {
      case BodyKind::rolling_element:
        if (body.is_roller_axis()) {
          roller_rates(body, z, r, zdot);
          break;
        }
        if (body.ball_orientation) ball_angle_rates(body, z, zdot);
        for (int d = 0; d < 3; ++d) zdot[sl[swx + d]] = r[swx + d];
        break;
      case BodyKind::cage: cage_rates(body, z, r, zdot); break;
      case BodyKind::inner_ring:
      case BodyKind::outer_ring: ring_rates(body, m_.ring_spin(b, t, z), z, r, zdot); break;
    }
  }

  /// The rates of the velocity-type coordinates from a wrench (without gyroscopic terms).
  void contact_rate_derivative(int b, const double* z, const Wrench& w, double rates[coordinate_count]) const override {
    const Body& body = m_.bodies[static_cast<std::size_t>(b)];
    for (int c = 0; c < coordinate_count; ++c) rates[c] = 0;
    for (int d = 0; d < 3; ++d) rates[svx + d] = w.force[d] / body.mass;
    if (m_.has_orbital_velocity(body)) {  // the force along e_r, e_theta (orbital_frame.hpp)
      const Vec3 a = OrbitalFrame(z[body.slot[sx]], z[body.slot[sy]]).to_orbital(w.force / body.mass);
      for (int d = 0; d < 3; ++d) rates[svx + d] = a[d];
    }
    switch (body.kind) {
      case BodyKind::rolling_element:
        if (body.is_roller_axis()) {
          const Vec3 a = roller_axis(body, z);
          const Vec3 along = a.dot(w.moment) * a;  // I^-1 M, I = I_t (1 - a a^T) + I_a a a^T
          const Vec3 alpha = (w.moment - along) / body.transverse_inertia + along / body.axial_inertia;
          for (int d = 0; d < 3; ++d) rates[swx + d] = alpha[d];
          break;
        }
        for (int d = 0; d < 3; ++d) rates[swx + d] = w.moment[d] / body.axial_inertia;
        break;
      case BodyKind::cage: {
        const Mat3& r =
            memo_rotation(2 * static_cast<std::size_t>(b), z[body.slot[sax]], z[body.slot[say]], z[body.slot[saz]]);
        const Vec3 m_body = r.transpose() * w.moment;
        rates[swx] = m_body.x() / body.transverse_inertia;
        rates[swy] = m_body.y() / body.transverse_inertia;
        rates[swz] = m_body.z() / body.axial_inertia;
        break;
      }
      case BodyKind::inner_ring:
      case BodyKind::outer_ring:
        rates[swx] = w.moment.x() / body.transverse_inertia;
        rates[swy] = w.moment.y() / body.transverse_inertia;
        rates[swz] = w.moment.z() / body.axial_inertia;
        break;
    }
  }

  /// Kinematic rows, gyroscopic terms, supports and the rotation of the cage's contact moment into
  /// its frame: finite differences of rates() with the body's contact wrench frozen.
  void add_body_jacobian(double t, const double* z, const std::vector<Wrench>& contacts,
                         const FiniteDifferenceSteps& step, numerics::BorderedMatrix& jac) const override {
    const auto n = static_cast<std::size_t>(m_.state_size);
    std::vector<double> zp(z, z + n), f0(n), f1(n);
    Wrench net;
    for (std::size_t b = 0; b < m_.bodies.size(); ++b) {
      const Body& body = m_.bodies[b];
      if (!body.has_states()) continue;
      const int bi = static_cast<int>(b);
      rates(bi, t, z, contacts[b], net, f0.data());
      int states[coordinate_count];
      const int count = body_states(body, states);
      for (int k = 0; k < count; ++k) {
        const int j = states[k];
        const double h = step(j, z);
        zp[static_cast<std::size_t>(j)] = z[j] + h;
        rates(bi, t, zp.data(), contacts[b], net, f1.data());
        zp[static_cast<std::size_t>(j)] = z[j];
        for (int i = 0; i < count; ++i) {
          const auto row = static_cast<std::size_t>(states[i]);
          const double v = (f1[row] - f0[row]) / h;
          if (v != 0.0) jac.add(states[i], j, v);
        }
      }
    }
  }

  double body_energy(double t, const double* z) const override {
    double e = 0;
    for (const Body& body : m_.bodies) add_energy(body, t, z, e);
    return e;
  }

  ExternalPower external_power(int b, double t, const double* z) const override {
    const Body& body = m_.bodies[static_cast<std::size_t>(b)];
    // Neither a loaded, supported ring nor the cage (a rolling element): every term below is +0,
    // and the sums of PowerTerms::evaluate start at +0, so leaving it out changes no bit.
    if (!body.ring && body.kind != BodyKind::cage) return {};
    const auto& sl = body.slot;
    auto state = [&](int c) { return sl[c] >= 0 ? z[sl[c]] : 0.0; };
    const Vec3 v(state(svx), state(svy), state(svz));
    ExternalPower p;
    if (body.ring) {  // on the generalized coordinates the ring's equations use (small tilts)
      const auto& l = body.ring->load;
      p.loads = l.fx(t) * v.x() + l.fy(t) * v.y() + l.fz(t) * v.z() + l.mx(t) * state(swx) + l.my(t) * state(swy) +
                l.mz(t) * state(swz);
    }
    const Support s = support_of(body);
    p.support_loss = s.c_radial * (v.x() * v.x() + v.y() * v.y()) + s.c_axial * v.z() * v.z();
    if (body.kind == BodyKind::cage && s.c_tilt > 0) {  // the damper on the spin across the axis (external_wrench)
      const Mat3 r = memo_rotation(2 * static_cast<std::size_t>(b), state(sax), state(say), state(saz));
      const Vec3 axis = r.col(2);
      const Vec3 w_fixed = r * Vec3(state(swx), state(swy), state(swz));
      p.support_loss += s.c_tilt * (w_fixed - w_fixed.dot(axis) * axis).squaredNorm();
    } else if (body.kind != BodyKind::cage) {
      p.support_loss += s.c_tilt * (state(swx) * state(swx) + state(swy) * state(swy));
    }
    if (body.kind == BodyKind::cage && m_.params().cage.mass_eccentricity > 0) p.unbalance = unbalance_force(body, z).dot(v);
    return p;
  }

  double load_potential(int b, double t, const double* z) const override {
    const Body& body = m_.bodies[static_cast<std::size_t>(b)];
    if (!body.ring) return 0.0;
    const auto& sl = body.slot;
    auto state = [&](int c) { return sl[c] >= 0 ? z[sl[c]] : 0.0; };
    const auto& l = body.ring->load;
    return -(l.fx(t) * state(sx) + l.fy(t) * state(sy) + l.fz(t) * state(sz) + l.mx(t) * state(sax) +
             l.my(t) * state(say));
  }

  /// States of body b in coordinate order.
  static int body_states(const Body& b, int out[coordinate_count]) {
    int n = 0;
    for (int c = 0; c < coordinate_count; ++c)
      if (b.slot[c] >= 0) out[n++] = b.slot[c];
    return n;
  }

 private:
  struct Support {
    double k_radial = 0, c_radial = 0, k_axial = 0, c_axial = 0, k_tilt = 0, c_tilt = 0;
  };

  Support support_of(const Body& body) const {
    if (body.ring) {
      const auto& s = body.ring->support;
      return {s.stiffness, s.damping, s.axial_stiffness, s.axial_damping, s.tilt_stiffness, s.tilt_damping};
    }
    if (body.kind == BodyKind::cage) {
      const auto& s = m_.params().cage.support;
      return {s.radial_stiffness, s.radial_damping, s.axial_stiffness, s.axial_damping, s.tilt_stiffness, s.tilt_damping};
    }
    return {};
  }

  Wrench external_wrench(int b, double t, const double* z) const {
    const Body& body = m_.bodies[static_cast<std::size_t>(b)];
    Wrench w;
    auto state = [&](int c) { return body.slot[c] >= 0 ? z[body.slot[c]] : 0.0; };
    if (body.slot[svy] >= 0) w.force.y() -= body.mass * m_.gravity;
    if (body.kind == BodyKind::cage && m_.params().cage.mass_eccentricity > 0) w.force += unbalance_force(body, z);
    if (body.ring) {
      const auto& l = body.ring->load;
      w.force += Vec3(l.fx(t), l.fy(t), l.fz(t));
      w.moment += Vec3(l.mx(t), l.my(t), l.mz(t));
    }
    const Support s = support_of(body);
    if (s.k_radial > 0 || s.c_radial > 0) {
      w.force.x() -= s.k_radial * state(sx) + s.c_radial * state(svx);
      w.force.y() -= s.k_radial * state(sy) + s.c_radial * state(svy);
    }
    if (s.k_axial > 0 || s.c_axial > 0) w.force.z() -= s.k_axial * state(sz) + s.c_axial * state(svz);
    if (s.k_tilt > 0 || s.c_tilt > 0) {
      if (body.kind == BodyKind::cage) {
        // The spindle holds the direction of the cage axis a = R e_z: a spring with the potential
        // k (1 - a.e_z) (= k (1 - cos ax cos ay), k |tilt|^2 / 2 when small) and a damper on the
        // angular velocity across the axis, w - (w.a) a. Both are independent of the cage's turning
        // angle. (A damper on the body-frame rates wx, wy, which turn with the cage, rotates its
        // moment by the cage angle and pumps energy in for half of every cage revolution: the tilt
        // whirl that jammed the balls in 6309 case A12.)
        // The cage's kinematics keep this rotation in its slot (the same bits): a right-hand side's
        // elements asked for it at these angles.
        const Mat3 r = memo_rotation(2 * static_cast<std::size_t>(b), state(sax), state(say), state(saz));
        const Vec3 axis = r.col(2);
        const Vec3 w_fixed = r * Vec3(state(swx), state(swy), state(swz));
        w.moment += s.k_tilt * axis.cross(Vec3::UnitZ()) - s.c_tilt * (w_fixed - w_fixed.dot(axis) * axis);
      } else {
        // Rings: small-tilt rotor equations in the tilt angles themselves (states swx, swy are their rates).
        w.moment.x() -= s.k_tilt * state(sax) + s.c_tilt * state(swx);
        w.moment.y() -= s.k_tilt * state(say) + s.c_tilt * state(swy);
      }
    }
    return w;
  }

  /// The cage's static unbalance: its centre of mass sits at rho = R e (cos phi, sin phi, 0) from its
  /// axis (the state's centre; phi = cage.mass_eccentricity_angle, 0: along the cage frame's x), so
  /// Newton for the centre of mass, m (a + alpha x rho + w x (w x rho)) = F, puts -m w x (w x rho)
  /// on the centre's equation: the centrifugal force of the offset, turning with the cage (m e w_z^2
  /// outwards when it turns about its axis). The Euler term -m alpha x rho and
  /// the offset's change of the inertia tensor are left out (the cage's speed is nearly steady and
  /// e is micrometres against its radius): not a potential, so the energy sum does not hold it.
  Vec3 unbalance_force(const Body& body, const double* z) const {
    const auto& sl = body.slot;
    const Mat3 r = cardan_rotation(z[sl[sax]], z[sl[say]], z[sl[saz]]);
    const auto& cage = m_.params().cage;
    const double phase = cage.mass_eccentricity_angle, e = cage.mass_eccentricity;
    const Vec3 rho = phase == 0 ? Vec3(r.col(0) * e) : Vec3((std::cos(phase) * r.col(0) + std::sin(phase) * r.col(1)) * e);
    const Vec3 w = r * Vec3(z[sl[swx]], z[sl[swy]], z[sl[swz]]);
    return -body.mass * w.cross(w.cross(rho));
  }

  Vec3 roller_axis(const Body& body, const double* z) const {
    const auto b = static_cast<std::size_t>(&body - m_.bodies.data());
    return memo_rotation(2 * b + 1, z[body.slot[sax]], z[body.slot[say]], 0.0).col(2);
  }

  /// A roller: its axis angles' rates from w (bearing frame), and Euler's gyroscopic term
  /// w x (I w) = (I_a - I_t) (a . w) (w x a), taken through I^-1 (r holds I^-1 M).
  void roller_rates(const Body& body, const double* z, const double r[coordinate_count], double* zdot) const {
    const auto& sl = body.slot;
    const double spin_angle = sl[saz] >= 0 ? z[sl[saz]] : 0.0;  // a state only with a roller's own defect
    const Mat3 rotation =
        memo_rotation(2 * static_cast<std::size_t>(&body - m_.bodies.data()), z[sl[sax]], z[sl[say]], spin_angle);
    const Vec3 a = rotation.col(2);
    const Vec3 w(z[sl[swx]], z[sl[swy]], z[sl[swz]]);
    const Vec3 angle_rates = cardan_rates(z[sl[say]], spin_angle, rotation.transpose() * w);
    zdot[sl[sax]] = angle_rates.x();
    zdot[sl[say]] = angle_rates.y();
    if (sl[saz] >= 0) zdot[sl[saz]] = angle_rates.z();
    const Vec3 gyro = (body.axial_inertia - body.transverse_inertia) * a.dot(w) * w.cross(a);
    const Vec3 along = a.dot(gyro) * a;
    const Vec3 correction = (gyro - along) / body.transverse_inertia + along / body.axial_inertia;
    for (int d = 0; d < 3; ++d) zdot[sl[swx + d]] = r[swx + d] - correction[d];
  }

  /// A ball whose in-plane velocity states are orbital: its position's rates in the bearing frame,
  /// its velocity states' rates with the frame's turning terms (r holds the acceleration along e_r,
  /// e_theta, z).
  static void orbital_translation_rates(const Body& body, const double* z, const double r[coordinate_count], double* zdot) {
    const auto& sl = body.slot;
    const OrbitalFrame frame(z[sl[sx]], z[sl[sy]]);
    const Vec3 v(z[sl[svx]], z[sl[svy]], z[sl[svz]]);
    const Vec3 position_rates = frame.to_bearing(v);
    const Vec3 velocity_rates = frame.velocity_rates(Vec3(r[svx], r[svy], r[svz]), v);
    for (int d = 0; d < 3; ++d) zdot[sl[sx + d]] = position_rates[d], zdot[sl[svx + d]] = velocity_rates[d];
  }

  /// A ball's Cardan x-y-z angles turn with its angular velocity w (bearing frame; a sphere has no
  /// gyroscopic term): their rates from the body-frame w, R^T w.
  static void ball_angle_rates(const Body& body, const double* z, double* zdot) {
    const auto& sl = body.slot;
    const Mat3 rotation = cardan_rotation(z[sl[sax]], z[sl[say]], z[sl[saz]]);
    const Vec3 w(z[sl[swx]], z[sl[swy]], z[sl[swz]]);
    const Vec3 angle_rates = cardan_rates(z[sl[say]], z[sl[saz]], rotation.transpose() * w);
    for (int d = 0; d < 3; ++d) zdot[sl[sax + d]] = angle_rates[d];
  }

  /// Cardan x-y-z angle rates from the body-frame angular velocity, and Euler's equations.
  static void cage_rates(const Body& body, const double* z, const double r[coordinate_count], double* zdot) {
    const auto& sl = body.slot;
    const Vec3 wb(z[sl[swx]], z[sl[swy]], z[sl[swz]]);
    const Vec3 angle_rates = cardan_rates(z[sl[say]], z[sl[saz]], wb);
    for (int d = 0; d < 3; ++d) zdot[sl[sax + d]] = angle_rates[d];
    const Vec3 inertia(body.transverse_inertia, body.transverse_inertia, body.axial_inertia);
    const Vec3 gyro = wb.cross(inertia.cwiseProduct(wb));
    zdot[sl[swx]] = r[swx] - gyro.x() / inertia.x();
    zdot[sl[swy]] = r[swy] - gyro.y() / inertia.y();
    zdot[sl[swz]] = r[swz] - gyro.z() / inertia.z();
  }

  static void ring_rates(const Body& body, double spin, const double* z, const double r[coordinate_count], double* zdot) {
    const auto& sl = body.slot;
    if (sl[sax] >= 0) {
      const double wx = z[sl[swx]], wy = z[sl[swy]];
      const double gyro = body.axial_inertia / body.transverse_inertia * spin;
      zdot[sl[sax]] = wx;
      zdot[sl[say]] = wy;
      zdot[sl[swx]] = r[swx] - gyro * wy;
      zdot[sl[swy]] = r[swy] + gyro * wx;
    }
    if (sl[swz] >= 0) zdot[sl[swz]] = r[swz];
  }

  /// Adds body's terms to e one by one (the order of the sum is part of the output's bits).
  void add_energy(const Body& body, double t, const double* z, double& e) const {
    const auto& sl = body.slot;
    auto state = [&](int c) { return sl[c] >= 0 ? z[sl[c]] : 0.0; };
    const Vec3 x(state(sx), state(sy), state(sz)), v(state(svx), state(svy), state(svz));
    e += 0.5 * body.mass * v.squaredNorm();
    if (sl[svy] >= 0) e += body.mass * m_.gravity * x.y();
    if (body.is_roller_axis()) {
      const Vec3 w(state(swx), state(swy), state(swz));
      const double spin = roller_axis(body, z).dot(w);
      e += 0.5 * body.transverse_inertia * (w.squaredNorm() - spin * spin) + 0.5 * body.axial_inertia * spin * spin;
    } else if (body.kind == BodyKind::rolling_element) {
      e += 0.5 * body.axial_inertia * Vec3(state(swx), state(swy), state(swz)).squaredNorm();
    } else {
      e += 0.5 * body.transverse_inertia * (state(swx) * state(swx) + state(swy) * state(swy));
      e += 0.5 * body.axial_inertia * state(swz) * state(swz);
    }
    if (body.ring) {
      const auto& l = body.ring->load;
      e -= l.fx(t) * x.x() + l.fy(t) * x.y() + l.fz(t) * x.z() + l.mx(t) * state(sax) + l.my(t) * state(say);
    }
    const Support s = support_of(body);
    e += 0.5 * s.k_radial * (x.x() * x.x() + x.y() * x.y()) + 0.5 * s.k_axial * x.z() * x.z();
    if (body.kind == BodyKind::cage)
      e += s.k_tilt * (1.0 - std::cos(state(sax)) * std::cos(state(say)));  // see external_wrench
    else
      e += 0.5 * s.k_tilt * (state(sax) * state(sax) + state(say) * state(say));
  }

  const Model& m_;
};

}  // namespace

std::unique_ptr<BodyDynamics> make_spatial_dynamics(const Model& model) { return std::make_unique<SpatialDynamics>(model); }

}  // namespace raceway::bearing
