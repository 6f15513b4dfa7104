// Planar body dynamics: Newton in x, y and Euler about z in the bearing frame (the planar
// bearing's bodies carry sx, sy, saz, svx, svy, swz at most). The bearing frame is inertial, or
// turns with a planet carrier: then the frame's inertial forces join (carrier_frame.hpp).
#include <memory>

#include "solver/bearing/body_dynamics.hpp"
#include "solver/bearing/carrier_frame.hpp"
#include "solver/bearing/orbital_frame.hpp"

namespace raceway::bearing {

namespace {

using contact::Vec3;

class PlanarDynamics final : public BodyDynamics {
 public:
  explicit PlanarDynamics(const Model& model) : m_(model) {}

  void rates(int b, double t, const double* z, const Wrench& contacts, Wrench& net, double* zdot) const override {
    const Body& body = m_.bodies[static_cast<std::size_t>(b)];
    const auto& sl = body.slot;
    double fx = contacts.force.x(), fy = contacts.force.y(), mz = contacts.moment.z();
    if (sl[svy] >= 0) fy -= body.mass * m_.gravity;
    if (body.ring) {
      fx += body.ring->load.fx(t);
      fy += body.ring->load.fy(t);
      mz += body.ring->load.mz(t);
      const auto& sup = body.ring->support;
      if (sup.stiffness > 0 && sl[sx] >= 0) {
        fx -= sup.stiffness * z[sl[sx]] + sup.damping * z[sl[svx]];
        fy -= sup.stiffness * z[sl[sy]] + sup.damping * z[sl[svy]];
      }
    }
    net = Wrench{};
    net.force.x() = fx, net.force.y() = fy, net.moment.z() = mz;
    // The carrier frame's inertial forces drive the rates; the net wrench holds the real forces.
    if (const auto frame = carrier_frame(m_.params().carrier, t)) {
      if (sl[sx] >= 0) {
        const Vec3 v = bearing_velocity(body, z);
        const auto f = frame->force(body.mass, z[sl[sx]], z[sl[sy]], v.x(), v.y());
        fx += f[0], fy += f[1];
      }
      mz += frame->moment(body.axial_inertia);
    }
    if (m_.has_orbital_velocity(body)) {
      orbital_translation_rates(body, fx, fy, z, zdot);
    } else if (sl[sx] >= 0) {
      zdot[sl[sx]] = z[sl[svx]];
      zdot[sl[sy]] = z[sl[svy]];
      zdot[sl[svx]] = fx / body.mass;
      zdot[sl[svy]] = fy / body.mass;
    }
    if (sl[saz] >= 0) zdot[sl[saz]] = z[sl[swz]];
    if (sl[swz] >= 0) zdot[sl[swz]] = mz / body.axial_inertia;
  }

  void contact_rate_derivative(int b, const double* z, const Wrench& dw, double rates[coordinate_count]) const override {
    const Body& body = m_.bodies[static_cast<std::size_t>(b)];
    for (int c = 0; c < coordinate_count; ++c) rates[c] = 0;
    const double inv_mass = 1.0 / body.mass;
    rates[svx] = dw.force.x() * inv_mass;
    rates[svy] = dw.force.y() * inv_mass;
    rates[swz] = dw.moment.z() * (1.0 / body.axial_inertia);
    if (m_.has_orbital_velocity(body)) {  // the force along e_r, e_theta (orbital_frame.hpp)
      const Vec3 a = OrbitalFrame(z[body.slot[sx]], z[body.slot[sy]]).to_orbital({rates[svx], rates[svy], 0.0});
      rates[svx] = a.x(), rates[svy] = a.y();
    }
  }

  /// Kinematic rows (dq/dt = v), ring supports and the carrier frame's forces, analytically; a rolling
  /// element with orbital velocities by differences of its rates (its frame's turning terms).
  void add_body_jacobian(double t, const double* z, const std::vector<Wrench>& contacts,
                         const FiniteDifferenceSteps& step, numerics::BorderedMatrix& jac) const override {
    const auto frame = carrier_frame(m_.params().carrier, t);
    std::vector<double> scratch;
    for (const Body& body : m_.bodies) {
      const auto& sl = body.slot;
      if (m_.has_orbital_velocity(body)) {
        add_orbital_jacobian(body, t, z, contacts[static_cast<std::size_t>(&body - m_.bodies.data())], step, scratch, jac);
      } else if (sl[sx] >= 0) {
        jac.add(sl[sx], sl[svx], 1.0);
        jac.add(sl[sy], sl[svy], 1.0);
        if (body.ring && body.ring->support.stiffness > 0) {
          const auto& sup = body.ring->support;
          for (int d = 0; d < 2; ++d) {
            jac.add(sl[svx + d], sl[sx + d], -sup.stiffness / body.mass);
            jac.add(sl[svx + d], sl[svx + d], -sup.damping / body.mass);
          }
        }
        if (frame) {
          const auto d = frame->force_derivative();
          const int columns[4] = {sl[sx], sl[sy], sl[svx], sl[svy]};
          for (int row = 0; row < 2; ++row)
            for (int k = 0; k < 4; ++k)
              if (d[row][k] != 0.0) jac.add(sl[svx + row], columns[k], d[row][k]);
        }
      }
      if (sl[saz] >= 0) jac.add(sl[saz], sl[swz], 1.0);
    }
  }

