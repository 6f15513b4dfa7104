// The planar cylindrical roller bearing is the spatial one restricted to the plane: aligned and
// without axial load, the spatial model (rollers with tilt, skew and axial freedom, each race
// contact in slices, pocket bars in slices, a two-station land, ribs) must give the planar model's
// roller loads and cage speed. Seed 002 at 40 Hz (Fr 1 kN, gravity seating the cage on its land),
// both models from the same (planar) seating, compared over the window 5 to 15 ms after the start
// (0.2 to 0.6 shaft revolutions; the first 5 ms are the start-up transient's, the same in both).
//
// Roller loads: each roller's inner-race load (the sum of its slices' normal forces, spatial)
// averaged over the window, and the largest load at each sample; cage speed: its mean over the window.
// Measured: mean loads 0.073 % of the largest, the largest load at each sample within 0.31 %, cage
// speed 0.043 %. With the races lubricated (Moes EHD film and EHD traction, planar line contacts
// against the spatial model's slices; window 5 to 10 ms): mean loads 0.010 %, the largest load at
// each sample within 0.25 %, cage speed 0.0006 %.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "scheduler/executor.hpp"
#include "solver/bearing/element_traits.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/startup.hpp"
#include "io/scene/scene_parser.hpp"
#include "solver/numerics/integrator.hpp"
#include "tests/support/solver_test_support.hpp"

namespace raceway::bearing {
namespace {

struct Window {
  std::vector<std::vector<double>> loads;  ///< per sample, per roller: inner-race normal force [N]
  std::vector<double> cage_speed;          ///< per sample [rad/s]
};

/// Integrates the scene's model (planar or spatial) from its start and samples it every 0.25 ms
/// from 5 ms to `end`.
Window sample(const scene::Scene& scene, double end) {
  const scene::ModelKind space = scene.scene.model;
  const Model m = build_model(scene);
  scheduler::SerialExecutor executor;
  Equations eq(m, executor);
  numerics::Integrator integrator(eq, scene.solver, 0.0, initial_state(m, 0.0).state);
  const SegmentKind inner = space == scene::ModelKind::spatial ? SegmentKind::roller_inner_slice : SegmentKind::roller_inner_race;
  const Body& cage = m.bodies[static_cast<std::size_t>(m.cage)];
  Window w;
  std::vector<double> z, zdot(static_cast<std::size_t>(m.state_size));
  for (int i = 0; 5e-3 + 0.25e-3 * i <= end + 1e-12; ++i) {
    const double t = 5e-3 + 0.25e-3 * i;
    integrator.advance_to(t, z);
    eq.rhs(t, z.data(), zdot.data());
    std::vector<double> load(static_cast<std::size_t>(m.element_count), 0.0);
    for (std::size_t s = 0; s < m.segments.size(); ++s)
      if (m.segments[s].kind == inner)
        load[static_cast<std::size_t>(m.segments[s].element)] += eq.diagnostic(s, normal_force_field);
    w.loads.push_back(load);
    w.cage_speed.push_back(z[static_cast<std::size_t>(cage.slot[swz])]);
  }
  return w;
}

struct Agreement {
  double worst_mean = 0, worst_peak = 0, cage = 0, largest = 0;
};

/// The planar scene `text` against the same text with model = "spatial" (every spatial key at its
/// default: NU ribs, straight rollers, 20 slices per race), sampled to `end`.
Agreement compare(const std::string& text, double end, const char* label) {
  const std::string planar_model = "model = \"planar\"";
  const std::size_t at = text.find(planar_model);
  EXPECT_NE(at, std::string::npos);
  std::string spatial_text = text;
  spatial_text.replace(at, planar_model.size(), "model = \"spatial\"");
  const Window planar = sample(scene::parse_scene(text, "seed002_40hz.toml"), end);
  const Window spatial = sample(scene::parse_scene(spatial_text, "seed002_40hz.toml (spatial)"), end);
  const std::size_t rollers = planar.loads[0].size();
  const double samples = static_cast<double>(planar.loads.size());
  Agreement a;
  double planar_cage = 0, spatial_cage = 0;
  std::vector<double> mean_planar(rollers, 0.0), mean_spatial(rollers, 0.0);
  for (std::size_t i = 0; i < planar.loads.size(); ++i) {
    const double peak_planar = *std::max_element(planar.loads[i].begin(), planar.loads[i].end());
    const double peak_spatial = *std::max_element(spatial.loads[i].begin(), spatial.loads[i].end());
    a.largest = std::max(a.largest, peak_planar);
    a.worst_peak = std::max(a.worst_peak, std::abs(peak_spatial - peak_planar) / peak_planar);
    for (std::size_t k = 0; k < rollers; ++k) {
      mean_planar[k] += planar.loads[i][k] / samples;
      mean_spatial[k] += spatial.loads[i][k] / samples;
    }
    planar_cage += planar.cage_speed[i] / samples;
    spatial_cage += spatial.cage_speed[i] / samples;
  }
  for (std::size_t k = 0; k < rollers; ++k)
    a.worst_mean = std::max(a.worst_mean, std::abs(mean_spatial[k] - mean_planar[k]) / a.largest);
  a.cage = std::abs(spatial_cage / planar_cage - 1);
  std::printf("[ restriction ] %s 5-%.0f ms: mean roller loads %.3g %% of the largest (%.1f N), the largest load "
              "at each sample %.3g %%, cage speed %.3g %% (%.3f / %.3f rad/s)\n",
              label, end * 1e3, 100 * a.worst_mean, a.largest, 100 * a.worst_peak, 100 * a.cage, planar_cage,
              spatial_cage);
  return a;
}

TEST(SpatialRollerRestriction, Seed002AgreesWithThePlanarModel) {
  const Agreement a = compare(test::seed002_former_solver_text(), 15e-3, "seed002");
  EXPECT_GT(a.largest, 250.0);  // the load zone is there (Fr 1 kN on 13 rollers: about 310 N at its middle)
  EXPECT_LT(a.worst_mean, 5e-3);
  EXPECT_LT(a.worst_peak, 5e-3);
  EXPECT_LT(a.cage, 2e-3);
}

// The same with the races lubricated: the Moes EHD film and EHD traction (Couette and Poiseuille) on
// every race contact, planar line contacts against spatial slices, in a gearbox oil (40 mPa s,
// 20 1/GPa). The cage's pocket bars and land stay dry in both. Window 5 to 10 ms.
TEST(SpatialRollerRestriction, Seed002WithEhdFilmsAgreesWithThePlanarModel) {
  std::string text = test::seed002_former_solver_text();
  const std::string dry = "[contact.roller_race]\nnormal = \"palmgren\"\n";
  const std::size_t at = text.find(dry);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, dry.size(),
               "[lubricant]\nviscosity = \"40 mPa s\"\npressure_viscosity = \"20 1/GPa\"\n\n"
               "[contact.roller_race]\nnormal = \"moes_ehd\"\n");
  const std::string tanh = "traction = \"tanh\"\nfriction_coefficient = 0.2\n";
  const std::size_t t = text.find(tanh, at);
  ASSERT_NE(t, std::string::npos);
  text.replace(t, tanh.size(), "traction = \"ehd\"\nfriction_coefficient = 0.06\n");
  const Agreement a = compare(text, 10e-3, "seed002 EHD");
  EXPECT_GT(a.largest, 250.0);
  EXPECT_LT(a.worst_mean, 5e-3);
  EXPECT_LT(a.worst_peak, 5e-3);
  EXPECT_LT(a.cage, 2e-3);
}

}  // namespace
}  // namespace raceway::bearing
