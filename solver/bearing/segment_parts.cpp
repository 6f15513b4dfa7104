// Segments cut into sub-tasks: a heavy contact's work shared out over several tasks (and so
// ranks), with results that do not depend on who computes what.
//
// Which segments: a ball-groove contact whose traction grid has more than one block
// (contact::traction_block_count: the grid's fixed decomposition, a function of the grid alone).
// Every such segment is always evaluated as its parts, at any rank count, so the arithmetic is the
// same whether the parts run on one rank or on many; the plan (scheduler/plan.hpp) only decides
// where they run.
//
//   right-hand side: part k computes traction block k at the segment's kinematics; parts 0 and 1
//     also hand on the contact prepared up to its traction (contact::prepare: geometry, normal
//     force, film, rolling resistance; its doubles split between their two records). The master
//     only adds the blocks in block order (contact::sum_traction_blocks, as evaluate does inside)
//     and completes the contact from the prepared doubles (contact::finish_groove_contact, a few
//     dozen flops, no law): bitwise the result of contact::evaluate;
//   Jacobian: the segment's evaluations (the base point, then one per state of its two bodies) go
//     round the parts (evaluation e to part e mod parts); a part returns its evaluations' wrenches;
//     the master forms the columns (r - base) / h exactly as an uncut segment's task does.
//
// A part's rhs record: [force_x, force_y, spin_moment, power_loss of its block, then (part 0) the
// first prepared_share doubles of the prepared contact, (part 1) the rest, 0 ...]. Jacobian:
// [valid: the AND over the part's evaluations, then per evaluation in order: the base result's
// whole record (evaluation 0, part 0) or the perturbed wrench itself (not yet the difference), 0
// ...]. Each part fills only the front of its record (segment_part_record_size): the executor sends
// no more between ranks.
#include <algorithm>
#include <array>
#include <optional>

#include "solver/bearing/equations.hpp"