  double body_energy(double t, const double* z) const override {
    double e = 0;
    for (const Body& body : m_.bodies) {
      const auto& sl = body.slot;
      if (sl[svx] >= 0) {
        const double vx = z[sl[svx]], vy = z[sl[svy]];
        const double x = z[sl[sx]], y = z[sl[sy]];
        e += 0.5 * body.mass * (vx * vx + vy * vy);
        e += body.mass * m_.gravity * y;
        if (body.ring) {
          e -= body.ring->load.fx(t) * x + body.ring->load.fy(t) * y;
          e += 0.5 * body.ring->support.stiffness * (x * x + y * y);
        }
        if (const auto frame = carrier_frame(m_.params().carrier, t)) e += frame->potential(body.mass, x, y);
      }
      if (sl[swz] >= 0) {
        const double w = z[sl[swz]];
        e += 0.5 * body.axial_inertia * w * w;
      }
    }
    return e;
  }

  ExternalPower external_power(int b, double t, const double* z) const override {
    const Body& body = m_.bodies[static_cast<std::size_t>(b)];
    const auto& sl = body.slot;
    auto state = [&](Coordinate c) { return sl[c] >= 0 ? z[sl[c]] : 0.0; };
    const Vec3 v = bearing_velocity(body, z);
    const double x = state(sx), y = state(sy), vx = v.x(), vy = v.y(), w = state(swz);
    ExternalPower p;
    if (body.ring) {
      p.loads = body.ring->load.fx(t) * vx + body.ring->load.fy(t) * vy + body.ring->load.mz(t) * w;
      const auto& sup = body.ring->support;
      if (sup.stiffness > 0 && sl[sx] >= 0) p.support_loss = sup.damping * (vx * vx + vy * vy);
    }
    if (const auto frame = carrier_frame(m_.params().carrier, t)) {
      // Euler force and moment; Coriolis does no work; the centrifugal potential in body_energy
      // changes in time with the carrier's speed: its partial derivative is the frame's work too.
      const double a = frame->acceleration, rx = frame->radius + x;
      if (sl[sx] >= 0)
        p.frame = body.mass * a * (y * vx - rx * vy) - body.mass * frame->speed * a * (rx * rx + y * y);
      p.frame += frame->moment(body.axial_inertia) * w;
    }
    return p;
  }

  double load_potential(int b, double t, const double* z) const override {
    const Body& body = m_.bodies[static_cast<std::size_t>(b)];
    const auto& sl = body.slot;
    if (!body.ring || sl[svx] < 0) return 0.0;
    return -(body.ring->load.fx(t) * z[sl[sx]] + body.ring->load.fy(t) * z[sl[sy]]);
  }

 private:
  /// The body's in-plane velocity in the bearing frame (its states' own unless orbital).
  Vec3 bearing_velocity(const Body& body, const double* z) const {
    const auto& sl = body.slot;
    if (sl[svx] < 0) return Vec3::Zero();
    const Vec3 v(z[sl[svx]], z[sl[svy]], 0.0);
    return m_.has_orbital_velocity(body) ? OrbitalFrame(z[sl[sx]], z[sl[sy]]).to_bearing(v) : v;
  }

  /// A rolling element with orbital velocities: its positions' rates in the bearing frame and its
  /// velocity states' rates from the force (fx, fy) with the frame's turning terms.
  static void orbital_translation_rates(const Body& body, double fx, double fy, const double* z, double* zdot) {
    const auto& sl = body.slot;
    const OrbitalFrame frame(z[sl[sx]], z[sl[sy]]);
    const Vec3 v(z[sl[svx]], z[sl[svy]], 0.0);
    const Vec3 position_rates = frame.to_bearing(v);
    const Vec3 velocity_rates = frame.velocity_rates(frame.to_orbital({fx / body.mass, fy / body.mass, 0.0}), v);
    zdot[sl[sx]] = position_rates.x(), zdot[sl[sy]] = position_rates.y();
    zdot[sl[svx]] = velocity_rates.x(), zdot[sl[svy]] = velocity_rates.y();
  }

  /// Its translational rows by forward differences of rates() in x, y, v_r, v_theta, the contact
  /// wrench frozen (the frame's turning terms and the frozen force turned with the frame's angle).
  void add_orbital_jacobian(const Body& body, double t, const double* z, const Wrench& contacts,
                            const FiniteDifferenceSteps& step, std::vector<double>& scratch,
                            numerics::BorderedMatrix& jac) const {
    const auto n = static_cast<std::size_t>(m_.state_size);
    scratch.assign(z, z + n);
    scratch.resize(3 * n);
    double* zp = scratch.data();
    double* f0 = zp + n;
    double* f1 = f0 + n;
    const int b = static_cast<int>(&body - m_.bodies.data());
    Wrench net;
    rates(b, t, z, contacts, net, f0);
    const int states[4] = {body.slot[sx], body.slot[sy], body.slot[svx], body.slot[svy]};
    for (const int j : states) {
      const double h = step(j, z);
      zp[j] = z[j] + h;
      rates(b, t, zp, contacts, net, f1);
      zp[j] = z[j];
      for (const int i : states)
        if (const double d = (f1[i] - f0[i]) / h; d != 0.0) jac.add(i, j, d);
    }
  }

  const Model& m_;
};

}  // namespace

std::unique_ptr<BodyDynamics> make_planar_dynamics(const Model& model) { return std::make_unique<PlanarDynamics>(model); }

}  // namespace raceway::bearing
