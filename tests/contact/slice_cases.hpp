// Test support for the spatial roller-race slice segment (contact/segments/roller_slice_segment.hpp):
// two configurations of an NJ 207-like bearing's crowned roller (an end slice on the inner race,
// a middle slice on the outer race) and a placement that puts the roller, tilted by 1 mrad, where
// the slice's approach has a chosen value, stated from the ring's radial line through the slice
// centre, independently of the segment.
#pragma once

#include <string>
#include <vector>

#include "ball_cases.hpp"
#include "contact/segments/roller_slice_segment.hpp"
#include "flange_cases.hpp"

namespace raceway::contact::test::slice {

using ball::Placement;
inline constexpr double inner_race_radius = 27.5e-3, outer_race_radius = 37.5e-3;
inline constexpr double max_approach = 1e-4;

struct SliceCase {
  std::string name;
  bool outer;
  std::size_t slice;
};

inline std::vector<SliceCase> all_cases() { return {{"inner_race_end_slice", false, 9}, {"outer_race_middle_slice", true, 4}}; }

inline SlicedLineContact sliced(bool damping) {
  const RollerProfile crown{.kind = RollerProfileKind::circular, .length = 10e-3, .corner_radius = 0.3e-3,
                            .crown_radius = 1.0, .flat_length = 4e-3};
  return make_sliced_line_contact(ball::steel_steel(), crown, 10, damping ? ball::damping_factor : 0.0, max_approach);
}

inline RollerSliceSegment make(const SliceCase& c, bool damping, bool traction) {
  const TractionCurve curve{traction ? ball::friction : 0.0, ball::slip_scale};
  return make_roller_slice_segment(sliced(damping), c.slice, c.outer ? outer_race_radius : inner_race_radius,
                                   flange::roller_radius, c.outer, curve);
}

/// Palmgren's K of the effective length (10 mm less two 0.3 mm corners) shared out by width (1 mm).
inline double expected_stiffness() {
  return palmgren_stiffness(ball::steel_steel(), 9.4e-3) * (1e-3 / 9.4e-3);
}

inline Placement place(const SliceCase& c, double approach, double dir) {
  const SlicedLineContact law = sliced(false);
  const double x = law.slice_centre[c.slice], reach = flange::roller_radius - law.law.slice_drop[c.slice];
  Placement p;
  p.a.position = Vec3(2e-4, -1e-4, 5e-5);
  p.a.rotation = ball::rotation_about(0.004, Vec3(1, 2, 0)) * ball::rotation_about(1.3, Vec3::UnitZ());
  const Mat3 attitude = flange::roller_attitude(dir);
  const double rho = c.outer ? outer_race_radius - reach + approach : inner_race_radius + reach - approach;
  const Vec3 slice_centre = rho * ball::radial(dir) + 0.7e-3 * Vec3::UnitZ();
  const Vec3 centre = slice_centre - x * attitude.col(2);
  const Vec3 n = (c.outer ? -1.0 : 1.0) * ball::radial(dir);
  p.b.position = p.a.position + p.a.rotation * centre;
  p.b.rotation = p.a.rotation * attitude;
  p.normal_on_b = p.a.rotation * n;
  const double race = c.outer ? outer_race_radius : inner_race_radius;
  p.point = p.a.position + p.a.rotation * (race * ball::radial(dir) + 0.7e-3 * Vec3::UnitZ());
  return p;
}

inline Placement placed(const SliceCase& c, double approach, double dir, const ball::Motion& m) {
  Placement p = place(c, approach, dir);
  ball::set_motion(p, m);
  return p;
}

}  // namespace raceway::contact::test::slice
