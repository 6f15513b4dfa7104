// A profiled roller's line contact cut into slices along the roller, each slice a Palmgren line
// contact (the registry's "palmgren" law, line_contact.hpp) with Hunt-Crossley damping, seeing its
// own approach: the approach at the roller's middle, plus the tilt times the slice's position, minus
// the profile drop at the slice's centre (roller_profile.hpp). Tilt is the angle between the roller's
// generatrix and the raceway's in the plane that contains the contact normal (> 0 presses the +x end
// harder), so a tilted straight roller loads one end: edge loading.
//
// Slice j of width w_j carries K_j = K(l_e) w_j / l_e, Palmgren's stiffness of the effective length
// l_e = l - 2 r_c shared out by width, so that an aligned straight roller carries exactly the unsliced
// law's K(l_e) delta^(10/9). The slices cover the whole length l, the rounded corners included: they
// carry only once the approach (or the tilt) exceeds the corner's drop. Slices are independent (no
// elastic coupling between neighbours: the usual slice model of Harris & Kotzalas, ch. 6); a
// logarithmic crown, which gives a uniform pressure in an elastic half-space, therefore gives slice
// loads that fall towards the ends in this model.
//
// Sums run over the slices in their index order, always: the result is a function of the inputs
// alone. Slice centres are mirror-symmetric bit for bit (x_{N-1-j} = -x_j), so mirroring the tilt
// mirrors the slice loads exactly. Pure functions; SI units.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "contact/laws/line_contact.hpp"
#include "contact/laws/roller_profile.hpp"

namespace raceway::contact {

struct SlicedLineContact {
  LineContactLaw law;                ///< stiffness K(l_e); slice_stiffness K_j; slice_drop at the centres
  std::vector<double> slice_centre;  ///< x_j [m] from the roller's middle, increasing
  double slice_width = 0;            ///< w [m], equal slices over the length
};

/// `slices` equal slices over the profile's length. Throws std::invalid_argument for slices < 1 or
/// a profile that validate_profile rejects.
SlicedLineContact make_sliced_line_contact(double reduced_modulus, const RollerProfile& profile, int slices,
                                           double damping_factor, double max_approach);

/// One slice's force for its own approach [m] and approach rate [m/s].
struct SliceForce {
  double force = 0;            ///< N, >= 0: elastic with Hunt-Crossley damping, clipped at zero
  double elastic_force = 0;    ///< N
  double elastic_energy = 0;   ///< J
  double damping_power = 0;    ///< W
  double d_approach = 0;       ///< d(force)/d(approach) [N/m]
  double d_rate = 0;           ///< d(force)/d(approach rate) [N s/m]
};
SliceForce evaluate_slice(const SlicedLineContact& contact, std::size_t slice, double approach, double approach_rate);

/// The approach of slice j for an approach `approach` at the middle and a tilt [rad].
inline double slice_approach(const SlicedLineContact& c, std::size_t j, double approach, double tilt) {
  return approach + tilt * c.slice_centre[j] - c.law.slice_drop[j];
}

/// The whole contact: force, moment about the roller's middle (sum of F_j x_j, > 0 with the +x end
/// loaded harder) and their derivatives. The variables, in order, of the derivative arrays:
/// approach, tilt, approach rate, tilt rate.
struct TiltedLineForce {
  double force = 0;           ///< N
  double moment = 0;          ///< N m
  double elastic_force = 0;   ///< N
  double elastic_energy = 0;  ///< J
  double damping_power = 0;   ///< W
  double max_slice_force = 0; ///< N, the most loaded slice
  std::array<double, 4> d_force{}, d_moment{};
  bool valid = true;  ///< false: a slice beyond the validity limit, or a non-finite input
};
/// `slice_forces`, if not empty (then of the slice count), receives each slice's force.
TiltedLineForce evaluate_tilted(const SlicedLineContact& contact, double approach, double tilt,
                                double approach_rate, double tilt_rate, std::span<double> slice_forces = {});

}  // namespace raceway::contact
