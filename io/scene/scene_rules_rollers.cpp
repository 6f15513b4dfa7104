// The rules of the spatial cylindrical roller bearing's keys (scene_rules.hpp): its profile, roller
// ends and ribs, the slices of its contacts, and which axial loads its ribs carry.
#include <algorithm>
#include <numbers>

#include <fmt/format.h>

#include "contact/laws/tapered_geometry.hpp"
#include "contact/segments/roller_flange_segment.hpp"
#include "io/scene/scene_rules.hpp"
#include "io/scene/scene_schema_rows.hpp"

namespace raceway::scene::schema::rules {

// ---- defaults ------------------------------------------------------------------------------------

// A spatial roller's race contact in 20 slices (a circular crown's load profile to about 1 % of
// the peak, tilt and edge loading resolved) and its pocket bars in 4 (skew against the bar's ends);
// planar: one (the planar model has no tilt).
std::optional<double> slices_default(const Bind& b) {
  if (!b.spatial_roller()) return 1;
  if (b.contact_kind == contact::roller_race_contact) return 20;
  return b.contact_kind == contact::roller_cage_contact ? 4 : 1;
}
// A flat end touches the rib with the rounding of its edge (the profile's corner, or a tenth of the
// roller where the profile has none); a spherical end is a sphere of about the pitch radius.
std::optional<double> end_radius_default(const Bind& b) {
  const BearingGeometry& g = b.scene.bearing;
  // A tapered roller's spherical large end: 0.9 of the apex distance of its centre (the usual 0.8 to
  // 0.95), so that it touches the cone's back rib near its middle.
  if (g.is_tapered() && g.roller.end == RollerEnd::spherical) {
    const std::string why = contact::tapered_geometry_problem(0.5 * g.pitch_diameter, 0.5 * g.roller_diameter, g.roller.cup_angle);
    if (why.empty())
      return 0.9 * contact::tapered_geometry(0.5 * g.pitch_diameter, 0.5 * g.roller_diameter, g.roller.cup_angle)
                       .apex_distance;
  }
  if (g.roller.end == RollerEnd::spherical) return 0.5 * g.pitch_diameter;
  return g.roller.corner_radius > 0 ? g.roller.corner_radius : 0.1 * g.roller_diameter;
}

// ---- conditions ----------------------------------------------------------------------------------

std::optional<std::string> circular_profile_only(const Section&, const Bind& b) {
  if (b.scene.bearing.roller.profile == contact::RollerProfileKind::circular) return std::nullopt;
  return "only for roller_profile = \"circular\"";
}
std::optional<std::string> logarithmic_profile_only(const Section&, const Bind& b) {
  const auto p = b.scene.bearing.roller.profile;
  if (p == contact::RollerProfileKind::lundberg || p == contact::RollerProfileKind::johns_gohar) return std::nullopt;
  return "only for a logarithmic roller_profile (\"lundberg\" or \"johns_gohar\")";
}
std::optional<std::string> tapered_only(const Section&, const Bind& b) {
  if (b.scene.bearing.is_tapered()) return std::nullopt;
  return std::string(table::kTaperedOnly);
}
std::optional<std::string> planar_crown_only(const Section&, const Bind& b) {
  if (!b.spatial_roller()) return std::nullopt;
  return "the planar model's crowning; a spatial roller's crown is bearing.roller_profile";
}

// ---- checks --------------------------------------------------------------------------------------

// The spatial roller's profile as contact/laws/roller_profile.hpp checks it.
void roller_profile_fits(const Row&, const Section& s, Bind& b) {
  const BearingGeometry& g = b.scene.bearing;
  // Any positive modulus: the checks are on lengths and loads.
  const std::string why = contact::validate_profile(g.roller_profile(1e11, 0.25 * g.roller_diameter));
  s.check(why.empty(), "roller_profile", [&] { return "the roller profile does not fit: " + why; });
  s.check(!g.is_tapered() || !s.has("ribs"), "ribs", [] {
    return std::string("a tapered roller bearing has one rib, the cone's back rib against the rollers' large ends: "
                       "leave ribs out (it is for cylindrical roller bearings)");
  });
}

// The apexes of cup, cone and roller meet on the axis only for a roller that fits the cup angle.
void cup_angle_fits(const Row&, const Section& s, Bind& b) {
  const BearingGeometry& g = b.scene.bearing;
  const std::string why =
      contact::tapered_geometry_problem(0.5 * g.pitch_diameter, 0.5 * g.roller_diameter, g.roller.cup_angle);
  s.check(why.empty(), "cup_angle", [&] {
    return fmt::format("a cup angle of {:.4g} deg with a {} roller on a {} pitch diameter: {}",
                       g.roller.cup_angle * 180 / std::numbers::pi, mm(g.roller_diameter), mm(g.pitch_diameter), why);
  });
  s.check(g.radial_clearance == 0, "radial_clearance", [&] {
    return fmt::format("a tapered roller bearing's play is axial: give radial_clearance = 0 (not {}) and set the play "
                       "or preload by the inner ring's axial load or axial_position",
                       mm(g.radial_clearance));
  });
}

void end_radius_fits(const Row&, const Section& s, Bind& b) {
  const BearingGeometry& g = b.scene.bearing;
  if (g.roller.end == RollerEnd::flat)
    s.check(g.roller.end_radius < 0.5 * g.roller_diameter, "end_radius", [&] {
      return fmt::format("a flat end's edge rounding of {} must be smaller than the roller radius ({})",
                         mm(g.roller.end_radius), mm(0.5 * g.roller_diameter));
    });
  else
    s.check(g.roller.end_radius > 0.5 * g.roller_diameter, "end_radius", [&] {
      return fmt::format("a spherical end's radius of {} must exceed the roller radius ({}): the end would not be a "
                         "cap of the sphere",
                         mm(g.roller.end_radius), mm(0.5 * g.roller_diameter));
    });
}

namespace {

/// The large end on the cone's back rib at a rib angle (what the tapered model builds), or nullopt
/// where the geometry itself is refused elsewhere (cup_angle_fits).
std::optional<std::string> back_rib_problem(const BearingGeometry& g, double rib_angle) {
  const double rm = 0.5 * g.pitch_diameter, rr = 0.5 * g.roller_diameter;
  if (!contact::tapered_geometry_problem(rm, rr, g.roller.cup_angle).empty()) return std::nullopt;
  const auto end = g.roller.end == RollerEnd::flat ? contact::RollerEndShape::flat : contact::RollerEndShape::spherical;
  const contact::RollerFlangeGeometry rib =
      contact::tapered_back_rib(contact::tapered_geometry(rm, rr, g.roller.cup_angle), rm,
                                g.roller_length + 2 * g.roller.corner_radius, end, g.roller.end_radius, rib_angle);
  return contact::flange_problem(rib);
}

// A tapered roller's large end must touch the cone's back rib at a Hertz point: the rib face, normal
// to the leaning roller's axis, is a cone about the bearing axis that curves away from a flat end's
// rounded edge only beyond a rib angle of about a degree, and from a spherical end only where the
// sphere's radius is below about the apex distance.
void large_end_fits_back_rib(const Section& s, const Bind& b) {
  const BearingGeometry& g = b.scene.bearing;
  const std::optional<std::string> why = back_rib_problem(g, g.roller.rib_angle);
  if (!why || why->empty()) return;
  const contact::TaperedGeometry t =
      contact::tapered_geometry(0.5 * g.pitch_diameter, 0.5 * g.roller_diameter, g.roller.cup_angle);
  std::string hint = fmt::format("give the spherical ends a smaller end_radius (makers use 0.8 to 0.95 of the apex "
                                 "distance, {} here)",
                                 mm(t.apex_distance));
  if (g.roller.end == RollerEnd::flat) {
    for (int tenth = 1; tenth < 100; ++tenth) {  // the smallest rib angle that works, to 0.1 deg
      const std::optional<std::string> w = back_rib_problem(g, tenth * std::numbers::pi / 1800);
      if (w && w->empty()) {
        hint = fmt::format("a flat end needs rib_angle of at least {:.1f} deg here, or give the rollers spherical ends",
                           0.1 * tenth);
        break;
      }
    }
  }
  const char* key = s.has("rib_angle") ? "rib_angle" : s.has("end_radius") ? "end_radius" : "roller_end";
  std::string_view reason = *why;
  if (reason.starts_with("roller flange: ")) reason.remove_prefix(15);
  s.fail(key, fmt::format("the rollers' {} large ends (end_radius {}) find no Hertz point on the cone's back rib at "
                          "a rib_angle of {:.3g} deg ({}): {}",
                          g.roller.end == RollerEnd::flat ? "flat" : "spherical", mm(g.roller.end_radius),
                          g.roller.rib_angle * 180 / std::numbers::pi, reason, hint));
}

}  // namespace

void rib_angle_fits_end(const Row&, const Section& s, Bind& b) {
  const RollerGeometry& r = b.scene.bearing.roller;
  s.check(r.end == RollerEnd::spherical || r.rib_angle > 0, "rib_angle", [] {
    return std::string("a flat roller end on a radial rib (rib_angle = 0) touches along a whole edge, not at a Hertz "
                       "point: give the rib an angle (e.g. \"0.5 deg\") or the rollers spherical ends");
  });
  if (b.scene.bearing.is_tapered()) large_end_fits_back_rib(s, b);
}

void end_clearance_fits(const Row&, const Section& s, Bind& b) {
  const BearingGeometry& g = b.scene.bearing;
  s.check(g.roller.end_clearance < 0.1 * g.roller_length, "roller_end_clearance", [&] {
    return fmt::format("an axial play of {} is more than a tenth of the roller length ({}); roller end play is "
                       "some tens of micrometres",
                       mm(g.roller.end_clearance), mm(g.roller_length));
  });
}

// A spatial roller bearing carries an axial load between its rings only through ribs on both: NU
// and N have ribs on one ring only (their rings float axially against each other: a locating
// bearing elsewhere takes the load); NJ's inner rib (its -z side) takes an inner-ring load along
// +z (an outer-ring load along -z); NUP takes both. The model's races are cylinders without edges:
// a load nothing carries would slide the ring away for ever.
void axial_load_carried_by_ribs(const Row&, const Section& s, Bind& b) {
  if (!b.spatial_roller()) return;
  const TimeFunction& fz = b.ring->load.fz;
  double lo = 0, hi = 0;
  for (const double v : fz.values) lo = std::min(lo, v), hi = std::max(hi, v);
  if (lo == 0 && hi == 0) return;
  const bool inner = b.ring == &b.scene.inner_ring;
  if (b.scene.bearing.is_tapered()) {
    // The cone's back rib and the raceways carry the cone pushed into the cup: an inner-ring load
    // along -z, an outer-ring load along +z.
    if (inner ? hi > 0 : lo < 0)
      s.fail("fz", fmt::format("a tapered roller bearing carries an axial load on its {} ring along {} only (the cone "
                               "pushed into the cup, the rollers' large ends on the cone's back rib at +z)",
                               inner ? "inner" : "outer", inner ? "-z" : "+z"));
    return;
  }
  const RibArrangement ribs = b.scene.bearing.roller.ribs;
  // The direction an NJ bearing carries on this ring: +z on the inner ring, -z on the outer.
  const bool along_carried = inner ? lo >= 0 : hi <= 0;
  const char* design = ribs == RibArrangement::nu ? "NU" : ribs == RibArrangement::n ? "N" : "NJ";
  if (ribs == RibArrangement::nu || ribs == RibArrangement::n)
    s.fail("fz", fmt::format("an {} bearing has ribs on one ring only and carries no axial load between its rings "
                             "(bearing.ribs = \"NJ\" or \"NUP\" do)",
                             design));
  if (ribs == RibArrangement::nj && !along_carried)
    s.fail("fz", fmt::format("an NJ bearing's single inner rib (its -z side) carries an axial load along {} on the "
                             "{} ring only; bearing.ribs = \"NUP\" carries both directions",
                             inner ? "+z" : "-z", inner ? "inner" : "outer"));
}

}  // namespace raceway::scene::schema::rules
