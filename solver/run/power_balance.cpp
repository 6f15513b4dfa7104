#include "solver/run/power_balance.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

namespace raceway::run {

namespace {

std::string value_name(const std::string& what, std::size_t i) { return fmt::format("power_balance.{}.{}", what, i); }

}  // namespace

PowerBalance::PowerBalance(const bearing::Model& m) : terms_(m), n_(terms_.size()) {
  last_p_.assign(n_, 0.0);
  total_.assign(n_, 0.0);
  last_row_.assign(n_, 0.0);
}

void PowerBalance::observe(const bearing::Equations& eq) {
  const double t = eq.last_rhs_time();
  pending_t_.push_back(t);
  pending_p_.resize(pending_p_.size() + n_);
  terms_.evaluate(eq, t, eq.last_rhs_state(), pending_p_.data() + pending_p_.size() - n_);
}

void PowerBalance::restart() {
  pending_t_.clear();
  pending_p_.clear();
}

void PowerBalance::take(double t, const double* p) {
  if (seeded_ && !(t > last_t_)) return;  // no time has passed since the last evaluation taken
  if (seeded_)
    for (std::size_t i = 0; i < n_; ++i) total_[i] += 0.5 * (last_p_[i] + p[i]) * (t - last_t_);
  seeded_ = true;
  last_t_ = t;
  std::copy(p, p + n_, last_p_.begin());
}

void PowerBalance::take_row(double t, std::vector<double>& row) {
  std::size_t k = 0;
  for (; k < pending_t_.size() && pending_t_[k] <= t; ++k) take(pending_t_[k], pending_p_.data() + k * n_);
  pending_t_.erase(pending_t_.begin(), pending_t_.begin() + static_cast<std::ptrdiff_t>(k));
  pending_p_.erase(pending_p_.begin(), pending_p_.begin() + static_cast<std::ptrdiff_t>(k * n_));
  last_row_ = total_;
  if (seeded_ && !pending_t_.empty() && t > last_t_) {  // the trapezoid up to t, towards the next evaluation
    const double dt = t - last_t_, s = dt / (pending_t_.front() - last_t_);
    for (std::size_t i = 0; i < n_; ++i) {
      const double at_t = last_p_[i] + s * (pending_p_[i] - last_p_[i]);
      last_row_[i] += 0.5 * (last_p_[i] + at_t) * dt;
    }
  }
  row.insert(row.end(), last_row_.begin(), last_row_.end());
}

void PowerBalance::save(Checkpoint& cp) const {
  cp.values["power_balance.seeded"] = seeded_ ? 1.0 : 0.0;
  cp.values["power_balance.last_time"] = last_t_;
  for (std::size_t i = 0; i < n_; ++i) {
    cp.values[value_name("last_power", i)] = last_p_[i];
    cp.values[value_name("work", i)] = total_[i];
    cp.values[value_name("row", i)] = last_row_[i];
  }
}

void PowerBalance::restore(const Checkpoint& cp) {
  restart();
  const auto value = [&](const std::string& name) {
    const auto it = cp.values.find(name);
    return it == cp.values.end() ? 0.0 : it->second;
  };
  seeded_ = value("power_balance.seeded") != 0.0;
  last_t_ = value("power_balance.last_time");
  for (std::size_t i = 0; i < n_; ++i) {
    last_p_[i] = value(value_name("last_power", i));
    total_[i] = value(value_name("work", i));
    last_row_[i] = value(value_name("row", i));
  }
}

json::JsonObject PowerBalance::summary_json(double window_start, double window_end, double stored_initial,
                                            double stored_final) const {
  json::JsonObject j, inputs, losses;
  double in = 0, out = 0;
  for (std::size_t i = 0; i < n_; ++i) {
    const bool input = i < bearing::PowerTerms::input_count;
    const std::string name = input ? bearing::PowerTerms::input_names[i]
                                   : terms_.loss_names()[i - bearing::PowerTerms::input_count];
    (input ? inputs : losses).add(name, last_row_[i]);
    (input ? in : out) += last_row_[i];
  }
  const double residual = in - out - (stored_final - stored_initial);
  j.add("window_s", std::vector<double>{window_start, window_end});
  j.add("input_work_j", std::move(inputs));
  j.add("loss_work_j", std::move(losses));
  j.add("input_work_total_j", in);
  j.add("loss_work_total_j", out);
  j.add("stored_energy_change_j", stored_final - stored_initial);
  j.add("residual_j", residual);
  j.add("relative_residual", in != 0.0 ? residual / std::abs(in) : 0.0);
  return j;
}

long PowerBalanceSeries::values(const bearing::Model& m) { return static_cast<long>(bearing::PowerTerms(m).size()) + 1; }

PowerBalanceSeries define_power_balance_series(h5::H5SeriesWriter& file, const bearing::Model& m) {
  const bearing::PowerTerms terms(m);
  PowerBalanceSeries s;
  s.inputs = bearing::PowerTerms::input_count;
  s.losses = terms.loss_names().size();
  file.define_series("/power_balance/input_work", {s.inputs}, "J",
                     "work delivered since the start, integrated over the solver's steps: the prescribed motions "
                     "(drive), the applied loads, the carrier frame, the cage's unbalance");
  file.define_series("/power_balance/loss_work", {s.losses}, "J",
                     "work dissipated since the start, integrated over the solver's steps, per segment kind, "
                     "supports' dampers, nodes' dampers");
  file.define_series("/power_balance/stored_energy", {}, "J",
                     "kinetic, elastic, support, gravity and carrier-frame energy (/energy without the applied "
                     "loads' potential)");
  file.set_attribute("/power_balance/input_work", "components",
                     std::vector<std::string>(std::begin(bearing::PowerTerms::input_names),
                                              std::end(bearing::PowerTerms::input_names)));
  file.set_attribute("/power_balance/loss_work", "components", terms.loss_names());
  s.input = file.series_id("/power_balance/input_work");
  s.loss = file.series_id("/power_balance/loss_work");
  s.stored = file.series_id("/power_balance/stored_energy");
  return s;
}

void append_power_balance(h5::H5SeriesWriter& file, const PowerBalanceSeries& s, const double* work,
                          const bearing::Equations& eq, double t, const double* z, double energy) {
  file.append(s.input, std::span<const double>(work, s.inputs));
  file.append(s.loss, std::span<const double>(work + s.inputs, s.losses));
  const double stored = bearing::PowerTerms::stored_energy(eq, t, z, energy);
  file.append(s.stored, std::span<const double>(&stored, 1));
}

}  // namespace raceway::run
