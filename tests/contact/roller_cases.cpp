#include "roller_cases.hpp"

#include <stdexcept>

namespace raceway::contact::test::roller {

std::vector<SegmentCase> all_segment_cases() {
  using namespace seed002;
  const double l = roller_length;
  std::vector<SegmentCase> cases;
  // A = ring, B = roller: steel on steel.
  cases.push_back({"RollerInnerRace", Kind::race, false, +1, steel_youngs, steel_poisson, steel_youngs,
                   steel_poisson, l});
  cases.push_back({"RollerOuterRace", Kind::race, true, +1, steel_youngs, steel_poisson, steel_youngs,
                   steel_poisson, l});
  // A = brass cage, B = steel roller.
  cases.push_back({"CageBarFront", Kind::bar, false, +1, brass_youngs, brass_poisson, steel_youngs,
                   steel_poisson, l});
  cases.push_back({"CageBarRear", Kind::bar, false, -1, brass_youngs, brass_poisson, steel_youngs,
                   steel_poisson, l});
  // A = brass cage, B = steel ring.
  cases.push_back({"CageInnerLand", Kind::land, false, +1, brass_youngs, brass_poisson, steel_youngs,
                   steel_poisson, land_length});
  cases.push_back({"CageOuterLand", Kind::land, true, +1, brass_youngs, brass_poisson, steel_youngs,
                   steel_poisson, land_length});
  return cases;
}

AnySegment make_segment(const SegmentCase& c, const LawOptions& o) {
  using namespace seed002;
  const double e_star = reduced_modulus(c.youngs_a, c.poisson_a, c.youngs_b, c.poisson_b);
  const LineContactLaw law = make_line_contact_law(e_star, c.length, o.slices, o.crown_drop,
                                                   o.damping ? damping_factor : 0.0, o.max_approach);
  const TractionCurve traction{o.traction ? friction_coefficient : 0.0, slip_velocity_scale};
  switch (c.kind) {
    case Kind::race:
      return RollerRaceSegment{.race_radius = c.internal ? outer_race_radius : inner_race_radius,
                               .roller_radius = roller_radius, .internal = c.internal, .law = law,
                               .traction = traction, .ehd = std::nullopt};
    case Kind::bar:
      return CageBarSegment{.pitch_radius = pitch_radius, .pocket_angle = pocket_angle,
                            .half_clearance = 0.5 * pocket_clearance, .roller_radius = roller_radius,
                            .side = c.side, .law = law, .traction = traction, .film = std::nullopt};
    case Kind::land:
      return CageLandSegment{.land_radius = c.internal ? outer_land_radius : inner_land_radius,
                             .clearance = land_clearance, .outer_land = c.internal, .law = law,
                             .traction = traction, .film = std::nullopt};
  }
  throw std::logic_error("make_segment: unknown kind");
}

SegmentResult evaluate_any(const AnySegment& s, const PlanarKinematics& a, const PlanarKinematics& b) {
  return std::visit([&](const auto& seg) { return evaluate(seg, a, b); }, s);
}

double expected_stiffness(const SegmentCase& c) {
  const double compliance = (1.0 - c.poisson_a * c.poisson_a) / c.youngs_a +
                            (1.0 - c.poisson_b * c.poisson_b) / c.youngs_b;
  return 0.70866 / compliance * std::pow(c.length, 8.0 / 9.0);
}

PlanarKinematics moving(double vx, double vy, double omega, double theta) {
  PlanarKinematics k;
  k.vx = vx;
  k.vy = vy;
  k.omega = omega;
  k.theta = theta;
  return k;
}

namespace {
Vec3 vec3(Vec v) { return {v[0], v[1], 0.0}; }
}  // namespace

std::vector<Motion> motions() {
  return {
      {moving(0, 0, 0), moving(0, 0, 0)},
      {moving(0.02, -0.01, 3.0), moving(-0.25, 0.4, -40.0)},
      {moving(0.004, -0.003, 0.8), moving(-0.006, 0.005, -2.5)},
      {moving(-0.3, 0.1, 30.0), moving(0.5, 0.2, 60.0)},
  };
}

double wrench_norm(const SegmentResult& r) {
  return std::abs(r.on_a.fx) + std::abs(r.on_a.fy) + std::abs(r.on_a.mz) + std::abs(r.on_b.fx) +
         std::abs(r.on_b.fy) + std::abs(r.on_b.mz);
}

Placement place(const SegmentCase& c, const AnySegment& s, PlanarKinematics a,
                PlanarKinematics b_motion, double approach, double direction, double shift) {
  Placement p{a, b_motion};
  const Vec u = unit(direction);
  Vec line_point{};  // on the line of action of the normal force
  switch (c.kind) {
    case Kind::race: {
      const auto& race = std::get<RollerRaceSegment>(s);
      // Inner race: roller outside the race, approach = R + r - d. Outer race: approach = d + r - R.
      const double distance = c.internal ? race.race_radius - race.roller_radius + approach
                                         : race.race_radius + race.roller_radius - approach;
      p.b.x = a.x + distance * u[0];
      p.b.y = a.y + distance * u[1];
      line_point = {a.x + race.race_radius * u[0], a.y + race.race_radius * u[1]};
      break;
    }
    case Kind::bar: {
      const auto& bar = std::get<CageBarSegment>(s);
      p.a.theta = direction - bar.pocket_angle;
      const Vec t = perp(u);
      // Roller centre: pocket centre + side (half clearance + approach) along the pocket's tangent.
      const double along = bar.side * (bar.half_clearance + approach);
      p.b.x = a.x + (bar.pitch_radius + shift) * u[0] + along * t[0];
      p.b.y = a.y + (bar.pitch_radius + shift) * u[1] + along * t[1];
      line_point = {p.b.x + bar.side * bar.roller_radius * t[0], p.b.y + bar.side * bar.roller_radius * t[1]};
      break;
    }
    case Kind::land: {
      const auto& land = std::get<CageLandSegment>(s);
      // The cage sits at eccentricity (clearance + approach) along u from the ring centre.
      const double distance = -(land.clearance + approach);
      p.b.x = a.x + distance * u[0];
      p.b.y = a.y + distance * u[1];
      line_point = {p.b.x + land.land_radius * u[0], p.b.y + land.land_radius * u[1]};
      break;
    }
  }
  p.normal_on_b = vec3(expected_normal_on_b(c, p));
  p.point = vec3(line_point);
  return p;
}

Vec expected_normal_on_b(const SegmentCase& c, const Placement& p) {
  switch (c.kind) {
    case Kind::race: {
      const Vec rel{p.b.x - p.a.x, p.b.y - p.a.y};
      const double d = norm(rel);
      const Vec n{rel[0] / d, rel[1] / d};
      return c.internal ? Vec{-n[0], -n[1]} : n;
    }
    case Kind::bar: {
      // The bar ahead (+1) pushes the roller back (against the positive rotation), the rear bar forward.
      const Vec t = perp(unit(p.a.theta + seed002::pocket_angle));
      return {-c.side * t[0], -c.side * t[1]};
    }
    case Kind::land: {
      const Vec e{p.a.x - p.b.x, p.a.y - p.b.y};
      const double d = norm(e);
      return {e[0] / d, e[1] / d};
    }
  }
  return {0, 0};
}

double surface_radius_b(const SegmentCase& c) {
  if (c.kind == Kind::land) return c.internal ? seed002::outer_land_radius : seed002::inner_land_radius;
  return seed002::roller_radius;
}

namespace {
void rotate_in_place(double& x, double& y, double c, double s) {
  const double rx = c * x - s * y;
  const double ry = s * x + c * y;
  x = rx;
  y = ry;
}
PlanarKinematics rotate_body(PlanarKinematics k, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  rotate_in_place(k.x, k.y, c, s);
  rotate_in_place(k.vx, k.vy, c, s);
  k.theta += angle;
  return k;
}
}  // namespace

Placement rotated(const Placement& p, double angle) {
  Placement q = p;
  q.a = rotate_body(p.a, angle);
  q.b = rotate_body(p.b, angle);
  const double c = std::cos(angle), s = std::sin(angle);
  rotate_in_place(q.normal_on_b.x(), q.normal_on_b.y(), c, s);
  rotate_in_place(q.point.x(), q.point.y(), c, s);
  return q;
}

Placement translated(const Placement& p, double dx, double dy) {
  Placement q = p;
  q.a.x += dx;
  q.a.y += dy;
  q.b.x += dx;
  q.b.y += dy;
  q.point += Vec3(dx, dy, 0.0);
  return q;
}

Placement advanced(const Placement& p, double dt) {
  Placement q = p;
  for (PlanarKinematics* k : {&q.a, &q.b}) {
    k->x += k->vx * dt;
    k->y += k->vy * dt;
    k->theta += k->omega * dt;
  }
  return q;
}

double power_on_bodies(const SegmentResult& r, const Placement& p) {
  return r.on_a.fx * p.a.vx + r.on_a.fy * p.a.vy + r.on_a.mz * p.a.omega + r.on_b.fx * p.b.vx +
         r.on_b.fy * p.b.vy + r.on_b.mz * p.b.omega;
}

}  // namespace raceway::contact::test::roller
