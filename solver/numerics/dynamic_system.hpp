// The seam between physics and numerics: what the integrator sees of a bearing model. A state
// vector laid out border first (rings, cage) then one equal-sized block per rolling element, a
// right-hand side, a Jacobian into a bordered matrix, absolute tolerances, and a way to explain a
// state when an integration fails. The bearing's equations (solver/bearing/equations.hpp)
// implement it; CVODE knows nothing of rollers or balls.
#pragma once

#include <string>
#include <vector>

#include "solver/numerics/bordered_matrix.hpp"

namespace raceway::numerics {

class DynamicSystem {
 public:
  virtual ~DynamicSystem() = default;
  virtual int state_size() const = 0;
  virtual int border_size() const = 0;
  virtual int block_count() const = 0;
  virtual int block_size() const = 0;
  /// Absolute tolerance per state (SI, by variable class).
  virtual std::vector<double> absolute_tolerance() const = 0;
  /// Whether adjust_error_weights() changes anything (else SUNDIALS' own weights are used).
  virtual bool adjusts_error_weights() const { return false; }
  /// Tightens the error weights `ewt` (1 / (rtol |z_i| + atol_i), SUNDIALS' own) for the state z
  /// at t, the start of the step they test. A pure function of (t, z): the same weights on every
  /// rank and after a restart from the same state, so nothing of it goes into a checkpoint.
  virtual void adjust_error_weights(double /*t*/, const double* /*z*/, double* /*ewt*/) const {}
  /// f(t, z). Returns 0, or 1 (recoverable) when a contact law left its valid range.
  virtual int rhs(double t, const double* z, double* zdot) = 0;
  /// J = df/dz into the bordered matrix. Returns 0, or 1 (recoverable).
  virtual int jacobian(double t, const double* z, BorderedMatrix& jac) = 0;
  /// Diagnosis of state `index` for a failed integration: its name, the most loaded contact of the
  /// body it belongs to (from the last rhs), and the contact that last left its valid range.
  virtual std::string explain_state(int index) const = 0;
  /// The largest next step from (t, z) the physics allows (a ball must not cross a race defect
  /// unseen) [s]; 0: no limit. A function of (t, z) alone.
  virtual double step_limit(double /*t*/, const double* /*z*/) const { return 0.0; }
  /// Whether step_limit ever limits (asked once, when the integrator is made).
  virtual bool limits_steps() const { return false; }
};

}  // namespace raceway::numerics
