// One element evaluated on its two markers, as a record (segment_record.hpp): the right-hand side's
// result and the Jacobian's finite differences. The common case, two body centres, is a plain
// call per side; a marker kind adds its own kinematics, and where its point follows the partner
// (a rim point follows the roller's azimuth) every column re-evaluates both sides.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "solver/bearing/body_dynamics.hpp"
#include "solver/bearing/element_traits.hpp"
#include "solver/bearing/marker.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/segment_record.hpp"

namespace raceway::bearing {

/// How an element's Jacobian is formed.
struct ElementShape {
  std::vector<SegmentColumn> columns;  ///< marker A's state columns, then marker B's
  int shift_a = 0, shift_b = 0;        ///< the markers' shift columns, after the state columns
  bool coupled = false;                ///< a marker follows its partner: every column re-evaluates both
  int record_columns() const { return static_cast<int>(columns.size()) + shift_a + shift_b; }
};
ElementShape element_shape(const Model& m, const Segment& seg);

namespace element_detail {

inline const MarkerKind* kind_of(const Marker& marker) {
  const auto* kind = std::get_if<std::shared_ptr<const MarkerKind>>(&marker);
  return kind ? kind->get() : nullptr;
}

inline contact::SpatialKinematics spatial_at(const Model& m, const Marker& marker, double t, const double* z) {
  if (const auto* centre = std::get_if<BodyCentre>(&marker)) return m.kinematics(centre->body, t, z);
  return std::get<std::shared_ptr<const MarkerKind>>(marker)->spatial(m, t, z);
}

/// Planar kinematics of both markers at (t, z) (a marker that follows its partner after it), with
/// shifts of their points, and the scratch each filled.
struct PlanarPair {
  contact::PlanarKinematics a, b;
  MarkerPoint point_a, point_b;
};
inline PlanarPair planar_pair(const Model& m, const Segment& seg, double t, const double* z, const double* shift_a,
                              const double* shift_b) {
  const Marker& ma = m.markers[static_cast<std::size_t>(seg.marker_a)];
  const Marker& mb = m.markers[static_cast<std::size_t>(seg.marker_b)];
  const MarkerKind* ka = kind_of(ma);
  const MarkerKind* kb = kind_of(mb);
  PlanarPair p;
  auto at = [&](const Marker& marker, const MarkerKind* kind, const contact::PlanarKinematics& partner,
                const double* shift, MarkerPoint& point) {
    return kind ? kind->planar(m, t, z, partner, shift, point)
                : m.planar_kinematics(std::get<BodyCentre>(marker).body, t, z);
  };
  if (ka && ka->follows_partner()) {
    p.b = at(mb, kb, contact::PlanarKinematics{}, shift_b, p.point_b);
    p.a = at(ma, ka, p.b, shift_a, p.point_a);
  } else {
    p.a = at(ma, ka, contact::PlanarKinematics{}, shift_a, p.point_a);
    p.b = at(mb, kb, p.a, shift_b, p.point_b);
  }
  return p;
}

/// The law on a pair, its wrenches moved to the markers' references.
template <class Law>
contact::SegmentResult evaluate_planar(const Model& m, const Law& law, const Segment& seg, const PlanarPair& p) {
  contact::SegmentResult r = evaluate(law, p.a, p.b);  // contact laws and internal springs alike
  if (const MarkerKind* k = kind_of(m.markers[static_cast<std::size_t>(seg.marker_a)])) k->to_reference(p.point_a, r.on_a);
  if (const MarkerKind* k = kind_of(m.markers[static_cast<std::size_t>(seg.marker_b)])) k->to_reference(p.point_b, r.on_b);
  return r;
}

/// A dry roller-cage bar between two body centres that stands clear of its roller by more than the
/// columns' position and angle steps can close (an angle's step moves the bar by at most twice the
/// pitch radius times it): every column's difference is then exactly zero, and the columns are
/// written as zeros without evaluating the law (bitwise what the differences give). The bars of a
/// pocket are clear of their roller most of the time.
template <class Law>
bool bar_stays_clear(const Model& m, const FiniteDifferenceSteps& step, const Law& law, const ElementShape& shape,
                     const double* z, double approach) {
  if constexpr (std::is_same_v<Law, contact::CageBarSegment>) {
    if (law.film || shape.coupled || shape.shift_a + shape.shift_b > 0 || !(approach < 0)) return false;
    double reach = 0;
    for (const SegmentColumn& c : shape.columns) {
      const VariableClass k = m.state_class[static_cast<std::size_t>(c.state)];
      if (k == VariableClass::position) reach += std::abs(step(c.state, z));
      if (k == VariableClass::angle) reach += 2.0 * law.pitch_radius * std::abs(step(c.state, z));
    }
    return approach < -2.0 * reach;
  } else {
    return false;
  }
}

/// A dry ball pocket between two body centres whose ball stands clear of the pocket by more than the
/// columns' steps can close: a position step moves the ball's centre off the pocket by at most the
/// step, a step of one of the Cardan angles turns the cage frame by that angle and so moves the
/// ball's centre in it by at most the angle times their distance (`cage`, `ball`: the markers at z).
/// Every column's wrench is then zero like the base's, the difference exactly zero, and the columns
/// are written as zeros without evaluating the law (bitwise what the differences give). A pocket is
/// clear of its ball most of the time.
template <class Law, class Result>
bool pocket_stays_clear(const Model& m, const FiniteDifferenceSteps& step, const Law& law, const Segment& seg,
                        const ElementShape& shape, const double* z, const contact::SpatialKinematics& cage,
                        const contact::SpatialKinematics& ball, const Result& base) {
  if constexpr (std::is_same_v<Law, contact::BallPocketSegment>) {
    const double approach = base.diagnostics.approach;
    if (law.film || shape.coupled || shape.shift_a + shape.shift_b > 0 || !(approach < 0)) return false;
    if (!std::holds_alternative<BodyCentre>(m.markers[static_cast<std::size_t>(seg.marker_a)]) ||
        !std::holds_alternative<BodyCentre>(m.markers[static_cast<std::size_t>(seg.marker_b)]))
      return false;
    const double arm = (ball.position - cage.position).norm();
    double reach = 0;
    for (const SegmentColumn& c : shape.columns) {
      const VariableClass k = m.state_class[static_cast<std::size_t>(c.state)];
      if (k == VariableClass::position) reach += std::abs(step(c.state, z));
      if (k == VariableClass::angle) reach += arm * std::abs(step(c.state, z));
    }
    return approach < -2.0 * reach;
  } else {
    return false;
  }
}

}  // namespace element_detail

/// The law at the thermal network's oil temperature: a ball-groove contact's lubricant viscosity
/// from Model::oil_viscosity (a copy in `warm`), every other law as it is.
/// Without a network (every shipped scene) nothing is copied or constructed.
template <class Law>
const Law& law_at_oil_temperature(const Model& m, const Law& law, const double* z, std::optional<Law>& warm) {
  if constexpr (std::is_same_v<Law, contact::BallGrooveSegment>) {
    if (m.oil_viscosity.state >= 0 && law.lubricant.viscosity > 0) {
      warm.emplace(law);
      warm->lubricant.viscosity = m.oil_viscosity.at(z, law.lubricant.viscosity);
      return *warm;
    }
  }
  return law;
}

template <class Law>
void write_element_result_of(const Model& m, const Law& law, const Segment& seg, double t, const double* z,
                             std::span<double> rec);

/// The element's result at (t, z).
template <class Law>
void write_element_result(const Model& m, const Law& law, const Segment& seg, double t, const double* z,
                          std::span<double> rec) {
  std::optional<Law> warm;
  write_element_result_of(m, law_at_oil_temperature(m, law, z, warm), seg, t, z, rec);
}

template <class Law>
void write_element_result_of(const Model& m, const Law& law, const Segment& seg, double t, const double* z,
                             std::span<double> rec) {
  if constexpr (PlanarElementLaw<Law>) {
    const Marker& ma = m.markers[static_cast<std::size_t>(seg.marker_a)];
    const Marker& mb = m.markers[static_cast<std::size_t>(seg.marker_b)];
    const auto* ca = std::get_if<BodyCentre>(&ma);
    const auto* cb = std::get_if<BodyCentre>(&mb);
    if (ca && cb) {  // two body centres, nearly every element: the law on the bodies' kinematics, no scratch
      write_result(evaluate(law, m.planar_kinematics(ca->body, t, z), m.planar_kinematics(cb->body, t, z)), rec);
      return;
    }
    const auto p = element_detail::planar_pair(m, seg, t, z, nullptr, nullptr);
    write_result(element_detail::evaluate_planar(m, law, seg, p), rec);
  } else {
    write_result(contact::evaluate(law, element_detail::spatial_at(m, m.markers[static_cast<std::size_t>(seg.marker_a)], t, z),
                                   element_detail::spatial_at(m, m.markers[static_cast<std::size_t>(seg.marker_b)], t, z)),
                 rec);
  }
}

/// The record of one element's Jacobian task: its result at (t, z), then one column of wrench
/// differences per column of its shape (forward differences).
template <class Law>
void write_element_jacobian(const Model& m, const FiniteDifferenceSteps& step, const Law& given, const Segment& seg,
                            const ElementShape& shape, double t, const double* z, std::span<double> rec) {
  using namespace element_detail;
  std::optional<Law> warm;  // the oil's temperature is no column: d/dT is left to Newton's iterations
  const Law& law = law_at_oil_temperature(m, given, z, warm);
  const Marker& ma = m.markers[static_cast<std::size_t>(seg.marker_a)];
  const Marker& mb = m.markers[static_cast<std::size_t>(seg.marker_b)];
  std::vector<double> zp(z, z + m.state_size);
  double* out = rec.data() + SegmentRecord::size;
  bool ok = true;
  if constexpr (PlanarElementLaw<Law>) {
    const PlanarPair at_z = planar_pair(m, seg, t, z, nullptr, nullptr);
    const contact::SegmentResult base = evaluate_planar(m, law, seg, at_z);
    ok = base.valid;
    // A bar clear of its roller: every difference is zero (bar_stays_clear).
    const bool clear = bar_stays_clear(m, step, law, shape, z, base.diagnostics.approach);
    for (const SegmentColumn& c : shape.columns) {
      if (clear) {
        out = std::fill_n(out, SegmentRecord::wrench_rows, 0.0);
        continue;
      }
      const auto j = static_cast<std::size_t>(c.state);
      const double h = step(c.state, z);
      zp[j] = z[j] + h;
      contact::SegmentResult r;
      if (shape.coupled) {
        r = evaluate_planar(m, law, seg, planar_pair(m, seg, t, zp.data(), nullptr, nullptr));
      } else {
        PlanarPair p = at_z;
        MarkerPoint& point = c.on_a ? p.point_a : p.point_b;
        const Marker& marker = c.on_a ? ma : mb;
        const MarkerKind* kind = kind_of(marker);
        const contact::PlanarKinematics moved =
            kind ? kind->planar(m, t, zp.data(), contact::PlanarKinematics{}, nullptr, point)
                 : m.planar_kinematics(std::get<BodyCentre>(marker).body, t, zp.data());
        (c.on_a ? p.a : p.b) = moved;
        r = evaluate_planar(m, law, seg, p);
      }
      zp[j] = z[j];
      ok = ok && r.valid;
      write_difference(r, base, 1.0 / h, out);
      out += SegmentRecord::wrench_rows;
    }
    // The shift columns: steps of the markers' points.
    for (int i = 0; i < shape.shift_a + shape.shift_b; ++i) {
      double shift[2 * SegmentRecord::wrench_rows] = {};
      const bool on_a = i < shape.shift_a;
      const int own = on_a ? i : i - shape.shift_a;
      const double h = kind_of(on_a ? ma : mb)->shift_step(m, step, own, z);
      shift[i] = h;
      const contact::SegmentResult r = evaluate_planar(
          m, law, seg, planar_pair(m, seg, t, z, shape.shift_a ? shift : nullptr, shape.shift_b ? shift + shape.shift_a : nullptr));
      ok = ok && r.valid;
      write_difference(r, base, 1.0 / h, out);
      out += SegmentRecord::wrench_rows;
    }
    write_result(base, rec);
  } else {
    const auto ka = spatial_at(m, ma, t, z), kb = spatial_at(m, mb, t, z);
    const auto base = contact::evaluate(law, ka, kb);
    ok = base.valid;
    const bool clear = pocket_stays_clear(m, step, law, seg, shape, z, ka, kb, base);  // every difference zero
    for (const SegmentColumn& c : shape.columns) {
      if (clear) {
        out = std::fill_n(out, SegmentRecord::wrench_rows, 0.0);
        continue;
      }
      const auto j = static_cast<std::size_t>(c.state);
      const double h = step(c.state, z);
      zp[j] = z[j] + h;
      const auto kp = spatial_at(m, c.on_a ? ma : mb, t, zp.data());
      const auto r = c.on_a ? contact::evaluate(law, kp, kb) : contact::evaluate(law, ka, kp);
      zp[j] = z[j];
      ok = ok && r.valid;
      write_difference(r, base, 1.0 / h, out);
      out += SegmentRecord::wrench_rows;
    }
    write_result(base, rec);
  }
  // The columns of states it does not depend on: zero (a task writes its whole record).
  std::fill(out, rec.data() + rec.size(), 0.0);
  rec[SegmentRecord::valid] = ok ? 1.0 : 0.0;
}

}  // namespace raceway::bearing
