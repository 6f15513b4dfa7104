// raceway TimeFunction: constant, or piecewise linear through (time, value) and held outside.
#include <algorithm>

#include "io/scene/scene.hpp"

namespace raceway::scene {

double TimeFunction::operator()(double t) const {
  if (values.empty()) return 0.0;
  if (times.empty() || t <= times.front()) return values.front();
  if (t >= times.back()) return values.back();
  // first knot strictly after t; t lies in [times[k-1], times[k])
  const auto k = static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin());
  const double t0 = times[k - 1], t1 = times[k];
  const double w = (t - t0) / (t1 - t0);
  return values[k - 1] + w * (values[k] - values[k - 1]);
}

double TimeFunction::derivative(double t) const {
  if (times.size() < 2 || t < times.front() || t >= times.back()) return 0.0;
  const auto k = static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin());
  return (values[k] - values[k - 1]) / (times[k] - times[k - 1]);
}

double TimeFunction::integral(double t) const {
  if (values.empty()) return 0.0;
  if (times.empty()) return values.front() * t;
  // Held at values.front() before the first knot, piecewise linear between knots, held after.
  double sum = values.front() * (std::min(t, times.front()) - 0.0);
  for (std::size_t k = 1; k < times.size() && t > times[k - 1]; ++k) {
    const double t1 = std::min(t, times[k]);
    sum += 0.5 * ((*this)(times[k - 1]) + (*this)(t1)) * (t1 - times[k - 1]);
  }
  if (t > times.back()) sum += values.back() * (t - times.back());
  return sum;
}

bool TimeFunction::is_zero() const {
  return std::all_of(values.begin(), values.end(), [](double v) { return v == 0.0; });
}

}  // namespace raceway::scene
