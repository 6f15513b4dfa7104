// The tapered 30206 the solver's roller tests seat: the shipped scene's estimated geometry, the inner
// ring driven at 3000 rpm, free, under 4 kN radial and 3 kN axial (every roller loaded), 12 slices.
#pragma once

#include <string>

namespace raceway::test {

/// The scene text; `bearing_keys` go at the end of its [bearing] table, `tail` at the end.
inline std::string tapered_30206_scene(const std::string& bearing_keys = "", const std::string& tail = "") {
  return R"(
[scene]
name = "tapered 30206"
end_time = "0.01 s"
output_interval = "1 ms"
model = "spatial"
[bearing]
type = "tapered_roller"
rolling_elements = 17
roller_diameter = "7.5 mm"
roller_length = "12 mm"
pitch_diameter = "46 mm"
cup_angle = "14 deg"
inner_bore_diameter = "30 mm"
outer_outside_diameter = "62 mm"
ring_width = "16 mm"
corner_radius = "0.6 mm"
roller_end = "spherical"
rib_angle = "1 deg"
)" + bearing_keys +
         R"(
[cage]
guidance = "rolling_element"
pocket_clearance = "0.3 mm"
material = "steel"
[inner_ring]
motion = "driven"
speed = "3000 rpm"
translation = "free"
axial = "free"
load = { fy = "-4 kN", fz = "-3 kN" }
[outer_ring]
motion = "fixed"
[contact.roller_race]
slices = 12
)" + tail;
}

}  // namespace raceway::test
