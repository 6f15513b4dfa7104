#include "solver/run/pocket_steps.hpp"

#include <algorithm>
#include <string>

#include <fmt/format.h>

#include "solver/bearing/segment_record.hpp"

namespace raceway::run {

namespace {

constexpr int circumferential_field = contact::field_index(contact::point_diagnostic_fields, "circumferential_force");
constexpr const char* quantity_names[PocketSteps::quantities] = {"onsets", "peak_force_n", "impulse_n_s",
                                                                 "contact_time_s"};

std::string value_name(const std::string& what, std::size_t i) { return fmt::format("pocket_steps.{}.{}", what, i); }

}  // namespace

PocketSteps::PocketSteps(const bearing::Model& m) {
  for (std::size_t s = 0; s < m.segments.size(); ++s) {
    const bearing::Segment& seg = m.segments[s];
    const int side = seg.kind == bearing::SegmentKind::cage_bar_front ? 0
                     : seg.kind == bearing::SegmentKind::cage_bar_rear ? 1
                     : seg.kind == bearing::SegmentKind::ball_pocket   ? -1
                                                              : -2;
    if (side == -2 || seg.element < 0) continue;
    columns_.push_back({static_cast<int>(s), seg.element, side});
    pockets_ = std::max(pockets_, seg.element + 1);
  }
  if (!columns_.empty()) pockets_ = std::max(pockets_, m.element_count);
  cells_ = static_cast<std::size_t>(pockets_) * sides;
  last_force_.assign(cells_, 0.0);
  interval_.assign(quantities * cells_, 0.0);
}

void PocketSteps::sum_forces(const std::vector<double>& records, double* force) const {
  std::fill(force, force + cells_, 0.0);
  for (const Column& c : columns_) {
    const double* diagnostics =
        records.data() + static_cast<std::size_t>(c.segment) * bearing::SegmentRecord::size + bearing::SegmentRecord::diagnostics;
    const double fn = diagnostics[bearing::normal_force_field];
    if (!(fn > 0)) continue;
    const int side = c.side >= 0 ? c.side : (diagnostics[circumferential_field] < 0 ? 0 : 1);
    force[static_cast<std::size_t>(c.pocket) * sides + static_cast<std::size_t>(side)] += fn;
  }
}

void PocketSteps::observe(double t, const std::vector<double>& records) {
  if (!active()) return;
  pending_t_.push_back(t);
  pending_force_.resize(pending_force_.size() + cells_);
  sum_forces(records, pending_force_.data() + pending_force_.size() - cells_);
}

void PocketSteps::restart() {
  pending_t_.clear();
  pending_force_.clear();
}

void PocketSteps::take(double t, const double* force) {
  double* onsets = interval_.data();
  double* peak = onsets + cells_;
  double* impulse = peak + cells_;
  double* contact_time = impulse + cells_;
  if (seeded_ && !(t > last_t_)) return;  // no time has passed since the last evaluation taken
  const double dt = seeded_ ? t - last_t_ : 0.0;
  for (std::size_t i = 0; i < cells_; ++i) {
    const auto side = i % sides;
    const double a = last_force_[i], b = force[i];
    peak[i] = std::max(peak[i], b);
    total_[1][side] = std::max(total_[1][side], b);
    if (!seeded_) continue;  // the first evaluation of a run: nothing before it to pair with
    const double onset = a == 0.0 && b > 0.0 ? 1.0 : 0.0;
    const double j = 0.5 * (a + b) * dt;
    const double on = 0.5 * ((a > 0.0 ? 1.0 : 0.0) + (b > 0.0 ? 1.0 : 0.0)) * dt;
    onsets[i] += onset, impulse[i] += j, contact_time[i] += on;
    total_[0][side] += onset, total_[2][side] += j, total_[3][side] += on;
  }
  seeded_ = true;
  last_t_ = t;
  std::copy(force, force + cells_, last_force_.begin());
}

void PocketSteps::take_row(double t, std::vector<double>& row) {
  std::size_t n = 0;
  while (n < pending_t_.size() && pending_t_[n] <= t) {
    take(pending_t_[n], pending_force_.data() + n * cells_);
    ++n;
  }
  pending_t_.erase(pending_t_.begin(), pending_t_.begin() + static_cast<std::ptrdiff_t>(n));
  pending_force_.erase(pending_force_.begin(), pending_force_.begin() + static_cast<std::ptrdiff_t>(n * cells_));
  row.assign(interval_.begin(), interval_.end());
  std::fill(interval_.begin(), interval_.end(), 0.0);
}

void PocketSteps::save(Checkpoint& cp) const {
  if (!active()) return;
  cp.values["pocket_steps.seeded"] = seeded_ ? 1.0 : 0.0;
  cp.values["pocket_steps.last_time"] = last_t_;
  for (std::size_t i = 0; i < cells_; ++i) cp.values[value_name("last_force", i)] = last_force_[i];
  for (std::size_t q = 0; q < quantities; ++q)
    for (std::size_t s = 0; s < sides; ++s) cp.values[value_name(quantity_names[q], s)] = total_[q][s];
}

void PocketSteps::restore(const Checkpoint& cp) {
  if (!active()) return;
  restart();
  std::fill(interval_.begin(), interval_.end(), 0.0);
  const auto value = [&](const std::string& name) {
    const auto it = cp.values.find(name);
    return it == cp.values.end() ? 0.0 : it->second;
  };
  seeded_ = value("pocket_steps.seeded") != 0.0;
  last_t_ = value("pocket_steps.last_time");
  for (std::size_t i = 0; i < cells_; ++i) last_force_[i] = value(value_name("last_force", i));
  for (std::size_t q = 0; q < quantities; ++q)
    for (std::size_t s = 0; s < sides; ++s) total_[q][s] = value(value_name(quantity_names[q], s));
}

json::JsonObject PocketSteps::totals_json() const {
  json::JsonObject j;
  if (!active()) return j;
  j.add("sides", "[0, 1]: 0 the bar ahead in +z (spatial: circumferential_force < 0; planar: cage_bar_front), "
                 "1 the bar behind");
  for (std::size_t q = 0; q < quantities; ++q)
    j.add(quantity_names[q], std::vector<double>(std::begin(total_[q]), std::end(total_[q])));
  return j;
}

}  // namespace raceway::run
