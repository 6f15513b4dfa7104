// The sensor on the housing (solver/bearing/housing.hpp): the housing's displacement, velocity and
// acceleration in x and y, sampled `per` times per output interval, at t_(i-1) + j dt / per
// (j = 1..per, the last at the output time t_i itself). Samples come from the integrator's
// interpolant of each accepted step (its derivative for the acceleration), not from extra
// right-hand sides, so sampling costs no evaluation and changes no step.
//
// Each output sample carries the sensor's samples of the interval that ends at it (the row at t = 0
// is NaN: no interval ends there), so the sensor's rows ride with the output's series: the same
// flushes, checksums and truncation at a resume. Samples past an output time are held until the
// next one; a restart of the integrator at a checkpoint drops those past it (the restarted
// integration gives them again), so a resumed run writes the same bits as an uninterrupted one.
#pragma once

#include <array>
#include <map>
#include <vector>

#include "solver/bearing/housing.hpp"
#include "solver/numerics/integrator.hpp"

namespace raceway::run {

class HousingSensor {
 public:
  /// Quantities per sensor sample in a row: time, then x and y of displacement, velocity, acceleration.
  static constexpr int quantities = 7;
  HousingSensor(const bearing::Model& m, double output_interval);
  bool active() const { return housing_ != nullptr; }
  int per_output() const { return per_; }
  /// After an accepted step: the samples within it.
  void observe(numerics::Integrator& integrator);
  /// Appends output sample `sample`'s sensor row to `row`: time (per), displacement (per x 2),
  /// velocity (per x 2), acceleration (per x 2).
  void take_row(long sample, std::vector<double>& row);
  /// The integrator restarts at t: samples past t are integrated again.
  void restart(double t);

 private:
  double time_of(long k) const;
  const bearing::Housing* housing_ = nullptr;
  double dt_ = 0;
  int per_ = 0;
  long next_ = 1;  ///< the next sensor index to sample
  std::map<long, std::array<double, quantities>> pending_;
  std::vector<double> z_, zdot_;
};

}  // namespace raceway::run
