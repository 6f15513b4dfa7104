#include "solver/run/housing_sensor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace raceway::run {

HousingSensor::HousingSensor(const bearing::Model& m, double output_interval)
    : housing_(bearing::housing_of(m)), dt_(output_interval), per_(housing_ ? housing_->sensor_samples() : 0) {}

// Sensor index k = i per + j lies j dt / per after output time i dt (the output's own times exactly
// at j = 0: the same arithmetic as the run loop's).
double HousingSensor::time_of(long k) const {
  const long i = k / per_, j = k % per_;
  return static_cast<double>(i) * dt_ + static_cast<double>(j) * (dt_ / per_);
}

void HousingSensor::observe(numerics::Integrator& integrator) {
  if (!housing_) return;
  const double reached = integrator.time();
  for (; time_of(next_) <= reached; ++next_) {
    const double t = time_of(next_);
    integrator.interpolate(t, 0, z_);
    integrator.interpolate(t, 1, zdot_);
    std::array<double, quantities> s{};
    s[0] = t;
    for (int i = 0; i < 2; ++i) {
      s[1 + i] = housing_->sensor(z_.data(), i);
      s[3 + i] = housing_->sensor(z_.data(), 2 + i);
      s[5 + i] = housing_->sensor(zdot_.data(), 2 + i);
    }
    pending_[next_] = s;
  }
}

void HousingSensor::take_row(long sample, std::vector<double>& row) {
  if (!housing_) return;
  const std::size_t start = row.size();
  row.resize(start + static_cast<std::size_t>(quantities * per_), std::numeric_limits<double>::quiet_NaN());
  if (sample == 0) return;
  double* time = row.data() + start;
  double* vectors = time + per_;  // displacement, velocity, acceleration: per x 2 each
  for (int j = 0; j < per_; ++j) {
    const long k = (sample - 1) * per_ + j + 1;
    const auto it = pending_.find(k);
    if (it == pending_.end()) continue;
    const auto& s = it->second;
    time[j] = s[0];
    for (int q = 0; q < 3; ++q)
      for (int i = 0; i < 2; ++i) vectors[q * 2 * per_ + 2 * j + i] = s[static_cast<std::size_t>(1 + 2 * q + i)];
    pending_.erase(it);
  }
}

void HousingSensor::restart(double t) {
  if (!housing_) return;
  for (auto it = pending_.begin(); it != pending_.end();)
    it = time_of(it->first) > t ? pending_.erase(it) : std::next(it);
  next_ = std::max(1L, static_cast<long>(std::floor(t / (dt_ / per_))) - 2);
  while (time_of(next_) <= t) ++next_;
}

}  // namespace raceway::run
