// A race's imperfections (a spall, waviness) in the model: built from the scene into the ball-groove
// laws and a spatial roller bearing's slice laws (contact/laws/race_imperfections.hpp: a change of
// the contact's geometry, nothing else), and the step limit that makes the integration see every
// rolling element's entry into a spall (a roller's: its centre's, the same for all its slices).
//
// A spall is short (0.18 mm on a 6205's outer race: some tens of microseconds of a ball's passage),
// and a step that carries a ball over it unseen leaves no trace the error test could find. So
// before each step the step is limited (Equations::step_limit): a ball outside a spall may step at
// most to the spall's leading edge at its present angular speed relative to the race; a ball
// within it, a tenth of its passage time. The limit is a function of (t, z) alone, so it is the
// same at every rank count and after a resume. A ball's own spall (solver/bearing/ball_model.cpp:
// the ball's orientation is then a state) is limited alike, as it turns towards a race contact.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "contact/laws/race_imperfections.hpp"
#include "io/scene/scene.hpp"
#include "solver/bearing/model.hpp"

namespace raceway::bearing {

/// The imperfections of a ring's race for its ball-groove laws; null when the race is perfect.
std::shared_ptr<const contact::RaceImperfections> race_imperfections(const scene::RingSpec& ring, double race_radius,
                                                                     double ball_radius);

/// Ball k's own imperfections ([rolling_element]: round its equator, race_radius = ball_radius = its
/// radius r) for its ball-groove laws; null when ball k is perfect.
std::shared_ptr<const contact::RaceImperfections> element_imperfections(const scene::Scene& scene, int k, double r);

/// Roller k's slice laws (a spatial roller bearing): `shared`, the laws every perfect nominal roller
/// uses, or, where roller k carries its own defect ([rolling_element]) or the rollers' diameters
/// scatter, copies of them that carry the defect and reach farther by roller k's radius less the
/// nominal one times `reach_per_radius` (the slice's roller_radius is measured along the race's
/// normal: 1 on a cylindrical race, cos(gamma) for a tapered roller of half angle gamma).
std::vector<int> roller_slice_laws(Model& m, const scene::Scene& scene, int k, const std::vector<int>& shared,
                                   double reach_per_radius = 1.0);

/// Lines for the model's description (raceway check): each race's spall and waviness, or "".
std::string describe_race_imperfections(const Model& m);

/// Steps a ball takes at least within a spall.
inline constexpr double steps_within_spall = 10;

/// Whether a ball-groove or roller-slice law of the model has a spall.
bool has_spall(const Model& m);
/// The largest step at (t, z) that lets no ball enter or cross a spall unseen [s]; 0 when the model
/// has no spall (no limit). A ball's own spall: at most the step that turns it to the nearer
/// contact's edge at the ball's spin relative to the contact frame; a tenth of its passage within. A
/// roller's own spall alike, at its spin about its axis relative to each race contact's normal.
double spall_step_limit(const Model& m, double t, const double* z);

}  // namespace raceway::bearing
