// The bearing as a multibody system: bodies, state layout and contact segments built from a scene.
// One description for every bearing kind: a planar roller bearing is the spatial description
// restricted to the coordinates it needs (x, y and the rotation about z), as a 2-D molecular
// dynamics code runs 2-D as 3-D restricted.
//
// Model no more than the scene needs:
//  - a coordinate that nothing depends on is not a state: a ball's orientation (a sphere's contact
//    geometry does not depend on it), a roller's and a ring's angle about their own axes;
//  - fixed and driven motions and prescribed misalignments are functions of time, not states;
//  - a segment exists only where the geometry can close it.
//
// State layout: border first (inner ring, outer ring, cage: whichever carry states), then one equal
// block per rolling element. The Jacobian is then block diagonal with borders (seed 000 fig. 2).
// Within a body the builder orders positions before velocities.
//
// Orientation (spatial): R = Rx(ax) Ry(ay) Rz(az) maps body-frame vectors to the bearing frame. Ring
// tilts are small (mrad); the cage keeps its full pose (its pockets are not symmetric).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "contact/laws/viscosity.hpp"
#include "contact/segments/ball_segments.hpp"
#include "contact/segments/drag_segments.hpp"
#include "contact/segments/roller_flange_segment.hpp"
#include "contact/segments/roller_pocket_segment.hpp"
#include "contact/segments/roller_segments.hpp"
#include "contact/segments/roller_slice_segment.hpp"
#include "io/scene/scene.hpp"
#include "solver/bearing/internal_springs.hpp"
#include "solver/bearing/marker.hpp"
#include "solver/bearing/nodes.hpp"

