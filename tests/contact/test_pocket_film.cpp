// The film of a ball in a cylindrical cage pocket (contact/laws/pocket_film.hpp) against a
// two-dimensional finite-volume Reynolds solver with cavitation (reynolds_fd2d.hpp), motion by motion
// (approach, rolling along the pocket's axis, the ball spinning about it: a journal bearing's wedge,
// and all together); and the lubricated pocket segment: action equals reaction, the film's work rate
// is its power loss, and the force passes continuously from film to dry contact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <variant>
#include <vector>

#include "ball_cases.hpp"
#include "contact/laws/pocket_film.hpp"
#include "contact/laws/reynolds_line_film.hpp"
#include "reynolds_fd2d.hpp"

namespace raceway::contact {
namespace {

constexpr double eta = 0.05, ball_radius = 6e-3, clearance = 0.05e-3;

PocketFilm pocket(int points = PocketFilm{}.points) {
  PocketFilm f;
  f.viscosity = eta;
  f.ball_radius = ball_radius;
  f.clearance = clearance;
  f.film_floor = 0;
  f.points = points;
  f.shear = false;
  return f;
}

struct Case {
  const char* name;
  PocketMotion motion;
};

std::vector<Case> motions() {
  const double e = 0.8 * clearance;
  return {
      {"approach", {{e, 0}, {2e-3, 0, 0}, {0, 0, 0}}},
      {"axial rolling", {{e, 0}, {0, 0, 0}, {0, -1000, 0}}},
      {"spin about the axis", {{e, 0}, {0, 0, 0}, {0, 0, 1000}}},
      {"offset off e1, approach and rolling", {{0.6 * e, 0.6 * e}, {1e-3, 1e-3, 0}, {300, -600, 0}}},
      {"all together", {{0.5 * e, -0.7 * e}, {5e-4, -1e-3, 0.05}, {400, 700, -600}}},
  };
}

test::PocketFdResult fd(const PocketMotion& m, int n_alpha = 256, int n_z = 121) {
  test::PocketFdProblem q;
  q.eta = eta;
  q.ball_radius = ball_radius;
  q.clearance = clearance;
  q.offset = m.offset;
  q.velocity = m.velocity;
  q.angular_velocity = m.angular_velocity;
  q.n_alpha = n_alpha;
  q.n_z = n_z;
  return test::solve_pocket_fd(q);
}

TEST(PocketFilm, AgainstTwoDimensionalReynolds) {
  for (const Case& c : motions()) {
    const PocketFilmForce law = evaluate_pocket_film(pocket(), c.motion);
    const test::PocketFdResult ref = fd(c.motion);
    const double size = std::hypot(ref.force_on_ball[0], ref.force_on_ball[1]);
    const double error = std::hypot(law.force_on_ball[0] - ref.force_on_ball[0], law.force_on_ball[1] - ref.force_on_ball[1]);
    std::printf("[ pocket ] %-36s law (%9.4g, %9.4g) N, 2-D Reynolds (%9.4g, %9.4g) N (%d sweeps): %.2f %%\n", c.name,
                law.force_on_ball[0], law.force_on_ball[1], ref.force_on_ball[0], ref.force_on_ball[1], ref.sweeps,
                100 * error / size);
    EXPECT_LT(error, 0.02 * size) << c.name;
  }
}

// The strips' grid: 48 strips on a Sommerfeld grid whose eccentricity stops near 0.98 give the film of
// 8192 strips on the film's own grid within 0.3 %, from an eccentricity of 0.5 to the film's floor,
// approaching, separating (the load then on the thick side), rolling, sliding and spinning (near the
// centre the resultant is a small difference of the strips' loads: 6 % of 0.02 N with 32 strips).
TEST(PocketFilm, StripGridConverged) {
  std::vector<PocketMotion> motions_at;
  for (const double eps : {0.5, 0.8, 0.9, 0.95, 0.99, 0.995, 0.999}) {
    const double e = eps * clearance;
    motions_at.push_back({{e, 0}, {2e-3, 0, 0}, {0, 0, 0}});
    motions_at.push_back({{e, 0}, {-2e-3, 0, 0}, {0, -1000, 0}});
    motions_at.push_back({{e, 0}, {0, 0, 0}, {0, -1000, 300}});
    motions_at.push_back({{e * 0.6, -e * 0.8}, {5e-4, -1e-3, 0.05}, {400, 700, -600}});
    motions_at.push_back({{e, 0}, {-1e-3, 1e-3, 0.3}, {400, 700, -600}});
    motions_at.push_back({{e, 0}, {1e-4, 1e-3, 0.3}, {40, 70, -2000}});
  }
  double worst = 0;
  for (const PocketMotion& m : motions_at) {
    PocketFilm fine = pocket(8192);
    fine.grid_eccentricity = 1.0;  // the film's own eccentricity
    const PocketFilmForce a = evaluate_pocket_film(fine, m), b = evaluate_pocket_film(pocket(), m);
    const double error = std::hypot(a.force_on_ball[0] - b.force_on_ball[0], a.force_on_ball[1] - b.force_on_ball[1]);
    worst = std::max(worst, error / std::hypot(a.force_on_ball[0], a.force_on_ball[1]));
  }
  std::printf("[ pocket ] %d strips against 8192: %.3f %% at worst\n", PocketFilm{}.points, 100 * worst);
  EXPECT_LT(worst, 0.003);
}

// The Couette shear of a ball spinning about the pocket's axis, centred: a concentric journal,
// Petroff's torque per strip, eta (r_b omega) / h0 over int dz / h0 (1 + X^2) = pi sqrt(2 r_b / h0):
// M = 2 pi r_p r_b^2 eta omega pi sqrt(2 r_b / c).
TEST(PocketFilm, CentredSpinShear) {
  PocketFilm f = pocket();
  f.shear = true;
  const double spin = 800;
  const PocketFilmForce r = evaluate_pocket_film(f, {{0, 0}, {0, 0, 0}, {0, 0, spin}});
  const double rp = ball_radius + clearance, pi = std::numbers::pi;
  const double petroff = 2 * pi * rp * ball_radius * ball_radius * eta * spin * pi * std::sqrt(2 * ball_radius / clearance);
  std::printf("[ pocket ] centred spin %.0f rad/s: shear moment %.5g N m (closed form %.5g), loss %.4g W\n", spin,
              -r.moment_on_ball[2], petroff, r.power_loss);
  EXPECT_NEAR(-r.moment_on_ball[2], petroff, 1e-9 * petroff);
  EXPECT_NEAR(r.power_loss, petroff * spin, 1e-9 * petroff * spin);
  EXPECT_NEAR(std::hypot(r.force_on_ball[0], r.force_on_ball[1]), 0.0, 1e-12);
}

// The film strip by strip as the header writes it: each strip's angle by trigonometry, the pocket's
// own frame, the line film through reynolds_line_load_per_length's formula with the ratio table's
// function. The law sums the same strips in blocks, in the frame of e, with its algebra rearranged.
PocketFilmForce strip_by_strip(const PocketFilm& f, const PocketMotion& m) {
  const double pi = std::numbers::pi, size = std::hypot(m.offset[0], m.offset[1]), c = f.clearance;
  const double h_min = c - size, floor = f.film_floor;
  const double h_floor = floor > 0 ? 0.5 * (h_min + floor + std::hypot(h_min - floor, floor)) : std::max(h_min, 0.0);
  const double eps = std::max(0.0, 1.0 - h_floor / c), beta = size > 0 ? std::atan2(m.offset[1], m.offset[0]) : 0.0;
  const double q8 = std::pow(eps / f.grid_eccentricity, 8.0);
  const double ge = f.grid_eccentricity < 1.0 ? eps / std::pow(1.0 + q8, 0.125) : eps;
  const double rb = f.ball_radius, rp = rb + c, dpsi = 2 * pi / f.points;
  const auto& v = m.velocity;
  const auto& w = m.angular_velocity;
  PocketFilmForce out;
  double px = 0, py = 0, loss = 0;
  for (int k = 0; k < f.points; ++k) {
    const double psi = (k + 0.5) * dpsi;
    const double gamma = 2 * std::atan2(std::sqrt((1 - ge) / (1 + ge)) * std::sin(psi / 2), std::cos(psi / 2));
    const double d_alpha = std::sqrt(1 - ge * ge) / (1 + ge * std::cos(psi)) * dpsi;
    const double n0 = std::cos(beta + gamma), n1 = std::sin(beta + gamma);
    const double h0 = c * (1 - eps * std::cos(gamma)), dh0_ds = c * eps * std::sin(gamma) / rp;
    const double v_t = -v[0] * n1 + v[1] * n0 + rb * w[2], rolling_a = rb * (w[0] * n1 - w[1] * n0);
    const double v_a = v[2] + rolling_a, u = 0.5 * (rolling_a - v[2]);
    const double sigma = (-(v[0] * n0 + v[1] * n1) + 0.5 * v_t * dh0_ds) * std::sqrt(2 * rb / h0);
    const double mag = std::hypot(u, sigma);
    const double g = mag > 0 ? reynolds_line_load_integral_of_ratio(sigma / (std::abs(u) + std::abs(sigma))) : 0.0;
    const double load = 24 * f.viscosity * rb / h0 * mag * g * rp * d_alpha;
    px -= load * n0;
    py -= load * n1;
    if (!f.shear) continue;
    const double drag = f.viscosity * pi * std::sqrt(2 * rb / h0) * rp * d_alpha;
    const double fx = drag * v_t * n1, fy = -drag * v_t * n0, fa = -drag * v_a;
    for (int i = 0; i < 3; ++i) out.force_on_ball[static_cast<std::size_t>(i)] += i == 0 ? fx : i == 1 ? fy : fa;
    out.moment_on_ball[0] += rb * n1 * fa;
    out.moment_on_ball[1] -= rb * n0 * fa;
    out.moment_on_ball[2] += rb * (n0 * fy - n1 * fx);
    loss += drag * (v_t * v_t + v_a * v_a);
  }
  out.force_on_ball[0] += px;
  out.force_on_ball[1] += py;
  out.power_loss = loss - (px * v[0] + py * v[1]);
  return out;
}

// Any number of strips (whole blocks and a part-empty last one), shear on, thin and thick films,
// every motion: the law's sums are the strip-by-strip ones to round-off.
TEST(PocketFilm, BlocksAgreeWithStripByStrip) {
  double worst = 0;
  for (const int points : {1, 5, 16, 31, 48, 50, 200}) {
    PocketFilm f = pocket(points);
    f.shear = true;
    f.film_floor = 0.2e-6;
    for (const double eps : {0.0, 0.3, 0.9, 0.999, 1.01}) {
      const double e = eps * clearance;
      for (const PocketMotion& m : {PocketMotion{{e, 0}, {2e-3, 0, 0}, {0, 0, 0}},
                                    PocketMotion{{-0.6 * e, 0.8 * e}, {5e-4, -1e-3, 0.05}, {400, 700, -600}},
                                    PocketMotion{{0.8 * e, -0.6 * e}, {-1e-3, 1e-3, 0.3}, {40, 70, -2000}}}) {
        const PocketFilmForce a = evaluate_pocket_film(f, m), b = strip_by_strip(f, m);
        // Relative to the force, with a floor far below these films' (1 uN against 17 mN and more)
        // for the motions whose film force is round-off (one strip on the thick side of a separating
        // film); the moment to it times r_b (a pure approach has no shear moment); the loss to itself.
        const double force = std::hypot(b.force_on_ball[0], b.force_on_ball[1], b.force_on_ball[2]) + 1e-6;
        const double moment = std::hypot(b.moment_on_ball[0], b.moment_on_ball[1], b.moment_on_ball[2]) + ball_radius * force;
        for (std::size_t i = 0; i < 3; ++i) {
          worst = std::max(worst, std::abs(a.force_on_ball[i] - b.force_on_ball[i]) / force);
          worst = std::max(worst, std::abs(a.moment_on_ball[i] - b.moment_on_ball[i]) / moment);
        }
        worst = std::max(worst, std::abs(a.power_loss - b.power_loss) / (b.power_loss + 1e-12));
      }
    }
  }
  std::printf("[ pocket ] blocks against strip by strip: %.2g relative at worst\n", worst);
  EXPECT_LT(worst, 1e-11);
}

// Non-finite motions, and finite ones whose film overflows, give an invalid film, not a crash.
TEST(PocketFilm, OverflowAndNonFiniteAreInvalid) {
  const double e = 0.5 * clearance, inf = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(evaluate_pocket_film(pocket(), {{e, 0}, {inf, 0, 0}, {0, 0, 0}}).valid);
  EXPECT_FALSE(evaluate_pocket_film(pocket(), {{e, 0}, {0, 0, 0}, {0, std::nan(""), 0}}).valid);
  EXPECT_FALSE(evaluate_pocket_film(pocket(), {{e, 0}, {1e300, -1e300, 1e300}, {1e300, 1e300, -1e300}}).valid);
  EXPECT_TRUE(evaluate_pocket_film(pocket(), {{e, 0}, {1e-3, 0, 0}, {0, 100, 0}}).valid);
}

// ---- the lubricated pocket segment ----------------------------------------------------------------

namespace ball = test::ball;

BallPocketSegment lubricated_pocket(double floor = 0.2e-6) {
  const ball::SpatialCase c{"cylindrical_pocket", ball::Kind::pocket, false, 0, PocketShape::cylindrical};
  BallPocketSegment s = std::get<BallPocketSegment>(ball::make_segment(c));
  PocketFilm f;
  f.viscosity = 0.05;
  f.ball_radius = s.ball_radius;
  f.clearance = 0.5 * s.clearance;
  f.film_floor = floor;
  s.film = f;
  return s;
}

ball::Placement placed(double approach, int motion = 1) {
  const ball::SpatialCase c{"cylindrical_pocket", ball::Kind::pocket, false, 0, PocketShape::cylindrical};
  return ball::placed(c, approach, 0.37, ball::motions()[static_cast<std::size_t>(motion)]);
}

double power_on_bodies(const SpatialSegmentResult& r, const ball::Placement& p) {
  return r.on_a.force.dot(p.a.velocity) + r.on_a.moment.dot(p.a.angular_velocity) + r.on_b.force.dot(p.b.velocity) +
         r.on_b.moment.dot(p.b.angular_velocity);
}

// Apart and in contact: action equals reaction about any point, and the work the film and the dry
// contact take from the bodies is the reported power loss (the film stores no energy; with the dry
// contact held at a constant approach, neither does it).
TEST(LubricatedPocket, ActionReactionAndPower) {
  const BallPocketSegment s = lubricated_pocket();
  const ball::SpatialCase c{"cylindrical_pocket", ball::Kind::pocket, false, 0, PocketShape::cylindrical};
  for (const double approach : {-100e-6, -10e-6, -1e-6, 2e-6}) {
    ball::Placement p = placed(approach);
    ball::stop_approach(c, p);
    const SpatialSegmentResult r = evaluate(s, p.a, p.b);
    ASSERT_TRUE(r.valid);
    const double scale = r.on_b.force.norm();
    EXPECT_GT(scale, 0.0) << approach;
    EXPECT_NEAR((r.on_a.force + r.on_b.force).norm(), 0.0, 1e-12 * scale);
    const Vec3 total = r.on_a.moment + p.a.position.cross(r.on_a.force) + r.on_b.moment + p.b.position.cross(r.on_b.force);
    EXPECT_NEAR(total.norm(), 0.0, 1e-12 * scale);
    const double power = -power_on_bodies(r, p);
    std::printf("[ pocket ] approach %6.1f um: force %.4g N, film %.3g um, power loss %.5g W (work rate %.5g W)\n",
                1e6 * approach, scale, 1e6 * r.diagnostics.film_thickness, r.diagnostics.power_loss, power);
    EXPECT_NEAR(r.diagnostics.power_loss, power, 1e-9 * std::abs(power) + 1e-12);
    EXPECT_GT(r.diagnostics.power_loss, 0.0);
  }
}

// The force passes continuously from the film to the dry contact at touch (the dry Hertz force starts
// from zero, the film's is held at its floor), and the film grows smoothly as the gap closes.
TEST(LubricatedPocket, ContinuousAtTheCriticalFilm) {
  const BallPocketSegment s = lubricated_pocket();
  const ball::Placement before = placed(-1e-12), after = placed(1e-12);
  const SpatialSegmentResult a = evaluate(s, before.a, before.b), b = evaluate(s, after.a, after.b);
  std::printf("[ pocket ] at touch: %.6g N before, %.6g N after, film %.3g um\n", a.on_b.force.norm(),
              b.on_b.force.norm(), 1e6 * a.diagnostics.film_thickness);
  EXPECT_GT(a.on_b.force.norm(), 0.0);
  EXPECT_NEAR((a.on_b.force - b.on_b.force).norm(), 0.0, 1e-5 * a.on_b.force.norm());
  EXPECT_NEAR((a.on_b.moment - b.on_b.moment).norm(), 0.0, 1e-5 * a.on_b.moment.norm() + 1e-12);
  // Without the dry law's overlap the segment's force is the film's alone, bounded at its floor.
  EXPECT_NEAR(a.diagnostics.film_thickness, 0.5 * (0.2e-6 + std::hypot(0.2e-6, 0.2e-6)), 1e-12);
  // Dry contact deeper in: the Hertz force adds to the film's.
  BallPocketSegment dry = s;
  dry.film.reset();
  const ball::Placement deep = placed(2e-6);
  const SpatialSegmentResult wet = evaluate(s, deep.a, deep.b), bare = evaluate(dry, deep.a, deep.b);
  EXPECT_GT(wet.diagnostics.normal_force, bare.diagnostics.normal_force);
}

// Without a film the segment is the dry pocket, bit for bit.
TEST(LubricatedPocket, WithoutFilmTheDryPocket) {
  BallPocketSegment s = lubricated_pocket();
  const ball::SpatialCase c{"cylindrical_pocket", ball::Kind::pocket, false, 0, PocketShape::cylindrical};
  const BallPocketSegment dry = std::get<BallPocketSegment>(ball::make_segment(c));
  s.film.reset();
  for (const double approach : {-5e-6, 3e-6}) {
    const ball::Placement p = placed(approach);
    const SpatialSegmentResult a = evaluate(s, p.a, p.b), b = evaluate(dry, p.a, p.b);
    EXPECT_EQ(a.on_b.force, b.on_b.force);
    EXPECT_EQ(a.on_a.moment, b.on_a.moment);
    EXPECT_EQ(a.diagnostics.power_loss, b.diagnostics.power_loss);
  }
}

}  // namespace
}  // namespace raceway::contact
