// The lubricant's rules (scene_rules.hpp): an oil given by its data sheet, the two kinematic
// viscosities at 40 and 100 degC with its density and temperature, gives the viscosity every law takes
// by Walther's equation (ASTM D341, contact/laws/viscosity.hpp); given that way or directly, not both.
#include <fmt/format.h>

#include "contact/laws/viscosity.hpp"
#include "io/scene/scene_rules.hpp"

namespace raceway::scene::schema::rules {

// An oil given by its data sheet (viscosity_40): viscosity_100, density and temperature are required.
std::optional<double> walther_point_default(const Bind& b) {
  if (b.scene.lubricant.viscosity_40 > 0) return std::nullopt;
  return 0.0;
}
// The viscosity at the oil's temperature by Walther's equation (ASTM D341) through the data sheet's two
// points, times the density; without a data sheet the key is required.
std::optional<double> walther_viscosity_default(const Bind& b) {
  const Lubricant& l = b.scene.lubricant;
  if (!(l.viscosity_40 > 0)) return std::nullopt;
  const contact::WaltherConstants w = contact::walther_constants(l.viscosity_40, 313.15, l.viscosity_100, 373.15);
  return l.density * contact::walther_viscosity(w, l.temperature);
}

void walther_points_fit(const Row&, const Section& s, Bind& b) {
  const Lubricant& l = b.scene.lubricant;
  if (!s.has("viscosity_100")) return;
  if (!(l.viscosity_40 > 0))
    s.fail("viscosity_100", "viscosity_100 comes with viscosity_40 (the oil's two data-sheet points); give both");
  if (!(l.viscosity_100 < l.viscosity_40))
    s.fail("viscosity_100", fmt::format("viscosity_100 ({:g} mm^2/s) must be below viscosity_40 ({:g} mm^2/s): an oil "
                                        "thins as it warms",
                                        1e6 * l.viscosity_100, 1e6 * l.viscosity_40));
}

void viscosity_given_once(const Row&, const Section& s, Bind& b) {
  if (s.has("viscosity") && b.scene.lubricant.viscosity_40 > 0)
    s.fail("viscosity", "give the viscosity, or the data sheet's viscosity_40 and viscosity_100 (with density and "
                        "temperature), not both");
}

// The mixture's drag takes the oil's density (its effective density is the fraction times it).
void drag_has_oil_density(const Row&, const Section& s, Bind& b) {
  if (b.scene.lubricant.oil_volume_fraction > 0 && !(b.scene.lubricant.density > 0))
    s.fail("oil_volume_fraction", "the oil-air mixture's drag needs the oil's density: give [lubricant] density");
}

}  // namespace raceway::scene::schema::rules
