// The lubricated cage land of a ball bearing: one station of CageLandSegment3 carrying its strip of
// the land's short journal-bearing film (contact/laws/short_bearing_film.hpp). Kept apart from
// ball_segments.cpp, which calls it once per station when the segment has a film.
#pragma once

#include <Eigen/Dense>

#include "contact/laws/short_bearing_film.hpp"

namespace raceway::contact {

struct LandFilmStation {
  Eigen::Vector3d force_on_ring = Eigen::Vector3d::Zero();   ///< N, bearing frame
  Eigen::Vector3d couple_on_ring = Eigen::Vector3d::Zero();  ///< N m, the Couette shear about the axis
  Eigen::Vector3d point = Eigen::Vector3d::Zero();           ///< where the force acts, bearing frame
  double power_loss = 0;                                      ///< W
  double minimum_film = 0;                                    ///< m, floored
  bool valid = true;
};

/// Station j of `stations` over a land of width `land_width`. `q` and `q_rate`: the station's
/// centre on the cage axis relative to the ring's centre, and its rate, in the ring frame (which
/// turns with the ring: the ring's surface is at rest in it); `relative_spin`: (omega_cage -
/// omega_ring) . ring axis. Inner land: the ring's land is the journal in the cage's bore; outer land:
/// the cage is the journal in the ring's land bore. The pressure's resultant on each surface passes
/// through its own axis; it is applied midway between the two axes (equal and opposite on the two
/// bodies, so action = reaction; the couple F x e/2 this leaves is of the order of the clearance).
LandFilmStation land_film_station(const ShortBearingFilm& film, double land_width, int stations, int j,
                                  bool outer_land, const Eigen::Matrix3d& ring_rotation,
                                  const Eigen::Vector3d& ring_position, const Eigen::Vector3d& q,
                                  const Eigen::Vector3d& q_rate, double relative_spin);

}  // namespace raceway::contact
