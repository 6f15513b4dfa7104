// raceway scene: the validated, SI-unit description of one simulation.
//
// Produced by scene::load_scene (TOML file) or scene::default_scene(); consumed by the model builder in
// solver/. Every quantity here is in SI units (m, kg, s, N, Pa, rad, rad/s); units are converted at
// the io boundary only. Every field has been validated when a Scene is returned.
#pragma once

#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "contact/laws/law_registry.hpp"
#include "contact/laws/race_imperfections.hpp"
#include "contact/laws/roller_profile.hpp"

namespace raceway::scene {

/// A scalar function of time: constant, or piecewise linear through (time, value) points and held
/// constant outside them. SI units of whatever it describes.
struct TimeFunction {
  std::vector<double> times;   ///< strictly increasing [s]; empty for a constant
  std::vector<double> values;  ///< same size as times, or one value for a constant

  static TimeFunction constant(double v) { return TimeFunction{{}, {v}}; }
  double operator()(double t) const;
  /// Time derivative (piecewise constant; 0 outside the table).
  double derivative(double t) const;
  /// Its integral from 0 to t (a driven ring's angle from its speed).
  double integral(double t) const;
  bool is_zero() const;
};

struct Material {
  std::string name;
  double density = 0;         ///< kg/m^3
  double youngs_modulus = 0;  ///< Pa
  double poisson_ratio = 0;   ///< -
};

enum class ModelKind { planar, spatial };

struct SceneInfo {
  std::string name;
  ModelKind model = ModelKind::planar;
  /// Dotted keys ("inner_ring.speed") whose values may lie beyond the sane range of their kind of
  /// quantity (io/scene/units.hpp: QuantityKind); every value is finite all the same.
  std::vector<std::string> allow_out_of_range;
  double end_time = 0;         ///< s
  double output_interval = 0;  ///< s
};

/// tapered_roller: a single-row tapered roller bearing (spatial model only): cone (inner ring) and
/// cup (outer ring) raceways are cones whose apexes meet on the axis (contact/laws/tapered_geometry.hpp).
enum class BearingType { cylindrical_roller, deep_groove_ball, four_point_contact_ball, angular_contact_ball, tapered_roller };

/// Ball-bearing geometry (spatial scenes). Groove radii are conformity * ball diameter. The contact
/// angle under load is never an input: it comes out of the groove geometry, the clearance and the
/// loads; an angular contact bearing's free contact angle is part of its groove geometry.
struct BallGeometry {
  double ball_diameter = 0;         ///< m
  double inner_conformity = 0;      ///< f_i = inner groove radius / ball diameter (> 0.5)
  double outer_conformity = 0;      ///< f_o = outer groove radius / ball diameter (> 0.5)
  /// Four-point bearings only: the angle at which a centred ball touches each gothic arc when the
  /// clearance is taken up symmetrically (sets the axial offset of the arcs' curvature centres:
  /// e = (r_groove - D/2) sin(angle) measured from the groove's mid-plane). 0 for deep groove.
  double arc_contact_angle = 0;     ///< rad
  /// Angular contact bearings only: the free contact angle alpha_0, at which the ball touches both
  /// grooves without load when the rings are centred: the grooves' curvature centres lie on the line
  /// through the ball centre at alpha_0 to the radial plane, A = (f_i + f_o - 1) D apart, the outer
  /// one on the +z side. Axial load on the inner ring along +z (or on the outer along -z) closes it.
  /// Equivalent to a deep groove bearing of clearance P_d = 2 A (1 - cos alpha_0) with its rings
  /// pushed together axially.
  double free_contact_angle = 0;    ///< rad
};

/// Cylindrical roller bearing designs by their ribs (flanges): NU two ribs on the outer ring; NJ
/// those and one on the inner ring, on its -z side (it carries an inner-ring axial load along +z);
/// NUP two on each ring; N two on the inner ring.
enum class RibArrangement { nu, nj, nup, n };
enum class RollerEnd { flat, spherical };

/// Spatial cylindrical roller bearings: the roller's profile along its length and its ends and ribs.
/// roller_length is the straight part; the profile's rounded corners add corner_radius at each end.
struct RollerGeometry {
  RibArrangement ribs = RibArrangement::nu;
  contact::RollerProfileKind profile = contact::RollerProfileKind::straight;
  double corner_radius = 0;  ///< m, r_c of the profile
  double crown_radius = 0;   ///< m, circular crown
  double flat_length = 0;    ///< m, circular crown: its straight middle
  double design_load = 0;    ///< N, logarithmic profiles
  RollerEnd end = RollerEnd::flat;
  double end_radius = 0;     ///< m: flat ends: the rounding of the face's edge; spherical ends: the sphere
  double rib_angle = 0;      ///< rad, the rib face's opening angle (0: a radial face)
  double end_clearance = 0;  ///< m, axial play of a roller between the two ribs of a ring
  /// Tapered roller bearings: alpha_o, the cup raceway's angle to the bearing axis (the catalogue's
  /// contact angle); the roller's and the cone's angles follow from it (tapered_geometry.hpp).
  double cup_angle = 0;      ///< rad
};

struct BearingGeometry {
  BearingType type = BearingType::cylindrical_roller;
  int rolling_elements = 0;
  double roller_diameter = 0;    ///< m
  double roller_length = 0;      ///< m (effective contact length)
  double pitch_diameter = 0;     ///< m
  double radial_clearance = 0;   ///< m, diametral clearance P_d: total radial play of one ring
                                 ///< against the other (outer race radius - inner race radius - D = P_d/2)
  double inner_bore_diameter = 0;       ///< m, bore of the inner ring (sets its mass unless given)
  double outer_outside_diameter = 0;    ///< m, outside diameter of the outer ring
  double ring_width = 0;                ///< m, width of both rings (default: roller_length)
  std::string roller_material;          ///< key into Scene::materials (rollers or balls)
  std::string ring_material;            ///< key into Scene::materials
  long scatter_seed = 1;                ///< seed of the drawn scatter (ball and roller diameters, pocket clearances)
  /// Ball bearings, the balls' diameter scatter (docs/vibration.md): ball k's diameter is
  /// ball.ball_diameter + ball_diameter_deviations[k]; the list is given or drawn from a normal
  /// distribution of standard deviation ball_diameter_scatter (scatter_seed). Empty: every ball nominal.
  double ball_diameter_scatter = 0;              ///< m, standard deviation
  std::vector<double> ball_diameter_deviations;  ///< m, one per ball, or empty
  /// Roller bearings, the rollers' diameter scatter: roller k's diameter (a tapered roller's at
  /// every section) is roller_diameter + roller_diameter_deviations[k], given or drawn like the
  /// balls' (roller_diameter_scatter, scatter_seed). Empty: every roller nominal.
  double roller_diameter_scatter = 0;              ///< m, standard deviation
  std::vector<double> roller_diameter_deviations;  ///< m, one per roller, or empty
  BallGeometry ball;                    ///< ball bearings
  RollerGeometry roller;                ///< spatial cylindrical and tapered roller bearings
  bool is_ball_bearing() const { return type != BearingType::cylindrical_roller && type != BearingType::tapered_roller; }
  bool is_tapered() const { return type == BearingType::tapered_roller; }
  /// The spatial roller's profile: roller_length is its straight part, the corners add
  /// corner_radius at each end; the modulus and rolling radius are the caller's.
  contact::RollerProfile roller_profile(double reduced_modulus, double rolling_radius) const {
    contact::RollerProfile p;
    p.kind = roller.profile;
    p.length = roller_length + 2 * roller.corner_radius;
    p.corner_radius = roller.corner_radius;
    p.crown_radius = roller.crown_radius;
    p.flat_length = roller.flat_length;
    p.design_load = roller.design_load;
    p.reduced_modulus = reduced_modulus;
    p.rolling_radius = rolling_radius;
    return p;
  }
  /// Diameter of the rolling element: roller or ball.
  double element_diameter() const { return is_ball_bearing() ? ball.ball_diameter : roller_diameter; }
  /// Race (groove bottom) diameters: d_m -/+ D -/+ P_d/2.
  double inner_race_diameter() const { return pitch_diameter - element_diameter() - 0.5 * radial_clearance; }
  double outer_race_diameter() const { return pitch_diameter + element_diameter() + 0.5 * radial_clearance; }
};

enum class CageGuidance { inner_land, outer_land, rolling_element };
enum class PocketShape { cylindrical, spherical };
/// Roller cages: the bars between the pockets rigid with the cage, or each a clamped beam.
enum class CageBridges { rigid, flexible };
/// The beam theory of a flexible part (cage bridges, the outer ring's rim): Timoshenko's (bending,
/// shear and, for the rim, extension) or Euler-Bernoulli's (bending only; the rim inextensional).
enum class BeamTheory { timoshenko, euler_bernoulli };

struct CageSupport {          ///< cage on a spindle (seed 000's aerostatic spindle); 0 = none
  double radial_stiffness = 0, radial_damping = 0;  ///< N/m, N s/m (x and y)
  double axial_stiffness = 0, axial_damping = 0;    ///< N/m, N s/m (z)
  double tilt_stiffness = 0, tilt_damping = 0;      ///< N m/rad, N m s/rad (about x and y)
  bool any() const { return radial_stiffness > 0 || axial_stiffness > 0 || tilt_stiffness > 0; }
};

struct CageSpec {
  CageGuidance guidance = CageGuidance::inner_land;
  PocketShape pocket_shape = PocketShape::cylindrical;  ///< ball bearings
  double pocket_clearance = 0;  ///< m, pocket width (diameter) minus roller (ball) diameter
  /// Ball bearings: pocket k's clearance is pocket_clearance + pocket_clearance_deviations[k] (given,
  /// or drawn with standard deviation pocket_clearance_scatter); empty: every pocket nominal.
  double pocket_clearance_scatter = 0;             ///< m, standard deviation
  std::vector<double> pocket_clearance_deviations;  ///< m, one per pocket, or empty
  double land_clearance = 0;    ///< m, radial clearance between cage and the guiding land
  double bar_width = 0;         ///< m, axial length of the roller-bar contact (default roller_length)
  double land_width = 0;        ///< m, axial width of the guiding land contact
  std::string material;         ///< key into Scene::materials
  double mass = 0;              ///< kg; 0 = computed from geometry and material
  double inertia = 0;           ///< kg m^2 about the bearing axis; 0 = computed
  double transverse_inertia = 0;  ///< kg m^2 about a diameter (spatial); 0 = computed
  double inner_diameter = 0;    ///< m, cage bore (spatial; 0 = d_m - 0.6 D)
  double outer_diameter = 0;    ///< m, cage outside diameter (spatial; 0 = d_m + 0.6 D)
  double width = 0;             ///< m, axial width of the cage (spatial; 0 = 0.8 ring width)
  double initial_offset = 0;    ///< m, the cage centre's start along +x from the seated place (spatial)
  double mass_eccentricity = 0; ///< m, centre of mass off the cage axis, at mass_eccentricity_angle (spatial)
  double mass_eccentricity_angle = 0; ///< rad, the centre of mass's direction from the cage frame's x towards its y
  CageSupport support;          ///< spatial: spindle-mounted cage
  CageBridges bridges = CageBridges::rigid;  ///< roller cages: rigid or flexible bars (bridges)
  double bridge_stiffness = 0;  ///< N/m, tangential, under the pocket force; 0 = from the beam section
  double bridge_thickness = 0;  ///< m, circumferential thickness of a bridge; 0 = computed
  double bridge_height = 0;     ///< m, radial height of a bridge; 0 = computed
  double bridge_damping_ratio = 0;  ///< structural damping of a bridge's bending
  BeamTheory bridge_theory = BeamTheory::timoshenko;  ///< flexible bridges: with shear, or bending only
};

enum class RingMotion { fixed, driven, free };

struct RingLoad {           ///< loads on a ring, in the bearing frame, functions of time
  TimeFunction fx, fy;      ///< N
  TimeFunction mz;          ///< N m (only meaningful for a free ring)
  TimeFunction fz;          ///< N, axial (spatial)
  TimeFunction mx, my;      ///< N m, tilting moments (spatial, ring tilt free)
};

struct RingSupport {        ///< linear spring-damper to ground, per translational direction
  double stiffness = 0;     ///< N/m; 0 = no support (radial: x and y)
  double damping = 0;       ///< N s/m
  double axial_stiffness = 0, axial_damping = 0;  ///< N/m, N s/m (spatial, z)
  double tilt_stiffness = 0, tilt_damping = 0;    ///< N m/rad, N m s/rad (spatial, about x and y)
};

/// Tilt of a ring about x and y (spatial scenes): held aligned, free (integrated), or a prescribed
/// misalignment given as functions of time (seed 000 case M24).
enum class RingTilt { fixed, free, prescribed };
/// The outer ring's raceway: rigid, or a thin elastic ring whose in-plane inextensional bending modes
/// n = 2..modes are states (solver/bearing/ring_modes.hpp; planar roller bearings, outer ring only).
enum class RingFlexibility { rigid, ring_modes };

/// A localized defect on a ring's race (ball bearings): contact/laws/race_imperfections.hpp.
struct SpallSpec {
  bool present = false;  ///< a [*_ring.spall] table was given
  double angle = 0;      ///< rad, its centre, ring frame, about the ring axis (0: along the ring's x)
  double length = 0;     ///< m, along the race
  double width = 0;      ///< m, across the race
  double depth = 0;      ///< m
  contact::SpallEdge edge = contact::SpallEdge::sharp;
};

/// A race's waviness: radius deviation sum A_k cos(n_k theta + phase_k) (ball bearings).
struct WavinessSpec {
  std::vector<int> orders;
  std::vector<double> amplitudes;  ///< m
  std::vector<double> phases;      ///< rad (empty: all 0)
  bool present() const { return !orders.empty(); }
};

struct RingSpec {
  RingMotion motion = RingMotion::fixed;
  TimeFunction speed;       ///< rad/s, for motion = driven
  bool translation_free = true;  ///< driven/free rings: x, y integrated (false = centre held fixed)
  bool axial_free = true;        ///< spatial, driven/free rings: z integrated (false = held)
  RingTilt tilt = RingTilt::fixed;  ///< spatial
  TimeFunction misalignment_x, misalignment_y;  ///< rad, rotation about x and y (tilt = prescribed)
  double axial_position = 0;     ///< m, spatial: where a ring held axially is held (preload by displacement)
  RingLoad load;
  RingSupport support;
  double mass = 0;          ///< kg; 0 = computed from geometry and material
  double inertia = 0;       ///< kg m^2; 0 = computed
  double transverse_inertia = 0;  ///< kg m^2 about a diameter (spatial); 0 = computed
  RingFlexibility flexibility = RingFlexibility::rigid;  ///< planar outer ring: rigid or modal rim
  int modes = 0;                 ///< ring_modes: the highest bending mode number kept (n = 2..modes)
  double rim_thickness = 0;      ///< m, radial, of the rim's bending section; 0 = outside - race radius
  double rim_width = 0;          ///< m, axial, of the rim's bending section; 0 = ring width
  double rim_damping_ratio = 0;  ///< ring_modes: modal damping ratio of every bending mode
  BeamTheory rim_theory = BeamTheory::timoshenko;  ///< ring_modes: thick ring, or thin inextensional
  SpallSpec spall;               ///< ball bearings: a spall on this ring's race
  WavinessSpec waviness;         ///< ball bearings: this ring's race's waviness
};

/// A rolling element's own imperfections (ball bearings, [rolling_element]): a spall and waviness
/// on one ball each, round the ball's equator in its own frame (contact/laws/element_imperfections.hpp).
struct RollingElementSpec {
  SpallSpec spall;               ///< angle: the spall's centre round the ball's equator
  int spall_element = 0;         ///< the ball that carries it (ball[k])
  WavinessSpec waviness;
  int waviness_element = 0;
  bool any() const { return spall.present || waviness.present(); }
};

/// The fixed outer ring mounted in a housing (ball bearings): the housing and ring move together
/// in x and y on the housing's spring and damper (its first mode per radial direction), with
/// optional further modes of the housing seen at the bearing seat ([housing.modes]); a sensor on it
/// is sampled every sensor_interval (solver/bearing/housing.hpp).
struct HousingSpec {
  bool present = false;    ///< a [housing] section was given
  double mass = 0;         ///< kg, the housing's (the outer ring's mass is added)
  double stiffness = 0;    ///< N/m, radial (x and y)
  double damping = 0;      ///< N s/m, radial
  double sensor_interval = 0;  ///< s, between the sensor's samples
  /// Further modes at the seat ([housing.modes]): modal mass kg, stiffness N/m, damping N s/m each.
  std::vector<double> mode_masses, mode_stiffnesses, mode_dampings;
  /// The sensor's displacement per unit of each mode's (the first mode's first); empty: all 1, the
  /// sensor at the seat.
  std::vector<double> sensor_participation;
};

/// The thermal network (solver/bearing/thermal_network.hpp): a [thermal] section switches it on.
/// A conductance or capacity left at -1 is taken from the geometry when the model is built.
struct ThermalSpec {
  bool present = false;                    ///< a [thermal] section was given
  double ambient_temperature = 293.15;     ///< K
  double initial_temperature = -1;         ///< K; -1: the ambient temperature
  double specific_heat = 460;              ///< J/(kg K), the rings and rolling elements (steel)
  double cage_specific_heat = 460;         ///< J/(kg K)
  double oil_heat_capacity = -1;           ///< J/K
  double housing_heat_capacity = -1;       ///< J/K
  double convection_coefficient = 200;     ///< W/(m^2 K), the parts to the oil
  double ambient_convection_coefficient = 20;  ///< W/(m^2 K), the housing to the ambient air
  double fit_conductance = 5000;           ///< W/(m^2 K), the rings' fits (shaft, housing)
  double element_ring_conductance = -1;    ///< W/K, one rolling element to one ring through its contact
};

/// Contact laws, chosen by name in the scene. The parser looks every name up in the law registry
/// (contact/laws/law_registry.hpp, which lists the laws each contact accepts) and stores its id;
/// models are built from `id`, `name` is the scene's spelling of it (for printing only).
struct NormalLaw {
  contact::LawId id = contact::LawId::palmgren;  ///< palmgren (line contact) | hertz (point contact)
  std::string_view name() const { return contact::law_entry(id).name; }
  int slices = 1;                 ///< slices along the roller length (planar: crowning only)
  double crown_drop = 0;          ///< m, profile drop at the roller ends (circular crown); 0 = straight
};
struct DampingLaw {
  contact::LawId id = contact::LawId::hunt_crossley;  ///< hunt_crossley | none
  std::string_view name() const { return contact::law_entry(id).name; }
  double factor = 0;                   ///< s/m: F = K delta^n (1 + factor * d(delta)/dt)
};
struct TractionLaw {
  contact::LawId id = contact::LawId::tanh_traction;  ///< tanh | none | limiting_shear (ball-race, needs a lubricant)
  std::string_view name() const { return contact::law_entry(id).name; }
  double friction_coefficient = 0; ///< - (limit value)
  double slip_velocity_scale = 0;  ///< m/s: mu = mu_max tanh(u / u_scale)
  int grid_x = 5, grid_y = 5;      ///< point contacts: traction grid over the ellipse (rolling x transverse)
  bool rolling_resistance = true;  ///< point contacts: EHL rolling resistance where there is a film
};
struct ContactSpec {
  NormalLaw normal;
  DampingLaw damping;
  TractionLaw traction;
};

struct Lubricant {
  std::string name;
  double viscosity_40 = 0;        ///< m^2/s, kinematic viscosity at 40 degC (0: not given)
  double viscosity_100 = 0;       ///< m^2/s, kinematic viscosity at 100 degC (0: not given)
  double density = 0;             ///< kg/m^3 (0: not given)
  double temperature = 0;         ///< K, the oil's temperature (0: not given)
  bool roelands = false;          ///< pressure-viscosity law of the traction: Roelands (true) or Barus
  double viscosity = 0;           ///< Pa s, dynamic viscosity at the bearing temperature
  double pressure_viscosity = 0;  ///< 1/Pa
  double limiting_shear_coefficient = 0;  ///< - : limiting shear stress = coefficient * pressure
  double viscosity_exponent_cap = 12;     ///< - : largest alpha p in the Barus law (contact/laws/point_contact.hpp);
                                          ///< 12 gives measured traction-curve shapes and practical steps
  double inlet_meniscus = 0;       ///< - : starvation's inlet meniscus in contact semi-widths (ball-groove films); 0: flooded
  double oil_volume_fraction = 0;  ///< - : oil's share of the cavity's oil-air mixture (drag and churning); 0: none
};

/// [life]: what the rating lives of ISO 281 and ISO/TS 16281 take besides the geometry and the run's
/// loads (computed by the report, io/report/report_life.py; docs/life.md). NaN: not given (the
/// report then uses its documented default, or the rating computed from the geometry).
struct LifeSpec {
  static constexpr double not_given = std::numeric_limits<double>::quiet_NaN();
  double reliability = not_given;           ///< percent, 90 to 99.95 (a_1); not given: 90
  double contamination_factor = not_given;  ///< e_C of ISO 281, (0, 1]; not given: 0.5
  double dynamic_load_rating = not_given;   ///< N, published C (else computed from the geometry)
  double static_load_rating = not_given;    ///< N, published C_0 (else ISO 76 from the geometry)
  double fatigue_load_limit = not_given;    ///< N, published C_u (else estimated from C_0)
  double lubricant_density = not_given;     ///< kg/m^3, for nu = eta / rho; not given: 870 kg/m^3
};

/// CVODE's multistep methods (bdf: stiff, adams: non-stiff), ARKODE's explicit Runge-Kutta pairs (erk) and
/// its diagonally implicit Runge-Kutta methods with the Newton solve (ark; solver/numerics/integrator.hpp).
enum class IntegrationMethod { bdf, adams, erk, ark };
/// Newton linear solver (solver/numerics/newton_backends.hpp). `automatic` picks block elimination or PETSc by
/// the number of rolling elements (the measured crossover; README "Newton linear solvers").
enum class LinearSolverKind { automatic, petsc_bordered, block_elimination, sundials_dense };
/// The frame of a rolling element's in-plane velocity states: the bearing's (vx, vy), or its orbital
/// frame (v_r, v_theta) at its own angular position about the bearing axis (solver/bearing/orbital_frame.hpp).
enum class ElementVelocityFrame { bearing, orbital };

struct SolverSpec {
  IntegrationMethod method = IntegrationMethod::bdf;
  int max_order = 5;                 ///< bdf, adams: largest order; erk, ark: the order of the pair
  bool stability_limit_detection = false;  ///< bdf: CVODE's BDF stability-limit detection (order 3 and up)
  /// bdf: the largest order chosen during the run between max_order and 2 by measured probes
  /// (solver/numerics/order_choice.hpp); the scene's default unless it gives max_order.
  bool automatic_order = false;
  double rtol = 1e-6;
  /// Tolerances this many times tighter on a rolling element's translational velocities while the
  /// element touches its pocket (or nearly); 1: off (solver/bearing/equations.hpp, adjust_error_weights).
  double pocket_tolerance_factor = 1;
  /// With the pocket factor: the cage's rotation rate is tightened by it too while any element
  /// touches its pocket (a pocket's approach rate is the difference of the element's orbital rate
  /// and the cage's, both large).
  bool pocket_tolerance_cage = false;
  /// Ball and planar roller bearings: the frame of the rolling elements' in-plane velocity states;
  /// with the orbital frame the pocket factor tightens v_theta alone.
  ElementVelocityFrame element_velocity_frame = ElementVelocityFrame::bearing;
  /// Orbital frame: the rolling elements' radial velocity tolerance is this many times the velocity tolerance.
  double radial_velocity_tolerance_factor = 1;
  /// Absolute tolerances per variable class (SI).
  double atol_position = 0;          ///< m
  double atol_angle = 0;             ///< rad
  double atol_velocity = 0;          ///< m/s
  double atol_angular_velocity = 0;  ///< rad/s
  LinearSolverKind linear_solver = LinearSolverKind::automatic;
  /// PETSc options for petsc-bordered ("-fieldsplit_1_pc_factor_mat_solver_type mumps ..."), and
  /// where they were given (for errors: file, line of the value).
  std::string petsc_options;
  std::string petsc_options_file;
  int petsc_options_line = 0;
  double max_step = 0;               ///< s; 0 = no limit
  double initial_step = 0;           ///< s; 0 = CVODE's estimate
  long max_steps = 500000000;        ///< total step budget for the run
  double max_wall_time = 0;          ///< s of wall-clock time for the integration; 0 = no limit
  double jacobian_perturbation = 1e-7;  ///< relative finite-difference increment
};

/// A planetary bearing (seed 003 eq. 1-6): the bearing frame rides on a carrier that turns about the
/// sun axis. The bearing axis lies at distance `radius` from the sun axis, along the bearing frame's
/// +x; the carrier turns at `speed` (psi'(t)) about z. Every quantity of the scene (positions,
/// velocities, ring speeds, loads) is in the bearing frame, which turns with the carrier.
struct CarrierSpec {
  bool present = false;  ///< a [carrier] section was given (else the bearing frame is inertial)
  double radius = 0;     ///< m, R_c: distance from the sun axis to the bearing axis
  TimeFunction speed;    ///< rad/s, psi'(t): the carrier's speed about z
};

struct OutputSpec {
  bool segments = true;   ///< per-segment diagnostics
  int segment_every = 1;  ///< the segment diagnostics at every this-th output sample (0, N, 2N, ...)
  double max_size = 4e9;  ///< bytes: a run whose series would be larger is refused before it starts
  double checkpoint_interval = 0;         ///< s simulated, between periodic checkpoints (0: none)
  double checkpoint_wall_interval = 300;  ///< s wall clock, after which a checkpoint is written (0: none)
};

/// A value a scene takes from the bearing catalogue (io/scene/catalogue.hpp) or a first-scene default
/// that comes with a designation, for `raceway check`.
struct CatalogueValue {
  std::string key;     ///< dotted scene key, "bearing.ball_diameter"
  std::string value;   ///< as TOML text, "\"7.94 mm\""
  std::string origin;  ///< where it comes from: a source, or the rule of an estimate, or why a default
  bool given = false;  ///< the scene gives the key itself: its value is used and this one is not
  bool first_scene_default = false;  ///< not bearing data: a default a first scene needs (gravity, lubricant)
};

/// One simulation, validated and in SI units, and where it came from.
struct Scene {
  std::string source;     ///< file path, or "<built-in default>"
  std::string text;       ///< the scene text as read (stored in the output file)
  /// Keys set on the command line, "section.key=VALUE" as given (--set), applied over the text.
  std::vector<std::string> overrides;
  SceneInfo scene;
  BearingGeometry bearing;
  std::map<std::string, Material> materials;
  CageSpec cage;
  RingSpec inner_ring;
  RingSpec outer_ring;
  Lubricant lubricant;
  LifeSpec life;
  ContactSpec roller_race;  ///< roller bearings: roller-race (spatial: per slice)
  ContactSpec roller_cage;  ///< roller bearings: roller-cage bar
  ContactSpec ball_race;    ///< spatial: ball-groove
  ContactSpec ball_cage;    ///< spatial: ball-pocket
  ContactSpec cage_land;
  ContactSpec roller_flange;  ///< spatial roller bearings: a roller's end on a rib
  RollingElementSpec rolling_element;  ///< ball bearings: a ball's spall and waviness (absent: perfect balls)
  HousingSpec housing;        ///< spatial: the outer ring in a housing (absent: the outer ring as its motion says)
  ThermalSpec thermal;        ///< the thermal network (absent: none, one temperature for the bearing)
  CarrierSpec carrier;    ///< planar: the bearing on a rotating planet carrier (absent: inertial frame)
  SolverSpec solver;
  OutputSpec output;
  bool gravity = false;   ///< gravity along -y (9.80665 m/s^2)
  /// [bearing] designation ("6205"; empty: none) and the values it filled in (in the order filled).
  std::string designation;
  std::vector<CatalogueValue> catalogue;
  /// Line of every key of the scene text ("inner_ring.load.fy" -> 31), for errors found after
  /// parsing (start-up, output size) that name the keys involved.
  std::map<std::string, int, std::less<>> key_lines;

  const Material& material(const std::string& key) const { return materials.at(key); }
  /// Line of a dotted key in the scene text; 0 when the key is not in it (a default).
  int line_of(std::string_view key) const {
    const auto it = key_lines.find(key);
    return it == key_lines.end() ? 0 : it->second;
  }
};

}  // namespace raceway::scene
