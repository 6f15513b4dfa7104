// The thermal network (a [thermal] section; off by default): one temperature per part, inner ring,
// outer ring, rolling elements (lumped), cage, oil and housing, first-order states in the border
// integrated with the motion:
//
//   C_k dT_k/dt = Q_k + sum_links G (T_other - T_k)      (links to the ambient: T_other = T_ambient)
//
// Q_k: the heat of the bearing's own losses, each segment's `power_loss` at the same right-hand
// side, half into each of its two bodies' parts (a rolling element's into the rolling elements),
// the drag and churning in the oil-air mixture into the oil. The supports' and the housing's
// dampers are outside the bearing: their losses are not heat of this network. Links: each ring to
// the rolling elements (through the contacts), the rings' raceways, the rolling elements and the
// cage to the oil (convection), the outer ring to the housing and the inner ring to the shaft (at
// the ambient temperature) through their fits, the housing to the ambient air. Capacities from the
// masses and specific heats; conductances from the geometry unless the scene gives them
// (docs/lubrication.md, "Thermal network"). The temperatures are no mechanical energy.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "io/scene/scene.hpp"
#include "solver/bearing/nodes.hpp"

namespace raceway::bearing {

struct Model;

class ThermalNetwork final : public Node {
 public:
  static constexpr int parts = 6;
  enum Part : int { inner_ring, outer_ring, rolling_elements, cage, oil, housing };
  static constexpr const char* part_names[parts] = {"inner_ring", "outer_ring", "rolling_elements", "cage", "oil", "housing"};
  static constexpr int ambient = -1;
  struct Link {
    int a, b;             ///< parts; b may be `ambient`
    double conductance;   ///< W/K
    std::string name;     ///< "outer_ring-housing"
  };
  /// Where a segment's loss goes: half to part a, half to part b.
  struct Heat {
    int a, b, field;  ///< field: power_loss in the segment's family's table
  };

  ThermalNetwork(std::array<double, parts> capacity, std::vector<Link> links, std::vector<Heat> heat, double ambient_temperature,
                 double initial_temperature, int first_state);

  int state(int part) const { return first_state_ + part; }
  const std::array<double, parts>& capacity() const { return capacity_; }
  const std::vector<Link>& links() const { return links_; }
  double ambient_temperature() const { return ambient_; }
  /// The heat into each part [W] from the segment records of a right-hand side.
  void heat_inputs(const double* records, double out[parts]) const;
  /// The heat flow through each link [W], from a to b, at the temperatures of z.
  void link_flows(const double* z, double* out) const;

  std::string name() const override { return "thermal_network"; }
  int force_count() const override { return 0; }
  void rates(const Model& m, double t, const double* z, const double* forces, double* zdot) const override;
  void add_segment_rates(const Model& m, double t, const double* z, const double* records, double* zdot) const override;
  void add_own_jacobian(const Model& m, double t, numerics::BorderedMatrix& jac) const override;
  void add_energy(const Model&, double, const double*, double&) const override {}
  void set_tolerances(std::vector<double>& atol) const override;
  void initial_state(std::vector<double>& z) const override;
  std::string describe(const Model& m) const override;

 private:
  double temperature(const double* z, int part) const { return part == ambient ? ambient_ : z[state(part)]; }
  std::array<double, parts> capacity_;
  std::vector<Link> links_;
  std::vector<Heat> heat_;
  double ambient_, initial_;
  int first_state_;
};

/// With a [thermal] section: its six states (border, after the cage's). Returns the first, or -1.
int add_thermal_states(Model& m, const scene::Scene& scene);
/// After the elements: the network node on the states from add_thermal_states (first >= 0).
void add_thermal_network(Model& m, const scene::Scene& scene, int first_state);
/// The model's thermal network, or nullptr.
const ThermalNetwork* thermal_network_of(const Model& m);

}  // namespace raceway::bearing
