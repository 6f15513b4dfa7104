// Geometric imperfections of a race: a localized defect (a spall) and waviness, as pure functions
// of where the contact sits on the race. They change the contact's geometry only: the race's
// surface is displaced along the contact normal by a height h (positive: the surface stands
// towards the rolling element, the approach grows by h; a spall's depth lowers it), and the
// contact's normal law, film and traction see the changed approach. This is how the published
// defect models put a defect into a rolling-bearing model (a change of the contact deflection:
// Sawalhi and Randall 2008, Patil et al. 2010; waviness: Wardle 1988; docs/references.md).
//
// Coordinates: `azimuth` is the contact's angle about the ring's axis in the ring's own frame
// (a defect on a turning ring turns with it); `transverse` the contact point's distance from the
// groove bottom across the race (along the groove's cross-section), which a spall's width bounds.
//
// The spall (length L along the race, width W across, depth H; its centre at `angle`): a rolling
// element of radius r cannot reach the bottom of a short defect. Its centre's path into the defect
// is what the published models use:
//  - sharp edges: the ball pivots on the leading edge, its centre drops by r - sqrt(r^2 - x^2) at
//    x past the edge, and rises over the trailing edge alike; the drop is at most H. The path is C1
//    where the ball enters (the drop starts with zero slope) and has a kink only at the bottom;
//  - smooth edges: a raised cosine over the length, h_max (1 - cos(2 pi x / L)) / 2 (C1 throughout),
//    whose peak h_max = min(H, r - sqrt(r^2 - (L/2)^2)) is the sharp path's.
// Across the race the defect acts where the contact point lies within W/2 of the groove bottom.
//
// Waviness: sum over orders n_k of A_k cos(n_k azimuth + phase_k) (the race's radius deviation
// towards the rolling elements).
#pragma once

#include <vector>

namespace raceway::contact {

enum class SpallEdge { sharp, smooth };

struct RaceSpall {
  double angle = 0;      ///< rad, the spall's centre, ring frame, about the ring axis
  double length = 0;     ///< m, along the race (arc length at the contact)
  double width = 0;      ///< m, across the race
  double depth = 0;      ///< m
  SpallEdge edge = SpallEdge::sharp;
};

struct RaceWaviness {
  std::vector<int> orders;          ///< lobes round the race
  std::vector<double> amplitudes;   ///< m, one per order
  std::vector<double> phases;       ///< rad, one per order
  bool any() const { return !orders.empty(); }
};

/// A race's imperfections. `race_radius`: the radius where the contacts run (turns the spall's
/// arc length into an angle).
struct RaceImperfections {
  double race_radius = 0;  ///< m
  double ball_radius = 0;  ///< m, limits the path into a short spall
  bool has_spall = false;
  RaceSpall spall;
  RaceWaviness waviness;
  bool any() const { return has_spall || waviness.any(); }
};

/// The surface's height at a contact and its rate of change with the azimuth.
struct RaceHeight {
  double height = 0;        ///< m, + towards the rolling element (adds to the approach)
  double per_azimuth = 0;   ///< m/rad, d(height)/d(azimuth)
};

/// The spall's drop of the rolling element's centre at arc length x from the spall's leading edge
/// (0 outside [0, L]), and its slope d(drop)/dx.
struct SpallDrop {
  double drop = 0, slope = 0;
};
SpallDrop spall_drop(const RaceSpall& s, double ball_radius, double x);
/// The deepest drop of a ball of radius r into the spall: min(H, r - sqrt(r^2 - (L/2)^2)).
double spall_effective_depth(const RaceSpall& s, double ball_radius);
/// The spall's half-span as an angle on a race of radius race_radius.
double spall_half_angle(const RaceImperfections& r);

/// The height of the race's surface at a contact (spall and waviness).
RaceHeight race_height(const RaceImperfections& r, double azimuth, double transverse);

}  // namespace raceway::contact
