// Planar body dynamics: Newton in x, y and Euler about z in the bearing frame (the planar
// bearing's bodies carry sx, sy, saz, svx, svy, swz at most). The bearing frame is inertial, or
// turns with a planet carrier: then the frame's inertial forces join (carrier_frame.hpp).
#include <memory>

#include "solver/bearing/body_dynamics.hpp"
#include "solver/bearing/carrier_frame.hpp"

namespace raceway::bearing {

namespace {

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
        const auto f = frame->force(body.mass, z[sl[sx]], z[sl[sy]], z[sl[svx]], z[sl[svy]]);
        fx += f[0], fy += f[1];
      }
      mz += frame->moment(body.axial_inertia);
    }
    if (sl[sx] >= 0) {
      zdot[sl[sx]] = z[sl[svx]];
      zdot[sl[sy]] = z[sl[svy]];
      zdot[sl[svx]] = fx / body.mass;
      zdot[sl[svy]] = fy / body.mass;
    }
    if (sl[saz] >= 0) zdot[sl[saz]] = z[sl[swz]];
    if (sl[swz] >= 0) zdot[sl[swz]] = mz / body.axial_inertia;
  }

  void contact_rate_derivative(int b, const double*, const Wrench& dw, double rates[coordinate_count]) const override {
    const Body& body = m_.bodies[static_cast<std::size_t>(b)];
    for (int c = 0; c < coordinate_count; ++c) rates[c] = 0;
    const double inv_mass = 1.0 / body.mass;
    rates[svx] = dw.force.x() * inv_mass;
    rates[svy] = dw.force.y() * inv_mass;
    rates[swz] = dw.moment.z() * (1.0 / body.axial_inertia);
  }

  /// Kinematic rows (dq/dt = v), ring supports and the carrier frame's forces, analytically.
  void add_body_jacobian(double t, const double*, const std::vector<Wrench>&, const FiniteDifferenceSteps&,
                         numerics::BorderedMatrix& jac) const override {
    const auto frame = carrier_frame(m_.params().carrier, t);
    for (const Body& body : m_.bodies) {
      const auto& sl = body.slot;
      if (sl[sx] >= 0) {
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
    const double x = state(sx), y = state(sy), vx = state(svx), vy = state(svy), w = state(swz);
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
  const Model& m_;
};

}  // namespace

std::unique_ptr<BodyDynamics> make_planar_dynamics(const Model& model) { return std::make_unique<PlanarDynamics>(model); }

}  // namespace raceway::bearing
