// Internal to raceway::scene: the rules that estimate a tapered roller bearing's internal geometry
// from its ISO 355 boundary dimensions (docs/catalogue.md, "Tapered roller bearings"). Pure
// functions of numbers in millimetres and degrees; catalogue.cpp turns them into scene values.
#pragma once

#include <optional>

namespace raceway::scene::catalogue {

/// An ISO 355 angle series: the cup angle alpha lies over lo_deg, up to and including hi_deg.
struct AngleRange {
  double lo_deg = 0, hi_deg = 0;
};
/// Angle series 2 to 7 of ISO 355; nullopt for any other number.
std::optional<AngleRange> iso355_angle_series(int series);

/// A size's boundary dimensions (mm, ISO 355), its angle series, and the e its maker publishes
/// where the catalogue has it.
struct TaperedBoundary {
  double bore = 0, outside = 0, total_width = 0, cone_width = 0, cup_width = 0;
  int angle_series = 0;
  std::optional<double> published_e;
};

/// The estimated internal geometry (mm, deg): the scene keys of a tapered roller bearing.
struct TaperedEstimate {
  double pitch_diameter = 0;    ///< d_m, through the rollers' middles
  double roller_diameter = 0;   ///< the roller's mean diameter (at its middle)
  double roller_length = 0;     ///< the straight (effective) length
  double corner_radius = 0;     ///< the rounding of each end, beyond roller_length
  double cup_angle = 0;         ///< deg
  double pocket_clearance = 0;  ///< the pressed steel cage's pocket play
  int rollers = 0;
};

/// The rules' constants (docs/catalogue.md says how each was calibrated).
struct TaperedRules {
  double roller_factor = 0.234;  ///< mean roller diameter = factor (D - d), to 0.1 mm
  double length_factor = 0.69;   ///< roller_length = factor C (the cup width), to 0.1 mm
  double roller_pitch = 1.13;    ///< one roller per this many mean diameters of the pitch circle
  double corner_factor = 0.08;   ///< corner radius = factor D_w, to 0.1 mm
  double pocket_factor = 0.04;   ///< pocket clearance = factor D_w, to 1 um
};

/// The cup angle (deg): atan(e / 1.5) of a published e, else the middle of the angle series, to
/// the nearest 0.5 deg. Throws std::invalid_argument for an angle series ISO 355 does not have.
double estimated_cup_angle(const TaperedBoundary& b);

TaperedEstimate estimate_tapered(const TaperedBoundary& b, const TaperedRules& rules = {});

}  // namespace raceway::scene::catalogue
