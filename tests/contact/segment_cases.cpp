#include "segment_cases.hpp"

#include <stdexcept>

namespace raceway::contact::test {

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
  TractionCurve traction;
  traction.friction_coefficient = o.traction ? friction_coefficient : 0.0;
  traction.slip_velocity_scale = slip_velocity_scale;
  switch (c.kind) {
    case Kind::race: {
      RollerRaceSegment s;
      s.race_radius = c.internal ? outer_race_radius : inner_race_radius;
      s.roller_radius = roller_radius;
      s.internal = c.internal;
      s.law = law;
      s.traction = traction;
      return s;
    }
    case Kind::bar: {
      CageBarSegment s;
      s.pitch_radius = pitch_radius;
      s.pocket_angle = pocket_angle;
      s.half_clearance = 0.5 * pocket_clearance;
      s.roller_radius = roller_radius;
      s.side = c.side;
      s.law = law;
      s.traction = traction;
      return s;
    }
    case Kind::land: {
      CageLandSegment s;
      s.land_radius = c.internal ? outer_land_radius : inner_land_radius;
      s.clearance = land_clearance;
      s.outer_land = c.internal;
      s.law = law;
      s.traction = traction;
      return s;
    }
  }
  throw std::logic_error("make_segment: unknown kind");
}

SegmentResult evaluate_any(const AnySegment& s, const PlanarKinematics& a, const PlanarKinematics& b) {
  return std::visit([&](const auto& seg) { return evaluate(seg, a, b); }, s);
}

bool jacobian_any(const AnySegment& s, const PlanarKinematics& a, const PlanarKinematics& b,
                  const SegmentResult& base, const std::array<double, 12>& step,
                  std::array<std::array<double, 12>, 6>& jac) {
  return std::visit([&](const auto& seg) { return segment_jacobian(seg, a, b, base, step, jac); }, s);
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

Placement place(const SegmentCase& c, const AnySegment& s, PlanarKinematics a,
                PlanarKinematics b_motion, double approach, double direction, double shift) {
  Placement p{a, b_motion};
  const Vec u = unit(direction);
  double distance = 0;  // from A's reference point to B's centre along u
  Vec origin = position(a);
  switch (c.kind) {
    case Kind::race: {
      const auto& race = std::get<RollerRaceSegment>(s);
      // Inner race: roller outside the race, approach = R + r - d. Outer race: approach = d + r - R.
      distance = c.internal ? race.race_radius - race.roller_radius + approach
                            : race.race_radius + race.roller_radius - approach;
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
      return p;
    }
    case Kind::land: {
      const auto& land = std::get<CageLandSegment>(s);
      // The cage sits at eccentricity (clearance + approach) along u from the ring centre.
      distance = -(land.clearance + approach);
      break;
    }
  }
  p.b.x = origin[0] + distance * u[0];
  p.b.y = origin[1] + distance * u[1];
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
  return {rotate_body(p.a, angle), rotate_body(p.b, angle)};
}

Placement translated(const Placement& p, double dx, double dy) {
  Placement q = p;
  q.a.x += dx;
  q.a.y += dy;
  q.b.x += dx;
  q.b.y += dy;
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

}  // namespace raceway::contact::test
