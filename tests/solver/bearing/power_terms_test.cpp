// The power balance's terms at one state (solver/bearing/power_terms.hpp) against the rate of the
// stored energy along the motion: d(stored)/dt = (E(t + h, z + h f) - E(t - h, z - h f)) / 2h, the
// stored energy evaluated with the records of right-hand sides at the two displaced states, must
// equal the inputs less the losses. It checks that no power is left out and that every law's
// power_loss is the work its forces do beyond the change of its elastic energy. Each scene is
// integrated a little first, so that its contacts slide, its cage hits its pockets and its
// supports move.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/scene/scene_parser.hpp"
#include "scheduler/executor.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/power_terms.hpp"
#include "solver/bearing/startup.hpp"
#include "solver/numerics/integrator.hpp"
#include "tests/support/solver_test_support.hpp"

namespace raceway::bearing {
namespace {

struct Balance {
  double stored_rate = 0, inputs = 0, losses = 0, scale = 0;
  std::vector<double> terms;
};

/// The balance's two sides at the state reached at time t, central differences with step h.
Balance balance_after(const scene::Scene& scene, double t, double h) {
  const Model model = build_model(scene);
  scheduler::SerialExecutor executor;
  Equations eq(model, executor);
  executor.attach(eq.task_catalogue());
  std::vector<double> z;
  numerics::Integrator integrator(eq, scene.solver, 0.0, initial_state(model, 0.0).state);
  integrator.advance_to(t, z);
  const PowerTerms terms(model);
  std::vector<double> f(z.size()), zp(z.size());
  const auto stored = [&](double dt) {
    for (std::size_t i = 0; i < z.size(); ++i) zp[i] = z[i] + dt * f[i];
    std::vector<double> unused(z.size());
    eq.rhs(t + dt, zp.data(), unused.data());
    return terms.stored_energy(eq, t + dt, zp.data(), eq.energy(t + dt, zp.data()));
  };
  Balance b;
  eq.rhs(t, z.data(), f.data());
  b.terms.resize(terms.size());
  terms.evaluate(eq, t, z.data(), b.terms.data());
  for (std::size_t i = 0; i < b.terms.size(); ++i) {
    (i < PowerTerms::input_count ? b.inputs : b.losses) += b.terms[i];
    b.scale += std::abs(b.terms[i]);
  }
  const std::vector<double> f0 = f;
  const double up = stored(h), down = stored(-h);
  f = f0;
  b.stored_rate = (up - down) / (2 * h);
  std::printf("[ power ] %s at %.3g ms: dE/dt %.6g W, inputs %.6g W, losses %.6g W (", scene.scene.name.c_str(), t * 1e3,
              b.stored_rate, b.inputs, b.losses);
  for (std::size_t i = 0; i < b.terms.size(); ++i)
    std::printf("%s%s %.4g", i ? ", " : "",
                i < PowerTerms::input_count ? PowerTerms::input_names[i]
                                            : terms.loss_names()[i - PowerTerms::input_count].c_str(),
                b.terms[i]);
  std::printf("): mismatch %.3g of the terms' magnitudes\n", (b.stored_rate - b.inputs + b.losses) / b.scale);
  return b;
}

void expect_balanced(const Balance& b, double tolerance) {
  ASSERT_GT(b.scale, 0.0);
  EXPECT_NEAR(b.stored_rate, b.inputs - b.losses, tolerance * b.scale);
}

TEST(PowerTerms, BallBearingBalancesTheStoredEnergyRate) {
  const Balance b = balance_after(test::load_job_scene("6205_first_scene.toml"), 2e-3, 1e-9);
  EXPECT_GT(b.terms[0], 0.0) << "the driven inner ring delivers power";
  EXPECT_GT(b.losses, 0.0);
  expect_balanced(b, 2e-5);
}

TEST(PowerTerms, RollerBearingBalancesTheStoredEnergyRate) {
  scene::Scene s = test::load_job_scene("seed002_100hz.toml");
  const Balance b = balance_after(s, 2e-3, 1e-9);
  EXPECT_GT(b.terms[0], 0.0);
  EXPECT_NE(b.terms[1], 0.0) << "the load on the free inner ring does work while it moves";
  expect_balanced(b, 2e-5);
}

/// A seed 003 scene with dry roller-race contacts (Palmgren, tanh traction), its cage's films kept.
/// The EHD race law's power_loss is not the work its forces do (docs/lubrication.md: the Poiseuille
/// force, applied equal and opposite at the contact, does work through the slip alone, while the
/// law counts it times the entrainment speed; the film's elastic energy leaves out its dependence on
/// the film), which RacesWithEhdFilmsLeaveAResidual measures.
scene::Scene dry_races(const std::string& name) {
  std::ifstream in(std::string(RACEWAY_SOURCE_DIR) + "/jobs/scenes/" + name);
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  const auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) s.replace(at, from.size(), to);
  };
  replace("normal = \"moes_ehd\"", "normal = \"palmgren\"");
  replace("traction = \"ehd\"", "traction = \"tanh\"\nslip_velocity_scale = \"0.05 m/s\"");
  return scene::parse_scene(s, name);
}

TEST(PowerTerms, CarrierFrameAndFilmsBalanceTheStoredEnergyRate) {
  // The planet bearing while its carrier spins up: the frame's Euler terms and the centrifugal
  // potential's change in time, the hydrodynamic roller/cage and the land's losses.
  const Balance b = balance_after(dry_races("seed003_planet_carrier.toml"), 1e-3, 1e-9);
  EXPECT_NE(b.terms[2], 0.0) << "the spinning-up carrier frame does work";
  expect_balanced(b, 2e-5);
}

TEST(PowerTerms, RacesWithEhdFilmsLeaveAResidual) {
  // The EHD race law as shipped: its power_loss exceeds the work of its forces (measured 565 W of
  // 17.6 kW of losses at 1 ms of seed003_no_carrier), far beyond the differences' error. When the
  // law is made consistent this test fails and is to be folded into the ones above.
  const Balance b = balance_after(test::load_job_scene("seed003_no_carrier.toml"), 1e-3, 1e-9);
  EXPECT_GT(b.stored_rate - (b.inputs - b.losses), 0.01 * b.losses);
}

TEST(PowerTerms, OnlyTheRingsHaveALoadPotential) {
  // stored_energy asks only the bodies with a ring's load for their potential: every other body's
  // must be exactly 0.0, and the sum the bits of subtracting every body's (a ball and a roller model).
  for (const char* name : {"6205_first_scene.toml", "seed002_100hz.toml"}) {
    const Model model = build_model(test::load_job_scene(name));
    scheduler::SerialExecutor executor;
    Equations eq(model, executor);
    executor.attach(eq.task_catalogue());
    std::vector<double> z = initial_state(model, 0.0).state;
    for (std::size_t i = 0; i < z.size(); ++i) z[i] += 1e-6 * (1.0 + static_cast<double>(i % 7));  // every state moved
    const double t = 1e-3, energy = 1.25;
    double every = energy, rings = 0;
    for (std::size_t b = 0; b < model.bodies.size(); ++b) {
      const double v = eq.dynamics().load_potential(static_cast<int>(b), t, z.data());
      every -= v;
      if (model.bodies[b].ring) rings += std::abs(v);
      else EXPECT_EQ(v, 0.0) << name << ": body " << b;
    }
    EXPECT_GT(rings, 0.0) << name << ": a loaded ring has a potential";
    EXPECT_EQ(PowerTerms::stored_energy(eq, t, z.data(), energy), every) << name;
  }
}

}  // namespace
}  // namespace raceway::bearing
