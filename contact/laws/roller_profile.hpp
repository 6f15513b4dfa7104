// The axial profile of a roller (or of its raceway): how far the surface drops below the straight
// generatrix at a distance x from the roller's middle. A profiled roller's line contact is cut
// into slices (sliced_line_contact.hpp), each seeing the approach minus the drop at its centre.
//
// Four profiles, named in a table like the contact laws (the scene's spelling, one line of meaning):
//  - straight: a cylinder whose ends are rounded by the corner radius r_c, tangent to it at
//    |x| = l/2 - r_c: drop = r_c - sqrt(r_c^2 - (|x| - l/2 + r_c)^2) beyond, r_c at the end face;
//  - circular: a circular crown of radius R_c beyond a straight middle of length l_f (0: crowned over
//    the whole length): drop = R_c - sqrt(R_c^2 - (|x| - l_f/2)^2) for |x| > l_f/2;
//  - lundberg: Lundberg's logarithmic profile for a design load Q_d on the effective length
//    l_e = l - 2 r_c, drop = Q_d / (pi l_e E*) ln(1 / (1 - (2x / l_e)^2)) (for two equal steel bodies
//    the familiar 2 Q_d (1 - nu^2) / (pi E l_e)); infinite at |x| = l_e/2, so only slice centres,
//    which lie inside, are ever asked for;
//  - johns_gohar: Johns and Gohar's finite form, drop = Q_d / (pi l_e E*) ln(1 / (1 - (1 - (b/a)^2)
//    (2x / l_e)^2)), a = l_e / 2 and b the Hertz half-width of the design load,
//    b = sqrt(4 Q_d R_x / (pi l_e E*)) with R_x the contact's reduced radius in the rolling direction.
// The corner radius rounds the ends of every profile: its drop adds to the crown's (the corner is
// a few tenths of a millimetre, where crowns drop by micrometres; the sum is the usual slice-model
// approximation of the blend). References: docs/references.md (Lundberg 1939; Johns & Gohar 1981;
// Fujiwara & Kawase 2007 for both logarithmic forms in the notation used here).
//
// Pure functions of their arguments; SI units.
#pragma once

#include <span>
#include <string>
#include <string_view>

namespace raceway::contact {

enum class RollerProfileKind { straight, circular, lundberg, johns_gohar };

struct RollerProfile {
  RollerProfileKind kind = RollerProfileKind::straight;
  double length = 0;          ///< l [m], the roller's length between its end faces
  double corner_radius = 0;   ///< r_c [m], 0 <= r_c < l/2: the rounding of the ends
  double crown_radius = 0;    ///< R_c [m] (circular)
  double flat_length = 0;     ///< l_f [m] (circular), 0 <= l_f < l - 2 r_c
  double design_load = 0;     ///< Q_d [N] (lundberg, johns_gohar)
  double reduced_modulus = 0; ///< E* [Pa] (lundberg, johns_gohar)
  double rolling_radius = 0;  ///< R_x [m], reduced radius in the rolling direction (johns_gohar)
};

/// The length that carries load when the roller is aligned: l - 2 r_c.
double effective_length(const RollerProfile& profile);

/// Johns and Gohar's b: the Hertz half-width of the design load, sqrt(4 Q_d R_x / (pi l_e E*)) [m].
double johns_gohar_half_width(const RollerProfile& profile);

/// The profile drop [m] at x [m] from the roller's middle, |x| < l/2 (>= 0, even in x). Throws
/// std::invalid_argument for a profile that validate_profile rejects or |x| >= l/2.
double profile_drop(const RollerProfile& profile, double x);

/// Empty if the profile is well formed, else the reason ("corner_radius must be below half the
/// length", ...), for the scene parser's error messages.
std::string validate_profile(const RollerProfile& profile);

/// The profiles by name, in a fixed order, as the law registry lists laws.
struct ProfileEntry {
  RollerProfileKind kind;
  std::string_view name;     ///< the scene's spelling
  std::string_view meaning;  ///< one line, for errors and docs
};
std::span<const ProfileEntry> registered_profiles();
/// The profile called `name`, or nullptr.
const ProfileEntry* find_profile(std::string_view name);
/// "straight, circular, lundberg, johns_gohar", for error messages.
std::string known_profile_names();

}  // namespace raceway::contact
