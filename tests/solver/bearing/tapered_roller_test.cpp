// A single-row tapered roller bearing (solver/bearing/tapered_roller_model.cpp, tapered_startup.cpp)
// under a combined radial and axial load (4 kN, 1.6 kN: a load zone of part of the rollers), at rest, against a quasi-static solution derived here:
// each roller in its meridian plane (r, z) between the cone, the cup and the cone's back rib, with
// the geometry's angles from the apex construction written in this file (the cup angle and the
// mean roller radius fix the roller's half angle: tan(gamma) = r_r sin(alpha_o - gamma) / r_m,
// solved by bisection), each raceway contact the registry's Palmgren slices of the profile at
// the roller's own radius there, the rib a Hertz point; unknowns: each roller's place and lean and
// the inner ring's displacement, solved together by a damped Newton method. The model's seated
// cone, cup and rib loads per roller and the inner ring's axial displacement agree within 2 %; the
// seated state is an equilibrium of the dynamic model's equations; the rollers' axial components
// balance the axial load. Also: the planar model refuses a tapered bearing with a clear reason.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <tuple>
#include <numbers>
#include <string>
#include <vector>

#include "contact/laws/point_contact.hpp"
#include "contact/laws/sliced_line_contact.hpp"
#include "io/scene/scene_parser.hpp"
#include "scheduler/executor.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/startup.hpp"
#include "solver/run/output_writer.hpp"

namespace raceway::bearing {
namespace {

constexpr double pi = std::numbers::pi;
constexpr double deg = pi / 180;

std::string scene_text(const std::string& model = "spatial") {
  return R"(
[scene]
name = "tapered at rest"
model = ")" + model + R"("
end_time = "0.01 s"
output_interval = "1 ms"
[bearing]
type = "tapered_roller"
rolling_elements = 17
roller_diameter = "7.5 mm"
roller_length = "12 mm"
pitch_diameter = "46 mm"
cup_angle = "14 deg"
inner_bore_diameter = "30 mm"
outer_outside_diameter = "62 mm"
corner_radius = "0.6 mm"
roller_end = "spherical"
rib_angle = "1 deg"
[cage]
guidance = "rolling_element"
pocket_clearance = "0.3 mm"
[inner_ring]
motion = "driven"
speed = "0 rpm"
translation = "free"
axial = "free"
load = { fy = "-4 kN", fz = "-1.6 kN" }
[outer_ring]
motion = "fixed"
)";
}

/// The reference: Z rollers in their meridian planes, the inner ring displaced by (ex, ey, ez).
struct Reference {
  int z = 17;
  double rm = 23e-3, rr = 3.75e-3, alpha_o = 14 * deg, length = 12e-3 + 1.2e-3, rib = 1 * deg;
  double fy = -4000, fz = -1600;
  double gamma = 0, beta = 0, alpha_i = 0, apex = 0;  // apex: distance from the apex to a roller's middle
  double end_radius = 0, rib_k = 0, e_star = 0;
  contact::SlicedLineContact slices;

  explicit Reference(const scene::Scene& scene) {
    double lo = 0, hi = alpha_o;  // tan(g) - rr sin(alpha_o - g) / rm rises with g
    for (int i = 0; i < 200; ++i) {
      const double g = 0.5 * (lo + hi);
      (std::tan(g) - rr * std::sin(alpha_o - g) / rm > 0 ? hi : lo) = g;
    }
    gamma = 0.5 * (lo + hi);
    beta = alpha_o - gamma;
    alpha_i = beta - gamma;
    apex = rm / std::sin(beta);
    end_radius = 0.9 * apex;  // the scene's default for a spherical end
    const auto& steel = scene.material("steel");
    e_star = contact::reduced_modulus(steel.youngs_modulus, steel.poisson_ratio, steel.youngs_modulus,
                                      steel.poisson_ratio);
    contact::RollerProfile p;
    p.length = length;
    p.corner_radius = 0.6e-3;
    slices = contact::make_sliced_line_contact(e_star, p, 20, 0.0, 1.0);
    // Rib: the sphere against the rib's cone, whose face leans by rib - beta from a radial plane.
    const double g = rib - beta;
    const double centre_r = rm + (0.5 * length - end_radius) * std::sin(beta);
    rib_k = contact::hertz_point_contact(1 / end_radius + std::sin(g) / (centre_r - end_radius * std::sin(g)),
                                         1 / end_radius, e_star)
                .stiffness;
  }

