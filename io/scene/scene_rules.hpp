// The rules of a scene that tie keys together, named by the rows of the schema table
// (scene_schema.cpp) that use them:
//   defaults that follow from other keys (a bore one element diameter inside the inner race),
//   conditions under which a key applies (speed only for a driven ring),
//   checks run after a key is read (the clearance smaller than a roller, a fixed ring does not
//   tilt freely, limiting-shear traction needs a lubricant), and
//   check_scene, the checks across sections (the rollers fit on the pitch circle, something
//   holds the bearing).
//
// Internal to raceway::scene.
#pragma once

#include <optional>
#include <string>

#include "io/scene/scene_schema.hpp"
#include "io/scene/scene_section.hpp"

namespace raceway::scene::schema::rules {

// ---- defaults that follow from other keys (nullopt: the key is required here) ------------------
std::optional<double> inner_bore_default(const Bind& b);
std::optional<double> outer_outside_default(const Bind& b);
std::optional<double> ring_width_default(const Bind& b);
std::optional<double> bar_width_default(const Bind& b);
std::optional<double> land_width_default(const Bind& b);
std::optional<double> walther_point_default(const Bind& b);
std::optional<double> walther_viscosity_default(const Bind& b);
std::optional<double> cage_bore_default(const Bind& b);
std::optional<double> cage_outside_default(const Bind& b);
std::optional<double> cage_width_default(const Bind& b);
std::optional<double> ring_support_stiffness_default(const Bind& b);
std::optional<double> friction_default(const Bind& b);
std::optional<double> rolling_resistance_default(const Bind& b);
std::optional<double> max_order_default(const Bind& b);
std::optional<double> slices_default(const Bind& b);
std::optional<double> end_radius_default(const Bind& b);
long max_order_limit(const Bind& b);
// On for bdf unless the scene gives max_order.
std::optional<double> automatic_order_default(const Bind& b);

// ---- conditions: why a key does not apply here, or nullopt -------------------------------------
std::optional<std::string> four_point_only(const Section& s, const Bind& b);
std::optional<std::string> circular_profile_only(const Section& s, const Bind& b);
std::optional<std::string> tapered_only(const Section& s, const Bind& b);
std::optional<std::string> logarithmic_profile_only(const Section& s, const Bind& b);
std::optional<std::string> planar_crown_only(const Section& s, const Bind& b);
std::optional<std::string> contact_angle_applies(const Section& s, const Bind& b);
std::optional<std::string> axially_held_only(const Section& s, const Bind& b);
std::optional<std::string> unless_ball_material(const Section& s, const Bind& b);
std::optional<std::string> land_guided_only(const Section& s, const Bind& b);
std::optional<std::string> driven_ring_only(const Section& s, const Bind& b);
std::optional<std::string> moving_ring_only(const Section& s, const Bind& b);
std::optional<std::string> outer_ring_only(const Section& s, const Bind& b);
std::optional<std::string> ring_modes_only(const Section& s, const Bind& b);
std::optional<std::string> prescribed_tilt_only(const Section& s, const Bind& b);
std::optional<std::string> force_needs_free_centre(const Section& s, const Bind& b);
std::optional<std::string> axial_force_needs_axially_free(const Section& s, const Bind& b);
std::optional<std::string> tilting_moment_needs_free_tilt(const Section& s, const Bind& b);
std::optional<std::string> moment_needs_free_ring(const Section& s, const Bind& b);
std::optional<std::string> support_needs_moving_ring(const Section& s, const Bind& b);
std::optional<std::string> radial_support_needs_free_centre(const Section& s, const Bind& b);
std::optional<std::string> axial_support_needs_axially_free(const Section& s, const Bind& b);
std::optional<std::string> tilt_support_needs_free_tilt(const Section& s, const Bind& b);
std::optional<std::string> damping_law_on(const Section& s, const Bind& b);
std::optional<std::string> traction_law_on(const Section& s, const Bind& b);
std::optional<std::string> bdf_only(const Section& s, const Bind& b);
std::optional<std::string> bdf_order_choice(const Section& s, const Bind& b);

// ---- checks after a key is read ----------------------------------------------------------------
void allowed_keys_in_scene(const Row& row, const Section& s, Bind& b);
void output_interval_within_run(const Row& row, const Section& s, Bind& b);
void carrier_without_gravity(const Row& row, const Section& s, Bind& b);
void initial_step_within_run(const Row& row, const Section& s, Bind& b);
void model_fits_bearing_type(const Row& row, const Section& s, Bind& b);
void clearance_fits_elements(const Row& row, const Section& s, Bind& b);
void bore_inside_inner_race(const Row& row, const Section& s, Bind& b);
void outside_beyond_outer_race(const Row& row, const Section& s, Bind& b);
void ring_wider_than_ball(const Row& row, const Section& s, Bind& b);
void ball_pocket_clearance_fits(const Row& row, const Section& s, Bind& b);
void land_clearance_fits(const Row& row, const Section& s, Bind& b);
void cage_offset_within_clearances(const Row& row, const Section& s, Bind& b);
void land_width_within_rings(const Row& row, const Section& s, Bind& b);
void cage_bore_between_race_and_pitch(const Row& row, const Section& s, Bind& b);
void cage_outside_between_pitch_and_race(const Row& row, const Section& s, Bind& b);
void cage_width_fits(const Row& row, const Section& s, Bind& b);
void bars_within_rollers(const Row& row, const Section& s, Bind& b);
void cage_support_has_spring(const Row& row, const Section& s, Bind& b);
void damper_has_spring(const Row& row, const Section& s, Bind& b);
void fixed_ring_tilt_not_free(const Row& row, const Section& s, Bind& b);
void misalignment_given(const Row& row, const Section& s, Bind& b);
void ring_support_has_spring(const Row& row, const Section& s, Bind& b);
void crown_drop_fits(const Row& row, const Section& s, Bind& b);
void roller_profile_fits(const Row& row, const Section& s, Bind& b);
void cup_angle_fits(const Row& row, const Section& s, Bind& b);
void end_radius_fits(const Row& row, const Section& s, Bind& b);
void rib_angle_fits_end(const Row& row, const Section& s, Bind& b);
void end_clearance_fits(const Row& row, const Section& s, Bind& b);
void axial_load_carried_by_ribs(const Row& row, const Section& s, Bind& b);
void limiting_shear_has_lubricant(const Row& row, const Section& s, Bind& b);
void film_law_has_lubricant(const Row& row, const Section& s, Bind& b);
void walther_points_fit(const Row& row, const Section& s, Bind& b);
void viscosity_given_once(const Row& row, const Section& s, Bind& b);
void drag_has_oil_density(const Row& row, const Section& s, Bind& b);
void traction_fits_normal_law(const Row& row, const Section& s, Bind& b);
void rolling_resistance_has_film(const Row& row, const Section& s, Bind& b);
void remember_petsc_options_place(const Row& row, const Section& s, Bind& b);
void order_exists_for_method(const Row& row, const Section& s, Bind& b);
// The automatic order chooses between max_order and 2: max_order must be 3 or more.
void automatic_order_has_choice(const Row& row, const Section& s, Bind& b);

// ---- the race's imperfections and the housing (imperfection_rules.cpp) -------------------------
void spall_given(const Row& row, const Section& s, Bind& b);
void waviness_lists_match(const Row& row, const Section& s, Bind& b);
/// A ball's spall and waviness ([rolling_element]): the spall shorter than a quarter of the ball's
/// circumference (the two race contacts lie half a circumference apart), the lists matched.
void element_spall_given(const Row& row, const Section& s, Bind& b);
void element_waviness_given(const Row& row, const Section& s, Bind& b);
/// Scatter of the balls' diameters and the pockets' clearances (imperfection_rules.cpp): a given
/// list has one value per ball (pocket); a scatter draws that list (scatter_draws.hpp).
void ball_deviations_per_ball(const Row& row, const Section& s, Bind& b);
void ball_diameters_drawn(const Row& row, const Section& s, Bind& b);
void roller_deviations_per_roller(const Row& row, const Section& s, Bind& b);
void roller_diameters_drawn(const Row& row, const Section& s, Bind& b);
void pocket_deviations_per_pocket(const Row& row, const Section& s, Bind& b);
void pocket_clearances_drawn(const Row& row, const Section& s, Bind& b);
std::optional<std::string> housing_holds_fixed_outer_ring(const Section& s, const Bind& b);
void sensor_interval_within_output(const Row& row, const Section& s, Bind& b);
void housing_mode_lists_match(const Row& row, const Section& s, Bind& b);
void sensor_participation_per_mode(const Row& row, const Section& s, Bind& b);

// ---- across sections ---------------------------------------------------------------------------
/// The rolling elements fit on the pitch circle (with room for ball-cage bars), and the rings are
/// held radially (and, spatial, axially and in tilt). Errors name [bearing] or [outer_ring] keys.
void check_scene(const Section& bearing, const Section& outer_ring, const Scene& scene);
/// Something holds the cage radially: a land, a support with radial stiffness, or (ball-guided)
/// spherical pockets. A ball-guided cage in cylindrical (radially drilled) pockets is held only
/// while the balls stay spread around it: they slide along the pockets' radial axes, and once they
/// bunch the cage drifts through the rings. Errors name [cage] keys; checked after every section.
void check_cage_held(const Section& cage, const Scene& scene);

}  // namespace raceway::scene::schema::rules