namespace raceway::bearing {

/// Generalized coordinates of a body: the full spatial set; Body::slot[c] is the state index of
/// coordinate c or -1 (not a state). Angles: ring tilts (sax, say) or the cage's Cardan angles.
/// Angular velocities: balls and spatial rollers in the bearing frame; rings (swx, swy) tilt rates
/// and swz the spin about the ring's axis; the cage in its own frame. A spatial roller's angles are
/// sax, say: the direction of its axis R e_z, R = Rx(ax) Ry(ay) (its angle about its own axis, saz
/// of R = Rx Ry Rz, is a state only with a roller's own defect in the scene). A planar body uses sx, sy, saz, svx, svy, swz.
enum Coordinate : int { sx = 0, sy, sz, sax, say, saz, svx, svy, svz, swx, swy, swz };
inline constexpr int coordinate_count = 12;

enum class VariableClass { position, angle, velocity, angular_velocity };
enum class BodyKind { inner_ring, outer_ring, cage, rolling_element };

/// One rigid body. Its degrees of freedom are the coordinates with a slot (the mask).
struct Body {
  std::string name;
  BodyKind kind = BodyKind::rolling_element;
  int index = 0;                  ///< rolling-element number, 0 for the others
  double mass = 0;                ///< kg
  double axial_inertia = 0;       ///< kg m^2 about the body's own (bearing-parallel) axis
  double transverse_inertia = 0;  ///< kg m^2 about a diameter (spatial bodies)
  std::array<int, coordinate_count> slot{-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1};
  int offset = 0, size = 0;       ///< contiguous block of this body's states
  /// Rings: motion, drive, loads, support (in the model's own parameters, never the scene's).
  const scene::RingSpec* ring = nullptr;
  /// A ball whose orientation is a state (a ball's own defect turns with it): the Cardan angles
  /// sax, say, saz of R = Rx Ry Rz, which are a spatial roller's axis angles otherwise.
  bool ball_orientation = false;
  /// A spatial roller: its axis angles sax, say are states.
  bool is_roller_axis() const { return kind == BodyKind::rolling_element && slot[3] >= 0 && !ball_orientation; }
  /// A spatial roller whose angle about its own axis is a state too (saz: a roller's own defect turns with it).
  bool has_roller_spin_angle() const { return is_roller_axis() && slot[5] >= 0; }
  bool has_states() const { return size > 0; }
  bool has(Coordinate c) const { return slot[c] >= 0; }
};

/// The closed set of segment kinds (each is one dataset group in the output, in this order).
enum class SegmentKind {
  roller_inner_race, roller_outer_race, cage_bar_front, cage_bar_rear,
  ball_inner_groove, ball_outer_groove, ball_pocket, cage_land, cage_bridge, outer_ring_mode,
  roller_inner_slice, roller_outer_slice, roller_flange,  ///< spatial roller bearings: race slices, roller end on a rib
  ball_drag, cage_churning  ///< ball bearings in an oil-air mixture: a ball's drag, the cage's churning moment
};
inline constexpr int segment_kind_count = 15;
const char* segment_kind_name(SegmentKind k);

/// The laws an element can evaluate, with their parameters: the contact laws of contact/segments
/// and the internal springs of the flexible parts (solver/bearing/internal_springs.hpp).
/// Dispatched once per element evaluation by std::visit: a jump table, no virtual call per contact.
using SegmentLaw = std::variant<contact::RollerRaceSegment, contact::CageBarSegment, contact::CageLandSegment,
                                contact::BallGrooveSegment, contact::BallPocketSegment, contact::CageLandSegment3,
                                CageBridgeSpring, RingModeSpring, contact::RollerSliceSegment,
                                contact::RollerPocketBarSegment, contact::RollerFlangeSegment,
                                contact::BallDragSegment, contact::CageChurningSegment>;

/// An element: a contact or an internal spring between two markers (A, B as in contact/segments),
/// with its law in Model::laws. `body_a`, `body_b`: the rigid bodies the markers move with (for
/// start-up, diagnostics and the cut contacts, which attach to body centres only).
struct Segment {
  SegmentKind kind;
  int body_a, body_b;
  int law;      ///< index into Model::laws (segments of one kind often share one)
  int element;  ///< rolling element it belongs to, -1 for cage-land
  std::string name;
  int marker_a = -1, marker_b = -1;  ///< indices into Model::markers (build_model fills body centres)
};

/// What the model copies from the scene at build time: the model holds no scene.
struct ModelParameters {
  std::string scene_name, source;
  scene::BearingGeometry bearing;
  scene::CageSpec cage;
  scene::RingSpec inner_ring, outer_ring;
  scene::CarrierSpec carrier;
  scene::SolverSpec solver;
  scene::ContactSpec ball_race, ball_cage;  ///< for the model's description
};

/// The oil's viscosity at the thermal network's oil temperature (a [thermal] section and a lubricant
/// given by its data sheet): density x Walther's kinematic viscosity. The ball-groove contacts take it
/// (element_evaluation.hpp: law_at_oil_temperature). state < 0: none, the laws keep the scene's.
struct OilViscosity {
  int state = -1;  ///< the oil's temperature
  contact::WaltherConstants walther;
  double density = 0;  ///< kg/m^3
  /// Pa s at z, or `otherwise` where the temperature is not set yet (a seating's state, 0 K).
  double at(const double* z, double otherwise) const {
    const double t = z[state];
    return t > 0 ? density * contact::walther_viscosity(walther, t) : otherwise;
  }
};

struct Model {
  /// The scene's values the model and its dynamics read after the build. Shared and immutable, so
  /// Body::ring stays valid when a model is moved or copied.
  std::shared_ptr<const ModelParameters> parameters;
  scene::ModelKind kind = scene::ModelKind::planar;  ///< the space: planar or spatial dynamics
  scene::BearingType bearing_type = scene::BearingType::cylindrical_roller;
  /// Rigid bodies: inner ring, outer ring, cage, rolling elements (in that order, always).
  std::vector<Body> bodies;
  int inner_ring = 0, outer_ring = 1, cage = 2, first_element = 3;
  /// Blocks of coordinates that are not rigid bodies (a flexible ring's modes, a bridge's bending):
  /// each knows its states, rates, own Jacobian terms, energy and start (nodes.hpp). Their states
  /// are in the border, placed where their builder step adds them.
  std::vector<std::shared_ptr<const Node>> nodes;
  /// Where elements attach: a body's centre, or a marker kind of a flexible part (marker.hpp).
  std::vector<Marker> markers;
  int element_count = 0;
  int state_size = 0;
  int border_size = 0;  ///< states of rings, cage and nodes; rolling-element blocks follow
  int block_size = 0;   ///< states per rolling element
  std::vector<VariableClass> state_class;
  std::vector<std::string> state_name;
  std::vector<SegmentLaw> laws;
  std::vector<Segment> segments;
  /// Rows whose rate follows a body's acceleration (a relative coordinate's): when a contact's
  /// wrench derivative moves body b's rate of `coordinate`, row `row` gets factor times it.
  struct RateFollower {
    int body, coordinate, row;
    double factor;
  };
  std::vector<RateFollower> rate_followers;

