#include "contact/segments/land_film.hpp"

namespace raceway::contact {

LandFilmStation land_film_station(const ShortBearingFilm& film, double land_width, int stations, int j,
                                  bool outer_land, const Eigen::Matrix3d& rot, const Eigen::Vector3d& ring_position,
                                  const Eigen::Vector3d& q, const Eigen::Vector3d& q_rate, double relative_spin) {
  LandFilmStation out;
  const double strip = land_width / stations;
  const double z1 = -0.5 * land_width + j * strip;
  ShortBearingFilm f = film;
  f.width = strip;
  f.pressure_width_cubed = strip_pressure_width_cubed(land_width, z1, z1 + strip);
  // The journal's centre relative to the bore's, in the ring frame.
  const double sign = outer_land ? 1.0 : -1.0;  // outer land: the cage (station) is the journal
  const ShortBearingForce s =
      evaluate_short_bearing(f, {sign * q.x(), sign * q.y()}, {sign * q_rate.x(), sign * q_rate.y()},
                             outer_land ? relative_spin : 0.0, outer_land ? 0.0 : relative_spin);
  out.valid = s.valid;
  out.minimum_film = s.minimum_film;
  out.power_loss = s.power_loss;
  // On the journal: the ring (inner land) or the cage (outer land: the ring gets the opposite).
  const Eigen::Vector3d on_journal = rot * Eigen::Vector3d(s.on_journal[0], s.on_journal[1], 0.0);
  const Eigen::Vector3d torque = rot.col(2) * s.couette_torque;
  out.force_on_ring = outer_land ? Eigen::Vector3d(-on_journal) : on_journal;
  out.couple_on_ring = outer_land ? Eigen::Vector3d(-torque) : torque;
  out.point = ring_position + rot * Eigen::Vector3d(0.5 * q.x(), 0.5 * q.y(), q.z());
  return out;
}

}  // namespace raceway::contact