  /// One roller's forces (r, z, moment about its tangent) and its contact loads, for its middle at
  /// (r, z), its lean beta + d, and the ring's displacement (er, ez) in its meridian plane.
  struct Roller {
    Eigen::Vector3d wrench = Eigen::Vector3d::Zero();
    Eigen::Vector2d on_cone = Eigen::Vector2d::Zero();  ///< (r, z) on the inner ring: the cone's and the rib's
    double cone = 0, cup = 0, rib = 0;
  };
  Roller roller(double r, double zc, double d, double er, double ez) const {
    Roller out;
    const Eigen::Vector2d c(r, zc), a(std::sin(beta + d), std::cos(beta + d));
    auto add = [&](const Eigen::Vector2d& point, const Eigen::Vector2d& force) {
      out.wrench.head<2>() += force;
      const Eigen::Vector2d arm = point - c;
      out.wrench[2] += arm.y() * force.x() - arm.x() * force.y();
    };
    // Raceways through the apex at z_a = -rm / tan(beta): cone shifted with the ring.
    const double za = -rm / std::tan(beta);
    for (std::size_t j = 0; j < slices.slice_centre.size(); ++j) {
      const double x = slices.slice_centre[j];
      const Eigen::Vector2d s = c + x * a;
      const double reach = (apex + x) * std::sin(gamma) - slices.law.slice_drop[j];
      for (const bool cup : {false, true}) {
        const double angle = cup ? alpha_o : alpha_i;
        const Eigen::Vector2d n(std::cos(angle), -std::sin(angle));  // the raceway's outward normal
        const Eigen::Vector2d origin = cup ? Eigen::Vector2d(0, za) : Eigen::Vector2d(er, za + ez);
        const double dist = n.dot(s - origin);
        const double approach = cup ? reach + dist : reach - dist;
        if (approach <= 0) continue;
        const double q = slices.law.slice_stiffness[j] * std::pow(approach, 10.0 / 9.0);
        add(s - dist * n, (cup ? -q : q) * n);
        (cup ? out.cup : out.cone) += q;
        if (!cup) out.on_cone -= q * n;
      }
    }
    // Rib: face normal (rib to roller) n_f = (sin g, -cos g); touching at the nominal place.
    const double g = rib - beta;
    const Eigen::Vector2d nf(std::sin(g), -std::cos(g));
    const Eigen::Vector2d a0(std::sin(beta), std::cos(beta));
    const Eigen::Vector2d centre0 = Eigen::Vector2d(rm, 0) + (0.5 * length - end_radius) * a0;
    const Eigen::Vector2d centre = c + (0.5 * length - end_radius) * a;
    // The face moves with the ring; at the nominal place the sphere touches it: approach 0.
    const double delta = -nf.dot(centre - Eigen::Vector2d(er, ez) - centre0);
    if (delta > 0) {
      out.rib = rib_k * delta * std::sqrt(delta);
      add(centre - end_radius * nf, out.rib * nf);
      out.on_cone -= out.rib * nf;
    }
    return out;
  }

  double azimuth(int k) const { return 2 * pi * k / z; }

