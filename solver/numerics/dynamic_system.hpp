// The seam between physics and numerics (STYLE.md habit 1): what the integrator sees of a bearing
// model. A state vector laid out border first (rings, cage) then one equal-sized block per rolling
// element, a right-hand side, a Jacobian into a bordered matrix, absolute tolerances, and a way to
// explain a state when an integration fails. The planar (solver/equations.hpp) and the spatial
// (solver/spatial_equations.hpp) models implement it; CVODE knows nothing of rollers or balls.
#pragma once

#include <fmt/format.h>

#include <string>
#include <vector>

#include "solver/numerics/bordered_matrix.hpp"

namespace raceway::solver {

class DynamicSystem {
 public:
  virtual ~DynamicSystem() = default;
  virtual int state_size() const = 0;
  virtual int border_size() const = 0;
  virtual int block_count() const = 0;
  virtual int block_size() const = 0;
  /// Absolute tolerance per state (SI, by variable class).
  virtual std::vector<double> absolute_tolerance() const = 0;
  /// f(t, z). Returns 0, or 1 (recoverable) when a contact law left its valid range.
  virtual int rhs(double t, const double* z, double* zdot) = 0;
  /// J = df/dz into the bordered matrix. Returns 0, or 1 (recoverable).
  virtual int jacobian(double t, const double* z, BorderedMatrix& jac) = 0;
  /// Diagnosis of state `index` for a failed integration: its name, the most loaded contact of the
  /// body it belongs to (from the last rhs), and the contact that last left its valid range.
  virtual std::string explain_state(int index) const = 0;
};

/// DynamicSystem::explain_state for a model with `bodies` (offset, size), `segments` (body_a,
/// body_b, name) and `state_name`, from segment records whose diagnostics start with approach [m]
/// and normal force [N] at `diagnostics`.
template <class ModelT>
std::string explain_model_state(const ModelT& m, int index, const std::vector<double>& records, int record_size,
                                int diagnostics, int last_invalid) {
  std::string out = m.state_name[static_cast<std::size_t>(index)];
  int body = -1;
  for (std::size_t b = 0; b < m.bodies.size(); ++b)
    if (index >= m.bodies[b].offset && index < m.bodies[b].offset + m.bodies[b].size) body = static_cast<int>(b);
  std::size_t best = m.segments.size();
  double best_force = -1;
  const auto size = static_cast<std::size_t>(record_size), diag = static_cast<std::size_t>(diagnostics);
  for (std::size_t s = 0; s < m.segments.size() && !records.empty(); ++s) {
    const auto& seg = m.segments[s];
    if (seg.body_a != body && seg.body_b != body) continue;
    const double f = records[s * size + diag + 1];
    if (f > best_force) best_force = f, best = s;
  }
  if (best < m.segments.size())
    out += fmt::format("; most loaded contact of that body: {} ({:.4g} N, approach {:.4g} um)", m.segments[best].name,
                       best_force, 1e6 * records[best * size + diag]);
  if (last_invalid >= 0)
    out += fmt::format("; contact that last left its valid range: {}",
                       m.segments[static_cast<std::size_t>(last_invalid)].name);
  return out;
}

}  // namespace raceway::solver
