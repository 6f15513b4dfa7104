// What each element law is, said once: its space follows from its evaluate. A law evaluated on two
// markers' planar kinematics is of the line family (contact::SegmentResult, the line diagnostics
// table); one evaluated on spatial kinematics of the point family (contact::SpatialSegmentResult,
// the point table). The equations, the output writer and the diagnostics read these traits; no
// list of law types is written anywhere else.
#pragma once

#include <cstddef>
#include <type_traits>
#include <variant>

#include "contact/segments/diagnostic_fields.hpp"
#include "solver/bearing/model.hpp"

namespace raceway::bearing {

/// A law of the line family: evaluated on planar kinematics.
template <class Law>
concept PlanarElementLaw = requires(const Law& law, const contact::PlanarKinematics& k) { evaluate(law, k, k); };

/// The diagnostics table of a law's family.
template <class Law>
constexpr const auto& diagnostic_fields_of() {
  if constexpr (PlanarElementLaw<Law>)
    return contact::line_diagnostic_fields;
  else
    return contact::point_diagnostic_fields;
}

/// Whether an element's law is of the line family (planar kinematics, line diagnostics).
inline bool is_planar_element(const SegmentLaw& law) {
  return std::visit([](const auto& l) { return PlanarElementLaw<std::decay_t<decltype(l)>>; }, law);
}

/// The number of diagnostics an element's law writes (its family's table).
inline std::size_t diagnostic_count(const SegmentLaw& law) {
  return std::visit([](const auto& l) { return diagnostic_fields_of<std::decay_t<decltype(l)>>().size(); }, law);
}

/// The position of a named diagnostic in an element law's family table.
template <class Law>
constexpr int diagnostic_index(const char* name) {
  return contact::field_index(diagnostic_fields_of<Law>(), name);
}

}  // namespace raceway::bearing