  /// Unknowns (scaled: um, 10 urad): ex, ey, ez, then per roller dr, dz, d.
  Eigen::VectorXd residual(const Eigen::VectorXd& u, double spring) const {
    Eigen::VectorXd res(u.size());
    Eigen::Vector3d ring(0, fy, fz);
    for (int k = 0; k < z; ++k) {
      const double psi = azimuth(k);
      const double er = 1e-6 * (u[0] * std::cos(psi) + u[1] * std::sin(psi));
      const auto i = 3 + 3 * k;
      const Roller f = roller(rm + 1e-6 * u[i], 1e-6 * u[i + 1], 1e-5 * u[i + 2], er, 1e-6 * u[2]);
      ring += Eigen::Vector3d(f.on_cone.x() * std::cos(psi), f.on_cone.x() * std::sin(psi), f.on_cone.y());
      res[i] = f.wrench.x() - spring * u[i];
      res[i + 1] = f.wrench.y() - spring * u[i + 1];
      res[i + 2] = f.wrench.z() / rr - spring * u[i + 2];
    }
    for (int c = 0; c < 3; ++c) res[c] = ring[c] - spring * u[c];
    return res / 1000.0;
  }
};

Eigen::VectorXd solve(const Reference& ref) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 + 3 * ref.z);
  // The last spring, 1e-3 N per um, holds the unloaded rollers (as the model's seating does).
  for (const double spring : {1e3, 1e2, 1e1, 1.0, 0.1, 1e-2, 1e-3}) {
    double lambda = 1e-3;
    Eigen::VectorXd r = ref.residual(u, spring);
    for (int it = 0; it < 100 && r.lpNorm<Eigen::Infinity>() > 1e-10; ++it) {
      Eigen::MatrixXd jac(u.size(), u.size());
      for (Eigen::Index j = 0; j < u.size(); ++j) {
        Eigen::VectorXd up = u;
        up[j] += 1e-5;
        jac.col(j) = (ref.residual(up, spring) - r) / 1e-5;
      }
      bool better = false;
      for (int attempt = 0; attempt < 30 && !better; ++attempt) {
        Eigen::MatrixXd a = jac.transpose() * jac;
        const double floor = 1e-6 * a.diagonal().maxCoeff();
        for (Eigen::Index i = 0; i < u.size(); ++i) a(i, i) += lambda * std::max(a(i, i), floor);
        Eigen::VectorXd step = a.ldlt().solve(-jac.transpose() * r);
        if (step.lpNorm<Eigen::Infinity>() > 5) step *= 5 / step.lpNorm<Eigen::Infinity>();
        const Eigen::VectorXd rt = ref.residual(u + step, spring);
        if (rt.squaredNorm() < r.squaredNorm()) {
          u += step, r = rt, lambda = std::max(lambda / 5, 1e-12), better = true;
        } else {
          lambda *= 8;
        }
      }
      if (!better) break;
    }
  }
  return u;
}

struct ModelLoads {
  std::vector<double> cone, cup, rib;
  double inner_z = 0;
  double cone_angle_seen = 0, cup_angle_seen = 0;  ///< the loaded slices' contact_angle diagnostic (the last)
};

ModelLoads model_loads(const Model& m, const std::vector<double>& z) {
  ModelLoads out;
  out.cone.assign(static_cast<std::size_t>(m.element_count), 0.0);
  out.cup = out.cone, out.rib = out.cone;
  for (const auto& seg : m.segments) {
    auto ring = m.kinematics(seg.body_a, 0.0, z.data()), roller = m.kinematics(seg.body_b, 0.0, z.data());
    const auto k = static_cast<std::size_t>(seg.element);
    if (seg.kind == SegmentKind::roller_flange)
      out.rib[k] += contact::evaluate(m.law<contact::RollerFlangeSegment>(seg), ring, roller).diagnostics.normal_force;
    else if (seg.kind == SegmentKind::roller_inner_slice || seg.kind == SegmentKind::roller_outer_slice) {
      const bool cone = seg.kind == SegmentKind::roller_inner_slice;
      const auto d = contact::evaluate(m.law<contact::RollerSliceSegment>(seg), ring, roller).diagnostics;
      (cone ? out.cone : out.cup)[k] += d.normal_force;
      if (d.normal_force > 0) (cone ? out.cone_angle_seen : out.cup_angle_seen) = d.contact_angle;
    }
  }
  out.inner_z = z[static_cast<std::size_t>(m.bodies[static_cast<std::size_t>(m.inner_ring)].slot[sz])];
  return out;
}