  // Geometry, kept for start-up, output and diagnostics.
  double pitch_radius = 0, element_radius = 0;  ///< element_radius: the nominal one
  /// A diameter scatter: each ball's or roller's radius (element k; a tapered roller's at its middle);
  /// empty: every rolling element nominal.
  std::vector<double> element_radii;
  /// The radius of rolling element k.
  double radius_of_element(int k) const { return element_radii.empty() ? element_radius : element_radii[std::size_t(k)]; }
  double inner_race_radius = 0, outer_race_radius = 0;  ///< planar: race radii
  double nominal_contact_angle = 0;                     ///< rad (spatial): 0 deep groove, the arc angle four-point
  int arcs_per_ring = 1;                                ///< 2 for a four-point bearing
  double cone_angle = 0, cup_angle = 0;                 ///< rad, tapered roller bearings: the raceways' angles
  double gravity = 0;                                   ///< m/s^2 along -y
  const char* element_group = "rollers";                ///< output group of the rolling elements
  /// Spatial roller bearings: the planar model of the same scene (the spatial one restricted to the
  /// plane), whose seating starts the spatial one (spatial_roller_startup.cpp).
  std::shared_ptr<const Model> planar_restriction;
  /// With a thermal network and a lubricant's data sheet: the viscosity the ball-groove contacts take.
  OilViscosity oil_viscosity;

  /// [solver] element_velocity_frame = "orbital" (ball and planar roller bearings): a rolling element's
  /// svx, svy hold (v_r, v_theta) in its orbital frame (orbital_frame.hpp); kinematics() and
  /// planar_kinematics() give the bearing frame's.
  bool orbital_velocities = false;
  bool has_orbital_velocity(const Body& b) const { return orbital_velocities && b.kind == BodyKind::rolling_element; }
  /// Sets body b's centre velocity, given in the bearing frame, in z (in the frame of its states).
  void set_velocity(int b, const contact::Vec3& v, double* z) const;
  /// Body b's centre acceleration in the bearing frame from its states' rates zdot at z.
  contact::Vec3 acceleration(int b, const double* z, const double* zdot) const;

  const ModelParameters& params() const { return *parameters; }
  template <class Law>
  const Law& law(const Segment& s) const { return std::get<Law>(laws[static_cast<std::size_t>(s.law)]); }
  /// The first segment of a kind, or nullptr.
  const Segment* first_segment(SegmentKind k) const;
  /// Adds a marker; returns its index. (build_model adds a body-centre marker per body at the end and
  /// attaches every element that names no marker to its bodies' centres.)
  int add_marker(Marker marker);
  /// Adds a node (its states already added with add_state) and gives it its force slots; returns its index.
  int add_node(std::shared_ptr<Node> node);
  /// Generalized-force slots of all nodes (Loads::node).
  int node_force_count() const;
  /// Planning identity of node n for the scheduler (after the bodies').
  int node_planning_id(int n) const { return static_cast<int>(bodies.size()) + n; }

  /// Absolute tolerance per state from the scene, or from physical scales where the scene is silent.
  std::vector<double> absolute_tolerance() const;
  /// Planar kinematics of body b at (t, z): x, y, rotation about z and rates; the rest prescribed.
  contact::PlanarKinematics planar_kinematics(int b, double t, const double* z) const;
  /// Spatial kinematics of body b at (t, z): states from z, the rest prescribed.
  contact::SpatialKinematics kinematics(int b, double t, const double* z) const;
  /// Spin of a ring about its own axis at (t, z) [rad/s].
  double ring_spin(int b, double t, const double* z) const;
  /// Kinematic (epicyclic) cage speed for the rings' speeds at t [rad/s]: planar from the race
  /// radii, spatial at the nominal contact angle (seed 001 eq. 5-6).
  double epicyclic_cage_speed(double t) const;
  /// Spatial: the same at a given contact angle: the cage speed of balls rolling at that angle.
  double epicyclic_cage_speed(double t, double contact_angle) const;
  /// The model explained: bodies, states, segments, laws and the reasons (raceway check).
  std::string describe() const;
  std::string (*describer)(const Model&) = nullptr;  ///< its builder's description