namespace raceway::bearing {

namespace {

/// Segment-major records from task-major ones (`size` doubles each): an uncut segment's record is
/// its task's; for a cut one, combine(s, its parts' records, its record) fills it.
template <class Combine>
void gather_segments(const std::vector<int>& first_task, const std::vector<int>& parts, const std::vector<double>& tasks,
                     std::size_t size, std::vector<double>& segments, Combine combine) {
  segments.resize(first_task.size() * size);
  for (std::size_t s = 0; s < first_task.size(); ++s) {
    const double* first = tasks.data() + static_cast<std::size_t>(first_task[s]) * size;
    double* out = segments.data() + s * size;
    if (parts[s] == 1)
      std::copy_n(first, size, out);
    else
      combine(s, first, out);
  }
}

// Where a part's record holds its share of the prepared contact, and how much it holds: a cut
// segment has at least two parts, and two records hold it whole.
constexpr int traction_size = 4;
constexpr int prepared_share = SegmentRecord::size - traction_size;
static_assert(2 * prepared_share >= contact::PreparedGrooveContact::size);

/// The segment's ball-groove law at the oil's temperature in z (law_at_oil_temperature; a copy in `warm`).
const contact::BallGrooveSegment& groove_law(const Model& m, const Segment& seg, const double* z,
                                             std::optional<contact::BallGrooveSegment>& warm) {
  return law_at_oil_temperature(m, std::get<contact::BallGrooveSegment>(m.laws[static_cast<std::size_t>(seg.law)]), z, warm);
}

}  // namespace

namespace {

/// Evaluations of a cut segment's Jacobian (the base point and one per column) that part `part`
/// of `parts` makes: e = part, part + parts, ...
int part_evaluations(int evaluations, int part, int parts) { return (evaluations - part + parts - 1) / parts; }

/// Where evaluation i (0-based among the part's own) starts in a part's Jacobian record.
std::size_t jacobian_part_offset(int part, int i) {
  if (part != 0) return 1 + static_cast<std::size_t>(SegmentRecord::wrench_rows * i);
  return i == 0 ? 1 : 1 + SegmentRecord::size + static_cast<std::size_t>(SegmentRecord::wrench_rows * (i - 1));
}

}  // namespace

int Equations::segment_part_record_size(scheduler::Phase phase, int s, int part) const {
  const int parts = parts_[static_cast<std::size_t>(s)];
  if (phase == scheduler::Phase::rhs)
    return traction_size + (part == 0 ? prepared_share : part == 1 ? contact::PreparedGrooveContact::size - prepared_share : 0);
  const int evaluations = 1 + static_cast<int>(shapes_[static_cast<std::size_t>(s)].columns.size());
  const int n = part_evaluations(evaluations, part, parts);
  return static_cast<int>(jacobian_part_offset(part, n));
}

int segment_part_count(const SegmentLaw& law) {
  if (const auto* groove = std::get_if<contact::BallGrooveSegment>(&law)) return contact::traction_block_count(*groove);
  return 1;
}

void Equations::rhs_part(const double* context, int s, int part, std::span<double> rec) const {
  const double t = context[0];
  const double* z = context + 1;
  const Segment& seg = model_.segments[static_cast<std::size_t>(s)];
  contact::PreparedGrooveContact prepared;
  // Mode 1 (the seating): the ring at rest.
  const auto [ring, ball] = context[1 + model_.state_size] != 0.0
                                ? groove_kinematics_at_rest(model_, seg, t, z)
                                : std::pair{marker_spatial(model_, model_.markers[static_cast<std::size_t>(seg.marker_a)], t, z),
                                            marker_spatial(model_, model_.markers[static_cast<std::size_t>(seg.marker_b)], t, z)};
  std::optional<contact::BallGrooveSegment> warm;
  const contact::TractionResult block = contact::evaluate_traction_block(groove_law(model_, seg, z, warm), ring, ball, part,
                                                                         part < 2 ? &prepared : nullptr);
  std::fill(rec.begin(), rec.end(), 0.0);
  rec[0] = block.force_x;
  rec[1] = block.force_y;
  rec[2] = block.spin_moment;
  rec[3] = block.power_loss;
  if (part < 2) {
    std::array<double, 2 * prepared_share> all{};
    prepared.write(all.data());
    const int share = segment_part_record_size(scheduler::Phase::rhs, s, part) - traction_size;
    std::copy_n(all.begin() + part * prepared_share, share, rec.begin() + traction_size);
  }
}

void Equations::combine_rhs_parts(std::vector<double>& records) {
  const std::size_t size = SegmentRecord::size;
  std::array<contact::TractionResult, contact::max_traction_blocks> blocks{};
  std::array<double, 2 * prepared_share> prepared{};
  gather_segments(first_task_, parts_, task_records_, size, records, [&](std::size_t s, const double* first, double* out) {
    const auto parts = static_cast<std::size_t>(parts_[s]);
    for (std::size_t k = 0; k < parts; ++k) {
      const double* rec = first + k * size;
      blocks[k] = {rec[0], rec[1], rec[2], rec[3]};
    }
    std::copy_n(first + traction_size, prepared_share, prepared.begin());
    std::copy_n(first + size + traction_size, prepared_share, prepared.begin() + prepared_share);
    const auto result = contact::finish_groove_contact(
        contact::PreparedGrooveContact::read(prepared.data()),
        contact::sum_traction_blocks(std::span<const contact::TractionResult>(blocks.data(), parts)));
    write_result(result, std::span<double>(out, size));
  });
}

void Equations::jacobian_part(const double* context, int s, int part, std::span<double> rec) const {
  const double t = context[0];
  const double* z = context + 1;
  const Segment& seg = model_.segments[static_cast<std::size_t>(s)];
  std::optional<contact::BallGrooveSegment> warm;
  const auto& law = groove_law(model_, seg, z, warm);
  const std::vector<SegmentColumn>& columns = shapes_[static_cast<std::size_t>(s)].columns;
  const Marker& ma = model_.markers[static_cast<std::size_t>(seg.marker_a)];
  const Marker& mb = model_.markers[static_cast<std::size_t>(seg.marker_b)];
  const auto ka = marker_spatial(model_, ma, t, z), kb = marker_spatial(model_, mb, t, z);
  std::fill(rec.begin(), rec.end(), 0.0);
  bool ok = true;
  std::vector<double> zp(z, z + model_.state_size);
  std::array<double, SegmentRecord::size> perturbed{};
  const int evaluations = 1 + static_cast<int>(columns.size());
  const int parts = parts_[static_cast<std::size_t>(s)];
  for (int e = part; e < evaluations; e += parts) {
    double* out = rec.data() + jacobian_part_offset(part, e / parts);
    if (e == 0) {
      const auto base = contact::evaluate(law, ka, kb);
      write_result(base, std::span<double>(out, SegmentRecord::size));
      ok = ok && base.valid;
      continue;
    }
    const SegmentColumn& c = columns[static_cast<std::size_t>(e - 1)];
    const auto j = static_cast<std::size_t>(c.state);
    zp[j] = z[j] + step_(c.state, z);
    const auto kp = marker_spatial(model_, c.on_a ? ma : mb, t, zp.data());
    const auto r = c.on_a ? contact::evaluate(law, kp, kb) : contact::evaluate(law, ka, kp);
    zp[j] = z[j];
    ok = ok && r.valid;
    write_result(r, perturbed);
    std::copy_n(perturbed.begin(), SegmentRecord::wrench_rows, out);
  }
  rec[0] = ok ? 1.0 : 0.0;
}

void Equations::combine_jacobian_parts(const double* z) {
  const auto size = static_cast<std::size_t>(jacobian_record_);
  gather_segments(first_task_, parts_, jac_task_records_, size, jac_records_, [&](std::size_t s, const double* first, double* out) {
    const int parts = parts_[s];
    // The base point is part 0's first evaluation.
    std::copy_n(first + jacobian_part_offset(0, 0), SegmentRecord::size, out);
    bool ok = true;
    for (int k = 0; k < parts; ++k) ok = ok && first[static_cast<std::size_t>(k) * size] != 0.0;
    const std::vector<SegmentColumn>& columns = shapes_[s].columns;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const std::size_t offset = SegmentRecord::size + SegmentRecord::wrench_rows * c;
      const int e = static_cast<int>(c) + 1;
      const double* r = first + static_cast<std::size_t>(e % parts) * size + jacobian_part_offset(e % parts, e / parts);
      // (r - base) / h as write_difference forms it for an uncut segment: the same bits.
      const double inv = 1.0 / step_(columns[c].state, z);
      for (int i = 0; i < SegmentRecord::wrench_rows; ++i) out[offset + static_cast<std::size_t>(i)] = (r[i] - out[i]) * inv;
    }
    out[SegmentRecord::valid] = ok ? 1.0 : 0.0;
  });
}

}  // namespace raceway::bearing