TEST(TaperedRoller, CombinedLoadAgainstQuasiStaticRollers) {
  const scene::Scene scene = scene::parse_scene(scene_text(), "tapered.toml");
  const Model m = build_model(scene);
  const Reference ref(scene);
  EXPECT_NEAR(m.cone_angle, ref.alpha_i, 1e-12);
  EXPECT_NEAR(m.cup_angle, ref.alpha_o, 1e-15);
  const StartupReport start = initial_state(m, 0.0);
  const ModelLoads got = model_loads(m, start.state);
  const Eigen::VectorXd u = solve(ref);
  ASSERT_LT(ref.residual(u, 1e-3).lpNorm<Eigen::Infinity>(), 1e-6) << "the reference did not converge";
  double q_max = 0, axial = 0, deviation[3] = {0, 0, 0};
  int loaded = 0;
  for (int k = 0; k < ref.z; ++k) {
    const auto i = 3 + 3 * k;
    const double psi = ref.azimuth(k);
    const double er = 1e-6 * (u[0] * std::cos(psi) + u[1] * std::sin(psi));
    const auto f = ref.roller(ref.rm + 1e-6 * u[i], 1e-6 * u[i + 1], 1e-5 * u[i + 2], er, 1e-6 * u[2]);
    q_max = std::max(q_max, f.cone);
    const auto kk = static_cast<std::size_t>(k);
    for (const auto& [want, have, what] : {std::tuple{f.cone, got.cone[kk], "cone"}, std::tuple{f.cup, got.cup[kk], "cup"},
                                          std::tuple{f.rib, got.rib[kk], "rib"}})
      EXPECT_NEAR(have, want, 0.02 * want + 1.0) << what << " load of roller " << k;
    const double wants[3] = {f.cone, f.cup, f.rib}, haves[3] = {got.cone[kk], got.cup[kk], got.rib[kk]};
    if (f.cone > 50) ++loaded;
    for (int c = 0; c < 3; ++c)
      if (wants[c] > 50) deviation[c] = std::max(deviation[c], std::abs(haves[c] / wants[c] - 1));
    axial += got.cup[kk] * std::sin(ref.alpha_o);
  }
  // The slices' contact_angle is the raceway's own (the report's loads and lives read it).
  EXPECT_NEAR(got.cone_angle_seen, ref.alpha_i, 1e-12);
  EXPECT_NEAR(got.cup_angle_seen, ref.alpha_o, 1e-12);
  EXPECT_GT(q_max, 500.0);  // a loaded bearing
  EXPECT_GT(loaded, 5);
  EXPECT_LT(loaded, ref.z);  // a load zone: combined load, some rollers unloaded
  std::printf("tapered: %d of %d rollers loaded, largest cone load %.1f N; worst relative deviation cone %.2e, cup "
              "%.2e, rib %.2e; inner ring axial %.4f um (reference %.4f um)\n",
              loaded, ref.z, q_max, deviation[0], deviation[1], deviation[2], 1e6 * got.inner_z, u[2]);
  const double ez = 1e-6 * u[2];
  EXPECT_NEAR(got.inner_z, ez, 0.02 * std::abs(ez)) << "inner ring axial displacement";
  // The cup's axial components carry the axial load (the cup's slices at rest carry nothing else).
  EXPECT_NEAR(axial, -ref.fz, 0.01 * std::abs(ref.fz));
  // The seating is an equilibrium of the dynamic model: the rollers' and the inner ring's
  // accelerations times their masses are small beside the loads.
  scheduler::SerialExecutor executor;
  Equations eq(m, executor);
  std::vector<double> zdot(static_cast<std::size_t>(m.state_size));
  eq.rhs(0.0, start.state.data(), zdot.data());
  double worst = 0;
  for (int b = 0; b < static_cast<int>(m.bodies.size()); ++b) {
    const Body& body = m.bodies[static_cast<std::size_t>(b)];
    if (body.kind == BodyKind::cage) continue;
    for (int c = svx; c <= svz; ++c)
      if (body.slot[c] >= 0) worst = std::max(worst, body.mass * std::abs(zdot[static_cast<std::size_t>(body.slot[c])]));
  }
  EXPECT_LT(worst, 1e-3 * q_max);
}

// Rolling without slip on both raceway cones about their common apex: the cone's and the cup's
// contact lines at a roller section lie at one distance from the apex, so their radii are in the
// ratio sin(alpha_i) : sin(alpha_o), and the cage turns at w_i sin(alpha_i) / (sin(alpha_i) +
// sin(alpha_o)) (the inner ring driven, the cup fixed). The output's rolling speed is the same.
TEST(TaperedRoller, EpicyclicCageSpeedRollsOnBothCones) {
  std::string text = scene_text();
  text.replace(text.find("speed = \"0 rpm\""), 15, "speed = \"3000 rpm\"");
  const scene::Scene scene = scene::parse_scene(text, "tapered.toml");
  const Model m = build_model(scene);
  const Reference ref(scene);
  const double wi = 3000 * 2 * pi / 60;
  const double want = wi * std::sin(ref.alpha_i) / (std::sin(ref.alpha_i) + std::sin(ref.alpha_o));
  EXPECT_NEAR(m.epicyclic_cage_speed(0.0), want, 1e-12 * want);
  EXPECT_NEAR(want / wi, 0.4203, 5e-4);  // 14 deg cup, 10.10 deg cone
  scheduler::SerialExecutor executor;
  Equations eq(m, executor);
  EXPECT_EQ(run::OutputWriter::rolling_cage_speed(m, eq, 0.0), m.epicyclic_cage_speed(0.0));
}

TEST(TaperedRoller, PlanarModelRefusesIt) {
  try {
    (void)scene::parse_scene(scene_text("planar"), "tapered.toml");
    FAIL() << "a tapered bearing in the planar model was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("needs model = \"spatial\""), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace raceway::bearing
