// The thermal network (solver/bearing/thermal_network.hpp): its steady state against the hand
// solution of a resistance network, its own Jacobian, and in a ball bearing with a [thermal]
// section the heat it takes in against the power balance's losses at the same evaluation, and its
// energy: the heat in is what its capacities store plus what leaves to the ambient.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "io/scene/scene_parser.hpp"
#include "scheduler/executor.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/power_terms.hpp"
#include "solver/bearing/segment_record.hpp"
#include "solver/bearing/startup.hpp"
#include "solver/bearing/thermal_network.hpp"
#include "solver/numerics/bordered_matrix.hpp"
#include "solver/numerics/integrator.hpp"
#include "tests/support/solver_test_support.hpp"

namespace raceway::bearing {
namespace {

using TN = ThermalNetwork;

// A network whose steady state is worked by hand: the cage's heat Q_c flows cage -> oil ->
// rolling elements; the inner ring's Q_i splits between the shaft (G5, to the ambient) and the
// path through the rolling elements, the outer ring and the housing to the ambient air (G1, then
// the series R_s = 1/G2 + 1/G3 + 1/G4, which also carries Q_c).
constexpr double G1 = 0.8, G2 = 1.5, G3 = 4.0, G4 = 0.6, G5 = 2.5, G6 = 0.3, G7 = 0.9;
constexpr double Qi = 12.0, Qc = 3.0, Tamb = 300.0;

struct Chain {
  // Two "segments": the first's loss all into the inner ring, the second's into the cage.
  TN network{{400, 900, 250, 60, 5, 3000},
             {{TN::inner_ring, TN::rolling_elements, G1, "a"},
              {TN::rolling_elements, TN::outer_ring, G2, "b"},
              {TN::outer_ring, TN::housing, G3, "c"},
              {TN::housing, TN::ambient, G4, "d"},
              {TN::inner_ring, TN::ambient, G5, "e"},
              {TN::cage, TN::oil, G6, "f"},
              {TN::oil, TN::rolling_elements, G7, "g"}},
             {{TN::inner_ring, TN::inner_ring, 0}, {TN::cage, TN::cage, 0}},
             Tamb,
             Tamb,
             0};
  std::vector<double> records = std::vector<double>(2 * SegmentRecord::size, 0.0);
  Chain() {
    records[SegmentRecord::diagnostics] = Qi;
    records[SegmentRecord::size + SegmentRecord::diagnostics] = Qc;
  }
  std::vector<double> rates(const std::vector<double>& z) const {
    std::vector<double> zdot(TN::parts, 0.0);
    const Model unused;
    network.rates(unused, 0, z.data(), nullptr, zdot.data());
    network.add_segment_rates(unused, 0, z.data(), records.data(), zdot.data());
    return zdot;
  }
};

std::vector<double> hand_solution() {
  const double rs = 1 / G2 + 1 / G3 + 1 / G4;
  const double x = (Qi / G5 - Qc * rs) / (rs + 1 / G1 + 1 / G5);  // inner ring -> rolling elements
  std::vector<double> t(TN::parts);
  t[TN::inner_ring] = Tamb + (Qi - x) / G5;
  t[TN::rolling_elements] = t[TN::inner_ring] - x / G1;
  t[TN::outer_ring] = t[TN::rolling_elements] - (x + Qc) / G2;
  t[TN::housing] = t[TN::outer_ring] - (x + Qc) / G3;
  t[TN::oil] = t[TN::rolling_elements] + Qc / G7;
  t[TN::cage] = t[TN::oil] + Qc / G6;
  EXPECT_NEAR(t[TN::housing], Tamb + (x + Qc) / G4, 1e-9);
  return t;
}

TEST(ThermalNetwork, SteadyStateIsTheResistanceNetworksHandSolution) {
  const Chain c;
  const std::vector<double> t = hand_solution();
  for (double r : c.rates(t)) EXPECT_NEAR(r, 0.0, 1e-13);
  std::vector<double> off = t;
  off[TN::oil] += 0.1;
  EXPECT_GT(std::abs(c.rates(off)[TN::oil]), 1e-3) << "away from it the oil's temperature changes";
  // The linear network from the ambient temperature relaxes to it (implicit Euler, exact for the
  // steady state): the own Jacobian is the network's.
  numerics::BorderedMatrix jac(TN::parts, 0, 0);
  c.network.add_own_jacobian(Model{}, 0, jac);
  const Eigen::MatrixXd a = jac.to_dense();
  std::vector<double> z(TN::parts, Tamb);
  for (int step = 0; step < 200; ++step) {
    const std::vector<double> f = c.rates(z);
    const double h = 1e4;
    const Eigen::MatrixXd m = Eigen::MatrixXd::Identity(TN::parts, TN::parts) - h * a;
    const Eigen::VectorXd dz = m.partialPivLu().solve(h * Eigen::Map<const Eigen::VectorXd>(f.data(), TN::parts));
    for (int k = 0; k < TN::parts; ++k) z[static_cast<std::size_t>(k)] += dz[k];
  }
  for (int k = 0; k < TN::parts; ++k) EXPECT_NEAR(z[static_cast<std::size_t>(k)], t[static_cast<std::size_t>(k)], 1e-9) << k;
}

TEST(ThermalNetwork, TakesInTheBearingsLossesAndConservesTheirHeat) {
  scene::Scene s = test::load_job_scene("6205_first_scene.toml");
  std::string text = s.text + "\n[thermal]\nambient_temperature = \"25 degC\"\n";
  s = scene::parse_scene(text, "6205 with [thermal]");
  const Model model = build_model(s);
  const TN* network = thermal_network_of(model);
  ASSERT_NE(network, nullptr);
  scheduler::SerialExecutor executor;
  Equations eq(model, executor);
  executor.attach(eq.task_catalogue());
  std::vector<double> z;
  numerics::Integrator integrator(eq, s.solver, 0.0, initial_state(model, 0.0).state);
  integrator.advance_to(2e-3, z);
  std::vector<double> zdot(z.size());
  eq.rhs(2e-3, z.data(), zdot.data());
  // Heat in = the losses of the power balance that are the bearing's own (not the supports').
  const PowerTerms terms(model);
  std::vector<double> p(terms.size());
  terms.evaluate(eq, 2e-3, z.data(), p.data());
  double losses = 0;
  for (std::size_t i = PowerTerms::input_count; i < p.size() - 2; ++i) losses += p[i];
  double q[TN::parts], heat = 0;
  network->heat_inputs(eq.segment_records().data(), q);
  for (double v : q) heat += v;
  EXPECT_GT(losses, 0.1);
  EXPECT_NEAR(heat, losses, 1e-12 * losses);
  // Energy: heat in = sum C dT/dt + the flows to the ambient.
  std::vector<double> flow(network->links().size());
  network->link_flows(z.data(), flow.data());
  double stored = 0, out = 0;
  for (int k = 0; k < TN::parts; ++k)
    stored += network->capacity()[static_cast<std::size_t>(k)] * zdot[static_cast<std::size_t>(network->state(k))];
  for (std::size_t i = 0; i < flow.size(); ++i)
    if (network->links()[i].b == TN::ambient) out += flow[i];
  EXPECT_NEAR(stored + out, heat, 1e-9 * heat);
  // The parts warm from 25 degC where the heat goes: the rolling elements and both rings.
  for (const int k : {TN::inner_ring, TN::outer_ring, TN::rolling_elements})
    EXPECT_GT(z[static_cast<std::size_t>(network->state(k))], 298.15) << TN::part_names[k];
}

TEST(ThermalNetwork, BallGrooveFilmsTakeTheOilsViscosity) {
  // A data sheet's oil (68 and 8.5 mm^2/s at 40 and 100 degC): at the oil node's 40 degC the
  // viscosity is 8.0 times that at 100 degC (the densities' ratio is one), and Hamrock and Dowson's
  // central film grows as the viscosity to the 0.67: 4.03 times, at the same state otherwise.
  scene::Scene s = test::load_job_scene("6205_first_scene.toml");
  s = scene::parse_scene(s.text + "\n[lubricant]\nviscosity_40 = \"68 mm^2/s\"\nviscosity_100 = \"8.5 mm^2/s\"\n"
                                  "density = \"870 kg/m^3\"\ntemperature = \"70 degC\"\npressure_viscosity = \"20 1/GPa\"\n[thermal]\n",
                         "6205, an oil's data sheet and [thermal]");
  const Model model = build_model(s);
  ASSERT_GE(model.oil_viscosity.state, 0);
  scheduler::SerialExecutor executor;
  Equations eq(model, executor);
  executor.attach(eq.task_catalogue());
  const std::vector<double> start = initial_state(model, 0.0).state;
  EXPECT_DOUBLE_EQ(start[static_cast<std::size_t>(model.oil_viscosity.state)], 343.15) << "starts at the oil's temperature";
  std::vector<double> z;
  numerics::Integrator integrator(eq, s.solver, 0.0, start);
  integrator.advance_to(1e-3, z);  // rolling: the films need entrainment
  std::vector<double> zdot(z.size());
  eq.rhs(1e-3, z.data(), zdot.data());
  std::size_t s0 = 0;  // the most loaded inner-groove contact
  for (std::size_t i = 0; i < model.segments.size(); ++i)
    if (model.segments[i].kind == SegmentKind::ball_inner_groove &&
        eq.diagnostic(i, normal_force_field) > eq.diagnostic(s0, normal_force_field))
      s0 = i;
  constexpr int film = contact::field_index(contact::point_diagnostic_fields, "film_thickness");
  double h[2];
  for (const int i : {0, 1}) {
    z[static_cast<std::size_t>(model.oil_viscosity.state)] = i == 0 ? 313.15 : 373.15;
    eq.rhs(1e-3, z.data(), zdot.data());
    ASSERT_GT(eq.diagnostic(s0, normal_force_field), 1.0);
    h[i] = eq.diagnostic(s0, film);
  }
  const double eta40 = model.oil_viscosity.at(std::vector<double>(z.size(), 313.15).data(), 0);
  const double eta100 = model.oil_viscosity.at(std::vector<double>(z.size(), 373.15).data(), 0);
  EXPECT_NEAR(eta40 / eta100, 8.0, 1e-9);
  EXPECT_NEAR(h[0] / h[1], std::pow(8.0, 0.67), 0.01 * std::pow(8.0, 0.67));
}

}  // namespace
}  // namespace raceway::bearing
