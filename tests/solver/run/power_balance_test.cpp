// The power balance over whole runs (solver/run/power_balance.hpp): the inputs' work over a window
// of output times equals the losses' work plus the change of the stored energy, within 1 %, on a
// ball bearing and a roller bearing, read from the output file's /power_balance series; and the
// run summary's balance over the whole run is the file's last row. What is left over is the
// integrator's own dissipation (or gain) of energy, which shrinks with rtol: see
// docs/output_layout.md, "Power balance", for the measured rtol dependence.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "io/scene/scene_parser.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/thermal_network.hpp"
#include "solver/run/run.hpp"
#include "tests/support/solver_test_support.hpp"

namespace raceway::run {
namespace {

struct Window {
  double inputs = 0, losses = 0, stored = 0, drive = 0;
  double residual() const { return inputs - losses - stored; }
};

/// The balance from row `first` to the last row of a run's file.
Window window_of(const std::string& file, std::size_t first) {
  const test::Dataset in = test::read_dataset(file, "/power_balance/input_work");
  const test::Dataset loss = test::read_dataset(file, "/power_balance/loss_work");
  const test::Dataset stored = test::read_dataset(file, "/power_balance/stored_energy");
  const std::size_t last = in.shape[0] - 1;
  Window w;
  for (std::size_t j = 0; j < in.shape[1]; ++j) w.inputs += in.at(last, j) - in.at(first, j);
  for (std::size_t j = 0; j < loss.shape[1]; ++j) w.losses += loss.at(last, j) - loss.at(first, j);
  for (std::size_t j = 0; j < loss.shape[1]; ++j) EXPECT_GE(loss.at(last, j) - loss.at(first, j), 0.0) << "loss " << j;
  w.stored = stored.values[last] - stored.values[first];
  w.drive = in.at(last, 0) - in.at(first, 0);
  return w;
}

Window run_window(scene::Scene s, double end_time, double window_start) {
  s.scene.end_time = end_time;
  test::TempDir dir;
  RunOptions options;
  options.output_path = dir.file("power.h5");
  const RunSummary sum = run_scene(s, options);
  const auto first = static_cast<std::size_t>(std::lround(window_start / s.scene.output_interval));
  const Window w = window_of(options.output_path, first);
  std::printf("[ power ] %s, rtol %.0e, %.3g to %.3g ms: inputs %.6g J (drive %.6g J), losses %.6g J, stored "
              "energy change %.4g J, residual %.3g J = %.2e of the inputs; %ld steps, wall %.1f s\n",
              s.scene.name.c_str(), s.solver.rtol, window_start * 1e3, end_time * 1e3, w.inputs, w.drive, w.losses,
              w.stored, w.residual(), w.residual() / w.inputs, sum.stats.steps, sum.wall_time_s);
  return w;
}

TEST(PowerBalance, ClosesOnABallBearing) {
  // 6205 at its shipped rtol (1e-6), a quarter of an inner-ring revolution after the first 2 ms
  // (measured residual 6.5e-4 of the inputs; 6.1e-5 over the first 40 ms).
  const Window w = run_window(test::load_job_scene("6205_first_scene.toml"), 7e-3, 2e-3);
  EXPECT_GT(w.drive, 0.0);
  EXPECT_LT(std::abs(w.residual()), 0.01 * w.inputs);
}

TEST(PowerBalance, ClosesOnARollerBearing) {
  // Seed 002 at 40 Hz with rtol 1e-7, 10 to 20 ms, where the cage's impacts on its bars take most
  // of the drive (measured residual 2.8e-4). The scene ships rtol 1e-5, where BDF's own damping of
  // the rollers' resolved contact oscillations leaves 5-12 % of the inputs unaccounted (1e-6: 0.2-1.5 %).
  scene::Scene s = test::load_seed002_former_solver();
  s.solver.rtol = 1e-7;
  const Window w = run_window(s, 20e-3, 10e-3);
  EXPECT_GT(w.drive, 0.0);
  EXPECT_LT(std::abs(w.residual()), 0.01 * w.inputs);
}

TEST(PowerBalance, ThermalNetworkStoresTheLossesHeat) {
  // 6205 with a thermal network, 10 ms: what the network's parts store (sum C (T_end - T_0)) and
  // give to the ambient (the shaft and air links, trapezoid over the samples) is the losses' work
  // integrated over the steps, but the supports' and nodes' dampers (none here). Measured 8e-5 over 40 ms.
  scene::Scene s = test::load_job_scene("6205_first_scene.toml");
  s = scene::parse_scene(s.text + "\n[thermal]\nambient_temperature = \"25 degC\"\n", "6205 with [thermal]");
  s.scene.end_time = 10e-3;
  test::TempDir dir;
  RunOptions options;
  options.output_path = dir.file("thermal.h5");
  (void)run_scene(s, options);
  const std::string& file = options.output_path;
  const test::Dataset time = test::read_dataset(file, "/time");
  const test::Dataset temperature = test::read_dataset(file, "/thermal/temperature");
  const test::Dataset flow = test::read_dataset(file, "/thermal/link_flow");
  const test::Dataset loss = test::read_dataset(file, "/power_balance/loss_work");
  const bearing::Model model = bearing::build_model(s);
  const bearing::ThermalNetwork* network = bearing::thermal_network_of(model);
  ASSERT_NE(network, nullptr);
  const std::size_t last = time.values.size() - 1;
  double stored = 0, out = 0, losses = 0;
  for (std::size_t k = 0; k < bearing::ThermalNetwork::parts; ++k)
    stored += network->capacity()[k] * (temperature.at(last, k) - temperature.at(0, k));
  for (std::size_t i = 0; i + 1 <= last; ++i)
    for (std::size_t l = 0; l < network->links().size(); ++l)
      if (network->links()[l].b == bearing::ThermalNetwork::ambient)
        out += 0.5 * (flow.at(i, l) + flow.at(i + 1, l)) * (time.values[i + 1] - time.values[i]);
  for (std::size_t j = 0; j + 2 < loss.shape[1]; ++j) losses += loss.at(last, j) - loss.at(0, j);
  std::printf("[ thermal ] 10 ms: stored %.6g J, to the ambient %.4g J, losses' work %.6g J\n", stored, out, losses);
  EXPECT_GT(stored, 0.0);
  EXPECT_NEAR(stored + out, losses, 1e-3 * losses);
}

}  // namespace
}  // namespace raceway::run