  /// kinematics() computed (KinematicsMemo keeps what it returns).
  contact::SpatialKinematics body_kinematics(int b, double t, const double* z) const;
};

/// While one lives on a thread, Model::kinematics of its model on that thread at its t and its z
/// (the same pointer) computes each body's kinematics once and returns them again: a right-hand
/// side asks for a body's kinematics once per element it touches (a ring's and the cage's once per
/// rolling element, a ball's once per contact), all at one (t, z). The values z points to and the
/// model must not change while one lives. A hit returns the bits the call would. Each starts empty
/// (a nested one too, and the outer one is empty again after it), except a scope opened with a
/// `copy_of`: z then holds a copy of the values copy_of points to (Equations::rhs' context), and
/// the scope answers at either pointer; nested in a scope of the same model and t at copy_of itself
/// (the output's sample: its right-hand side, then its rows at the caller's z), it continues that
/// scope's entries and leaves them to it.
class KinematicsMemo {
 public:
  KinematicsMemo(const Model& model, double t, const double* z, const double* copy_of = nullptr);
  ~KinematicsMemo();
  KinematicsMemo(const KinematicsMemo&) = delete;
  KinematicsMemo& operator=(const KinematicsMemo&) = delete;

 private:
  const Model* previous_model_;
  const double* previous_z_;
  const double* previous_copy_of_;
  double previous_t_;
  bool continues_;
};

/// A column of an element's Jacobian: a state marker A's kinematics depend on, then marker B's (a
/// body's in coordinate order). The Jacobian tasks (whole or in parts) and the assembly read this
/// one order.
struct SegmentColumn {
  int body = -1;        ///< the body whose state it is (or whose frame the marker moves with)
  int coordinate = -1;  ///< the coordinate (Coordinate) of that body
  int state = -1;       ///< its index in the state vector
  bool on_a = true;     ///< marker A's (else B's)
  int also = -1;        ///< a second state the same column stands for (a relative coordinate's carrier), or -1
};
/// The columns of element seg: marker A's, then marker B's.
std::vector<SegmentColumn> segment_columns(const Model& m, const Segment& seg);

/// Builds the model of the scene's bearing type (the builder registry, builders.cpp). Throws
/// std::runtime_error naming the scene key when something cannot be built.
Model build_model(const scene::Scene& scene);
struct ModelBuilder;
/// The same with a given builder (a variant of a bearing type, or a test's).
Model build_model(const scene::Scene& scene, const ModelBuilder& builder);

/// Absolute tolerances per state from physical scales, where the scene's [solver] section gives
/// none: positions rtol times the pitch radius, angles rtol, velocities rtol times the driven ring's
/// surface speed at the pitch radius, angular velocities rtol times a rolling element's rolling spin.
std::vector<double> physical_absolute_tolerance(const ModelParameters& p, const std::vector<VariableClass>& state_class,
                                                double pitch_radius, double rolling_element_radius);

/// R = Rx(ax) Ry(ay) Rz(az).
contact::Mat3 cardan_rotation(double ax, double ay, double az);
/// cardan_rotation(ax, ay, az) of the angles last asked for in slot `slot`, on this thread: a
/// right-hand side asks for a body's kinematics once per segment and traction part (a roller: once
/// per slice), each time with the same angles, and the Jacobian's assembly a roller's axis once per
/// column. The rotation is a function of the three angles alone, so a hit (the same bits) returns
/// exactly what the call would. Slots: 2 b for body b's rotation in its kinematics, 2 b + 1 for a
/// second one of the same body (a ring's tilt alone, a roller's axis without its spin angle).
const contact::Mat3& memo_rotation(std::size_t slot, double ax, double ay, double az);
/// Rates of the Cardan x-y-z angles from a body-frame angular velocity (singular at ay = +-90 deg,
/// far beyond any cage tilt).
contact::Vec3 cardan_rates(double ay, double az, const contact::Vec3& body_angular_velocity);

/// The steps of one bearing type's builder. build_model runs them in the order every model has:
/// rings, cage (together the border, with the nodes of their flexible parts), rolling elements
/// (equal blocks), elements. The builder is chosen by the bearing type (builders.cpp), the
/// dynamics by the space (planar or spatial), separately.
struct ModelBuilder {
  void (*check)(const scene::Scene&);          ///< throws when the builder cannot build this scene (its space)
  void (*geometry)(Model&, const scene::Scene&);  ///< kind, element count, radii
  void (*rings)(Model&, const scene::Scene&);
  void (*cage)(Model&, const scene::Scene&);
  void (*rolling_elements)(Model&, const scene::Scene&);
  void (*segments)(Model&, const scene::Scene&);  ///< laws (derived constants once, here) and segments
  std::string (*describe)(const Model&);       ///< Model::describe
};
const ModelBuilder& roller_model_builder();  ///< planar cylindrical roller bearing (roller_model.cpp)
const ModelBuilder& ball_model_builder();    ///< spatial ball bearing (ball_model.cpp)
const ModelBuilder& spatial_roller_model_builder();  ///< spatial cylindrical roller bearing (spatial_roller_model.cpp)
const ModelBuilder& tapered_roller_model_builder();  ///< spatial tapered roller bearing (tapered_roller_model.cpp)
/// The builder of a bearing type in a space (the registry: builders.cpp).
const ModelBuilder& builder_for(scene::BearingType type, scene::ModelKind space);

/// A ring of a spatial model (ball_model.cpp): translation, axial position, tilt and spin as its
/// motion makes them states (positions, then velocities); inertias of a hollow cylinder unless given.
void add_spatial_ring(Model& m, BodyKind kind, const char* name, const scene::RingSpec& spec, double r_in,
                      double r_out, double width, double density);

/// The largest magnitude a time function takes (its table's values; it interpolates linearly).
double max_abs(const scene::TimeFunction& f);
/// Mass of a ring-shaped body (hollow cylinder) [kg].
double annulus_mass(double density, double r_in, double r_out, double width);
/// A new state of body b for coordinate c (named "<body>.<what>", class cls); used by the builders.
void add_state(Model& m, Body& b, Coordinate c, VariableClass cls, const char* what);
/// A new state named `name` of class cls that belongs to no body (a node's); returns its index.
int add_state(Model& m, VariableClass cls, const std::string& name);
/// Three states of body b: coordinates first, first + 1, first + 2 (x, y, z of a vector).
void add_states(Model& m, Body& b, Coordinate first, VariableClass cls, const std::array<const char*, 3>& what);
/// The scene's rolling elements: equal bodies "<name>[k]" whose states `add_states` adds (positions
/// before velocities), each one contiguous block.
void add_rolling_elements(Model& m, const char* name, double mass, double axial_inertia, double transverse_inertia,
                          void (*add_states)(Model&, Body&));
/// A spatial roller's states: position, its axis's two angles, velocity, angular velocity (11); with
/// spin_angle (a roller's own defect in the scene) its angle about its own axis too, after the axis's
/// angles (12: R = Rx(ax) Ry(ay) Rz(az), the roller's frame turning with it).
void (*spatial_roller_states(bool spin_angle))(Model&, Body&);
/// Roller bearings with a diameter scatter ([bearing] roller_diameter_deviations): each roller's
/// radius, roller_diameter / 2 plus half its deviation, into m.element_radii (left empty without one).
void set_roller_radii(Model& m, const scene::BearingGeometry& g);
/// A diameter scatter's rollers (m.element_radii): each one's mass and inertias from its own sections,
/// every section's radius grown by the roller's radius less the nominal one (a frustum of end radii
/// r_small, r_large and the given length; a cylinder's are equal). Planar rollers (no transverse
/// inertia) keep none. Nothing without a scatter.
void scale_scattered_rollers(Model& m, double nominal_mass, double r_small, double r_large, double length);
/// `raceway check`'s line for the rollers' diameters, each deviation in micrometres; empty without a scatter.
std::string describe_roller_diameters(const Model& m);

/// A roller's lubricated line contact (seed 003's films): the scene's lubricant over a contact of
/// `length`, fully flooded up to a gap of 2 % of the roller radius (the films' load there is below
/// 1e-3 of a loaded contact's).
contact::LineFilm line_film(const scene::Scene& scene, double e_star, double reduced_radius, double length,
                            double roller_radius);
/// The EHD film of a roller-race line contact (the planar race, or one slice of a spatial roller)
/// where the scene's roller_race normal law is "moes_ehd"; none otherwise. Its Palmgren stiffness,
/// largest approach and damping are the dry contact's; with traction = "ehd" the Couette friction
/// saturates at a slide-to-roll ratio of 5 %.
std::optional<contact::EhdRaceFilm> roller_race_film(const scene::Scene& scene, const contact::LineFilm& film,
                                                     double stiffness, double max_approach, double damping_factor);

}  // namespace raceway::bearing
