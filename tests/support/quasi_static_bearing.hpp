// A quasi-static ball bearing solved independently of solver/bearing/ball_startup.cpp: each ball on
// the line between its grooves' curvature centres with the series Hertz stiffness of its two
// contacts, Newton on the inner ring's displacement (the classical Jones-Harris picture without
// centrifugal and gyroscopic terms). Shared by the spatial quasi-static and angular contact tests.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "contact/laws/point_contact.hpp"
#include "contact/segments/ball_segments.hpp"
#include "io/scene/scene.hpp"

namespace raceway::test {

using contact::Vec3;

/// Single-arc ball bearing geometry as documented at groove_arcs (solver/bearing/ball_model.cpp):
/// groove radii r_g = f D. Deep groove: arc centres at radius r_p + (r_gi - R_b) - P_d/4 (inner, in
/// the inner ring's frame) and r_p - (r_go - R_b) + P_d/4 (outer), axial 0. Angular contact: on the
/// line through a centred ball at the free contact angle alpha_0, r_p + (r_gi - R_b) cos alpha_0 at
/// axial (r_gi - R_b) sin alpha_0 (inner) and r_p - (r_go - R_b) cos alpha_0 at -(r_go - R_b) sin
/// alpha_0 (outer), no clearance shift. Hertz constants from
/// contact::hertz_point_contact with the curvatures of the contact at angle alpha: ball 1/R_b both
/// ways; groove -1/r_g across; race +-cos(alpha)/rho along the rolling direction, rho = r_p -+ R_b
/// cos(alpha) (the same curvature function the model tabulates; the dynamics' exact contact radius
/// differs by P_d/4 = 4 um out of 27 mm, 1e-4 of the race curvature term, negligible).
struct QuasiStaticBearing {
  double rp = 0, rb = 0, rgi = 0, rgo = 0, pd = 0, e_star = 0;
  double r_inner_arc = 0, r_outer_arc = 0;
  double z_inner_arc = 0, z_outer_arc = 0;
  int z = 0;
  std::vector<double> ball_oversize;  ///< per ball (diameter less the nominal one); empty: all nominal

  explicit QuasiStaticBearing(const scene::Scene& s) {
    const auto& g = s.bearing;
    rp = 0.5 * g.pitch_diameter;
    rb = 0.5 * g.ball.ball_diameter;
    rgi = g.ball.inner_conformity * g.ball.ball_diameter;
    rgo = g.ball.outer_conformity * g.ball.ball_diameter;
    pd = g.radial_clearance;
    const auto& ball = s.materials.at(g.roller_material);
    const auto& ring = s.materials.at(g.ring_material);
    e_star = 1.0 / ((1 - ball.poisson_ratio * ball.poisson_ratio) / ball.youngs_modulus +
                    (1 - ring.poisson_ratio * ring.poisson_ratio) / ring.youngs_modulus);
    if (g.type == scene::BearingType::angular_contact_ball) {
      const double a0 = g.ball.free_contact_angle;
      r_inner_arc = rp + (rgi - rb) * std::cos(a0), z_inner_arc = (rgi - rb) * std::sin(a0);
      r_outer_arc = rp - (rgo - rb) * std::cos(a0), z_outer_arc = -(rgo - rb) * std::sin(a0);
    } else {
      r_inner_arc = rp + (rgi - rb) - 0.25 * pd;
      r_outer_arc = rp - (rgo - rb) + 0.25 * pd;
    }
    z = g.rolling_elements;
  }

  /// Hertz stiffness K (Q = K delta^1.5) of the inner or outer contact at contact angle alpha.
  /// r: the ball's radius (default the nominal one).
  double stiffness(bool outer, double cos_alpha, double r = 0) const {
    if (r == 0) r = rb;
    const double rho = outer ? rp + r * cos_alpha : rp - r * cos_alpha;
    const double kx = 1.0 / r + (outer ? -cos_alpha : cos_alpha) / rho;
    const double ky = 1.0 / r - 1.0 / (outer ? rgo : rgi);
    return contact::hertz_point_contact(kx, ky, e_star).stiffness;
  }

  struct Ball {
    double load = 0;       ///< N, the same at both contacts
    double cos_alpha = 1;  ///< of the line of centres
    double sin_alpha = 0;  ///< its axial component, from the outer arc centre towards the inner one
    Vec3 force_on_inner;   ///< N, bearing frame
    Vec3 position;         ///< ball centre
  };

