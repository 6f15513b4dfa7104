// Markers: where an element attaches. A marker gives the kinematics of its point at (t, z), the
// state columns they depend on (the element's Jacobian columns), how a wrench on it becomes
// generalized forces (J^T f: a body's wrench, a node's forces) and how a wrench derivative on it
// enters the Jacobian's rows.
//
// The common marker, a body's centre, is a plain struct dispatched without a virtual call; every
// other kind (a bar riding on a flexible bridge, a point on a flexible rim, a test's toy) is a
// MarkerKind, an open interface: adding one edits neither the equations, the model, the dynamics
// nor the output writer.
#pragma once

#include <array>
#include <memory>
#include <variant>
#include <vector>

#include "contact/segments/ball_segments.hpp"
#include "contact/segments/roller_segments.hpp"
#include "solver/numerics/bordered_matrix.hpp"

namespace raceway::bearing {

struct Model;
struct Segment;
struct SegmentColumn;
class Equations;
class FiniteDifferenceSteps;
using Wrench = contact::SpatialWrench;

/// What the equations sum: a wrench per rigid body, generalized forces per node slot.
struct Loads {
  std::vector<Wrench> body;
  std::vector<double> node;
  void clear();
};

/// The equations' side of a Jacobian assembly, for markers that add rows.
struct JacobianAssembly {
  const Model& model;
  const Equations& equations;
  double t;
  const double* z;
  numerics::BorderedMatrix& jac;
  /// d(rates of body b)/d(state) from a wrench derivative dw on b (with its rate followers).
  void add_body_rate_derivative(int b, int state, const Wrench& dw) const;
};

/// Scratch a marker fills when it gives kinematics and reads when it moves the result's wrench
/// to its reference point (a rim point's displacement).
struct MarkerPoint {
  std::array<double, 4> offset{};
};

class MarkerKind {
 public:
  virtual ~MarkerKind() = default;
  /// The rigid body whose frame it moves with (diagnostics, start-up), or -1.
  virtual int body() const = 0;
  /// Its identity for the scheduler's graph (a body's or a node's: Model::node_planning_id).
  virtual int planning_id() const = 0;
  /// Planar kinematics at (t, z). `partner`: the other marker's kinematics (read where
  /// follows_partner()); `shift`: offsets of its shift columns (null: none); `point`: scratch.
  virtual contact::PlanarKinematics planar(const Model& m, double t, const double* z,
                                           const contact::PlanarKinematics& partner, const double* shift,
                                           MarkerPoint& point) const = 0;
  /// Spatial kinematics at (t, z), for elements of the point family (a ring in its housing).
  virtual contact::SpatialKinematics spatial(const Model&, double, const double*) const;
  /// Whether its point depends on the partner's position (then the Jacobian's columns re-evaluate
  /// both markers).
  virtual bool follows_partner() const { return false; }
  /// Moves a planar wrench on it from its point to its reference (the moment about its body's centre).
  virtual void to_reference(const MarkerPoint&, contact::PlanarWrench&) const {}
  /// The state columns its kinematics depend on, appended to `out`.
  virtual void columns(const Model& m, bool on_a, std::vector<SegmentColumn>& out) const = 0;
  /// Extra Jacobian columns after the elements' state columns (shifts of its point), their steps.
  virtual int shift_columns() const { return 0; }
  virtual double shift_step(const Model&, const FiniteDifferenceSteps&, int, const double*) const { return 0; }
  /// Adds the wrench `w` (force 3, moment 3) on it to the loads.
  virtual void scatter(const Model& m, const Segment& seg, bool on_a, const double* w, double t, const double* z,
                       Loads& loads) const = 0;
  /// The rows of a wrench derivative dw on it (with respect to `state`).
  virtual void add_rate_derivative(const JacobianAssembly& a, int state, const Wrench& dw) const = 0;
  /// Terms only it knows (its generalized forces' dependence on the geometry, its shift columns),
  /// after the element's columns have been assembled; rec is the element's Jacobian record.
  virtual void add_jacobian_terms(const JacobianAssembly&, const Segment&, const std::vector<SegmentColumn>&,
                                  const double*) const {}
};

/// A body's centre: the kinematics of the body (Model::planar_kinematics / kinematics).
struct BodyCentre {
  int body = 0;
};

using Marker = std::variant<BodyCentre, std::shared_ptr<const MarkerKind>>;

}  // namespace raceway::bearing

namespace raceway::bearing {

/// Body b's state columns in coordinate order (a body-centre marker's).
void add_body_columns(const Model& m, int b, bool on_a, std::vector<SegmentColumn>& out);
/// Spatial kinematics of a marker: a body's centre, or its kind's.
contact::SpatialKinematics marker_spatial(const Model& m, const Marker& marker, double t, const double* z);
/// Planar kinematics of a marker that does not follow its partner.
contact::PlanarKinematics marker_planar(const Model& m, const Marker& marker, double t, const double* z);
/// The planar kinematics of element seg's other marker than `on_a`'s.
contact::PlanarKinematics partner_planar(const Model& m, const Segment& seg, bool on_a, double t, const double* z);
/// A marker's rows of a wrench derivative.
void marker_add_rate_derivative(const Model& m, const Marker& marker, const JacobianAssembly& a, int state,
                                const Wrench& dw);
/// The rigid body a marker moves with, or -1.
int marker_body(const Marker& marker);

}  // namespace raceway::bearing
