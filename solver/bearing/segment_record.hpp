// One segment evaluation as a flat record of doubles: what a contact task returns to the rank that
// sums the equations (scheduler tasks exchange flat records). The layout is the same for every
// segment family:
//
//   [ wrench on A: force x y z, moment x y z | wrench on B: the same | diagnostics | valid ]
//
// forces and moments at the bodies' centres in the bearing frame (a planar family fills force x, y
// and moment z); the diagnostics are the family's field table (contact/segments/diagnostic_fields.hpp)
// in table order, the rest of the slots zero; valid is 1 or 0 (the law left its valid range).
// A Jacobian record is the same record followed by one 12-row column of d(wrench on A, wrench on
// B)/d(state) per state of body A, then of body B.
#pragma once

#include <algorithm>
#include <span>

#include "contact/segments/diagnostic_fields.hpp"

namespace raceway::bearing {

struct SegmentRecord {
  static constexpr int on_a = 0;
  static constexpr int on_b = 6;
  static constexpr int wrench_rows = 12;  ///< wrench on A (6), on B (6)
  static constexpr int diagnostics = 12;
  static constexpr int max_diagnostics = std::max(contact::diagnostics_count, contact::point_diagnostics_count);
  static constexpr int valid = diagnostics + max_diagnostics;
  static constexpr int size = valid + 1;
};

/// Offsets of named diagnostics within a family's block (the same in both families).
inline constexpr int approach_field = contact::field_index(contact::line_diagnostic_fields, "approach");
inline constexpr int normal_force_field = contact::field_index(contact::line_diagnostic_fields, "normal_force");
static_assert(approach_field == contact::field_index(contact::point_diagnostic_fields, "approach"));
static_assert(normal_force_field == contact::field_index(contact::point_diagnostic_fields, "normal_force"));

/// Writes the diagnostics of a result by its family's field table.
template <class Table, class Diagnostics>
void write_diagnostics(const Table& fields, const Diagnostics& d, double* rec) {
  for (std::size_t i = 0; i < fields.size(); ++i) rec[SegmentRecord::diagnostics + i] = d.*(fields[i].member);
}

inline void write_result(const contact::SegmentResult& r, std::span<double> rec) {
  std::fill(rec.begin(), rec.begin() + SegmentRecord::size, 0.0);
  rec[SegmentRecord::on_a + 0] = r.on_a.fx;
  rec[SegmentRecord::on_a + 1] = r.on_a.fy;
  rec[SegmentRecord::on_a + 5] = r.on_a.mz;
  rec[SegmentRecord::on_b + 0] = r.on_b.fx;
  rec[SegmentRecord::on_b + 1] = r.on_b.fy;
  rec[SegmentRecord::on_b + 5] = r.on_b.mz;
  write_diagnostics(contact::line_diagnostic_fields, r.diagnostics, rec.data());
  rec[SegmentRecord::valid] = r.valid ? 1.0 : 0.0;
}

/// Always inlined: in the right-hand side's evaluation of every law (equations.cpp) GCC's growth limits
/// otherwise leave it out of line as soon as the evaluations grow a little, and a call per element
/// costs more than its stores (6309 R3: 2.6 M instructions per revolution).
[[gnu::always_inline]] inline void write_result(const contact::SpatialSegmentResult& r, std::span<double> rec) {
  std::fill(rec.begin() + SegmentRecord::diagnostics, rec.begin() + SegmentRecord::size, 0.0);
  for (int i = 0; i < 3; ++i) {
    rec[SegmentRecord::on_a + i] = r.on_a.force[i];
    rec[SegmentRecord::on_a + 3 + i] = r.on_a.moment[i];
    rec[SegmentRecord::on_b + i] = r.on_b.force[i];
    rec[SegmentRecord::on_b + 3 + i] = r.on_b.moment[i];
  }
  write_diagnostics(contact::point_diagnostic_fields, r.diagnostics, rec.data());
  rec[SegmentRecord::valid] = r.valid ? 1.0 : 0.0;
}

/// One Jacobian column: (r - base) / h by forward differences, times inv = 1 / h.
inline void write_difference(const contact::SegmentResult& r, const contact::SegmentResult& base, double inv,
                             double* out) {
  std::fill(out, out + SegmentRecord::wrench_rows, 0.0);
  out[0] = (r.on_a.fx - base.on_a.fx) * inv;
  out[1] = (r.on_a.fy - base.on_a.fy) * inv;
  out[5] = (r.on_a.mz - base.on_a.mz) * inv;
  out[6] = (r.on_b.fx - base.on_b.fx) * inv;
  out[7] = (r.on_b.fy - base.on_b.fy) * inv;
  out[11] = (r.on_b.mz - base.on_b.mz) * inv;
}

inline void write_difference(const contact::SpatialSegmentResult& r, const contact::SpatialSegmentResult& base,
                             double inv, double* out) {
  for (int i = 0; i < 3; ++i) {
    out[i] = (r.on_a.force[i] - base.on_a.force[i]) * inv;
    out[3 + i] = (r.on_a.moment[i] - base.on_a.moment[i]) * inv;
    out[6 + i] = (r.on_b.force[i] - base.on_b.force[i]) * inv;
    out[9 + i] = (r.on_b.moment[i] - base.on_b.moment[i]) * inv;
  }
}

/// Adds the wrench at rec (force 3, moment 3) to w.
inline void add_wrench(contact::SpatialWrench& w, const double* rec) {
  for (int i = 0; i < 3; ++i) w.force[i] += rec[i], w.moment[i] += rec[3 + i];
}

}  // namespace raceway::bearing