  /// One ball at azimuth psi (about the fixed outer ring's axis), inner ring displaced by c: the
  /// ball sits on the line between the outer arc centre (at psi) and the inner arc centre (at the
  /// ball's azimuth about the inner ring's axis); total approach delta = |C_i - C_o| - (r_gi - R_b)
  /// - (r_go - R_b); Q = K_eff delta^1.5, K_eff = (K_i^-2/3 + K_o^-2/3)^-3/2.
  /// oversize: the ball's diameter less the nominal one (its surface reaches oversize / 2 further
  /// into each groove).
  Ball ball(double psi, const Vec3& c, double oversize = 0) const {
    const double r = rb + 0.5 * oversize;
    const Vec3 e(std::cos(psi), std::sin(psi), 0.0);
    Ball b;
    b.position = rp * e;
    for (int pass = 0; pass < 3; ++pass) {  // the inner arc's azimuth depends on the ball's position
      const double phi = std::atan2(b.position.y() - c.y(), b.position.x() - c.x());
      const Vec3 co = r_outer_arc * e + Vec3(0.0, 0.0, z_outer_arc);
      const Vec3 ci = c + Vec3(r_inner_arc * std::cos(phi), r_inner_arc * std::sin(phi), z_inner_arc);
      const Vec3 d = ci - co;
      const double length = d.norm();
      const Vec3 u = d / length;  // from the outer arc centre through the ball to the inner one
      b.cos_alpha = std::hypot(u.x(), u.y());
      b.sin_alpha = u.z();
      const double ki = stiffness(false, b.cos_alpha, r), ko = stiffness(true, b.cos_alpha, r);
      const double k_eff = std::pow(std::pow(ki, -2.0 / 3.0) + std::pow(ko, -2.0 / 3.0), -1.5);
      const double delta = length - (rgi - r) - (rgo - r);
      b.load = delta > 0 ? k_eff * std::pow(delta, 1.5) : 0.0;
      const double delta_o = b.load > 0 ? std::pow(b.load / ko, 2.0 / 3.0) : 0.0;
      b.position = co + ((rgo - r) + delta_o) * u;
      // The inner contact's normal points from the ball centre away from the inner arc centre's side:
      // the ball pushes the inner ring along -u.
      b.force_on_inner = -b.load * u;
    }
    return b;
  }

  /// Sum of the balls' forces on the inner ring plus the applied load.
  Vec3 residual(const std::vector<double>& psi, const Vec3& c, const Vec3& load) const {
    Vec3 f = load;
    for (std::size_t k = 0; k < psi.size(); ++k) f += ball(psi[k], c, ball_oversize.empty() ? 0.0 : ball_oversize[k]).force_on_inner;
    return f;
  }

  /// Newton (with step halving) on the components `free` of the inner ring's displacement c (the
  /// others held) so that the balls at azimuths psi balance `load` along those components.
  Vec3 solve(const std::vector<double>& psi, const Vec3& load, Vec3 c, const std::vector<int>& free) const {
    const auto n = static_cast<Eigen::Index>(free.size());
    auto reduced = [&](const Vec3& cc) {
      const Vec3 r = residual(psi, cc, load);
      Eigen::VectorXd out(n);
      for (Eigen::Index i = 0; i < n; ++i) out[i] = r[free[static_cast<std::size_t>(i)]];
      return out;
    };
    const double h = 1e-10;  // m: 1e-5 of the deflections, far above round-off (~1e-20 m)
    for (int it = 0; it < 100; ++it) {
      const Eigen::VectorXd r = reduced(c);
      if (r.norm() < 1e-11 * load.norm()) return c;
      Eigen::MatrixXd jac(n, n);
      for (Eigen::Index j = 0; j < n; ++j) {
        Vec3 cp = c, cm = c;
        cp[free[static_cast<std::size_t>(j)]] += h, cm[free[static_cast<std::size_t>(j)]] -= h;
        jac.col(j) = (reduced(cp) - reduced(cm)) / (2 * h);
      }
      const Eigen::VectorXd step = jac.fullPivLu().solve(-r);
      double lambda = 1;
      for (; lambda > 1e-6; lambda *= 0.5) {
        Vec3 trial = c;
        for (Eigen::Index j = 0; j < n; ++j) trial[free[static_cast<std::size_t>(j)]] += lambda * step[j];
        if (reduced(trial).norm() < r.norm()) {
          c = trial;
          break;
        }
      }
      if (lambda <= 1e-6) break;
    }
    ADD_FAILURE() << "quasi-static equilibrium did not converge";
    return c;
  }
};

}  // namespace raceway::test
