// The shipped campaign files of seed 001's sweeps (jobs/campaigns/): each expands to the validation
// scene with the swept keys, as the campaign documents say.
#include <gtest/gtest.h>

#include <cstddef>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "io/scene/scene_parser.hpp"
#include "solver/driver/campaign_file.hpp"

namespace raceway::driver {
namespace {

const std::filesystem::path kSourceDir = RACEWAY_SOURCE_DIR;
constexpr double pi = std::numbers::pi;
double rpm(double v) { return v * pi / 30.0; }

// Seed 001's three sweeps are campaign files over the validation scene (jobs/campaigns/): each
// scene is the validation scene with the swept speed or loads, 20 inner-ring revolutions and 600
// output samples per revolution, as in the paper. Their "_unbalance" twins are the same sweeps with
// a cage unbalance of 50 um (docs/campaigns/qj215_whirl.md), 60 revolutions and four realisations
// per point (the cage started 0 to 75 um off-centre), the validation scene's cage otherwise.
TEST(JobScenes, QJ215SweepCampaignsAreTheValidationSceneSwept) {
  const scene::Scene reference = scene::load_scene((kSourceDir / "jobs" / "scenes" / "qj215_validation.toml").string());
  struct Case {
    std::string campaign;
    std::vector<double> rpm, fa, fr;
    double unbalance = 0, revolutions = 20;
    std::vector<double> offsets{0.0};  // the realisations of each point, slowest axis first
  };
  std::vector<Case> cases(3);
  cases[0].campaign = "qj215_speed";
  for (int v = 1000; v <= 8000; v += 1000) cases[0].rpm.push_back(v), cases[0].fa.push_back(1000), cases[0].fr.push_back(0);
  cases[1].campaign = "qj215_axial";
  for (int v = 1000; v <= 5000; v += 1000) cases[1].rpm.push_back(1000), cases[1].fa.push_back(v), cases[1].fr.push_back(0);
  cases[2].campaign = "qj215_radial";
  for (int v = 100; v <= 600; v += 100) cases[2].rpm.push_back(1000), cases[2].fa.push_back(2000), cases[2].fr.push_back(v);
  for (int k = 0; k < 3; ++k) {
    Case twin = cases[static_cast<std::size_t>(k)];
    twin.campaign += "_unbalance";
    twin.unbalance = 50e-6;
    twin.revolutions = 60;
    twin.offsets = {0.0, 25e-6, 50e-6, 75e-6};
    cases.push_back(twin);
  }
  for (const Case& c : cases) {
    SCOPED_TRACE(c.campaign);
    const auto campaign = load_campaign((kSourceDir / "jobs" / "campaigns" / (c.campaign + ".toml")).string());
    ASSERT_EQ(campaign.scenes.size(), c.rpm.size() * c.offsets.size());
    for (std::size_t n = 0; n < campaign.scenes.size(); ++n) {
      const std::size_t k = n / c.offsets.size();
      const scene::Scene s = campaign_scene(campaign, campaign.scenes[n]);
      EXPECT_NEAR(s.inner_ring.speed(0.0), rpm(c.rpm[k]), 1e-9);
      EXPECT_DOUBLE_EQ(s.inner_ring.load.fz(0.0), c.fa[k]);
      EXPECT_DOUBLE_EQ(s.inner_ring.load.fy(0.0), -c.fr[k]);
      EXPECT_TRUE(s.inner_ring.load.fx.is_zero());
      EXPECT_NEAR(s.inner_ring.speed(0.0) * s.scene.end_time / (2 * pi), c.revolutions, 1e-9);
      EXPECT_NEAR(s.scene.output_interval * s.inner_ring.speed(0.0) / (2 * pi), 1.0 / 600, 1e-12);
      EXPECT_EQ(s.bearing.rolling_elements, reference.bearing.rolling_elements);
      EXPECT_EQ(s.bearing.ball.inner_conformity, reference.bearing.ball.inner_conformity);
      EXPECT_EQ(s.cage.land_clearance, reference.cage.land_clearance);
      EXPECT_DOUBLE_EQ(s.cage.mass_eccentricity, c.unbalance);
      EXPECT_NEAR(s.cage.initial_offset, c.offsets[n % c.offsets.size()], 1e-15);
      EXPECT_EQ(s.ball_race.traction.friction_coefficient, reference.ball_race.traction.friction_coefficient);
    }
  }
}

// The test grease's twins (docs/campaigns/qj215_whirl.md, "Lubricated cage contacts and drag"): the
// Figure 18 points (600..2000 r/min x Fa 1000..2000 N), dry, lubricated and at rtol 1e-7, and the
// unbalance sweeps with their longer runs and rtol check, each the validation scene with the LGMT 3
// base oil at 40 degC, where the data sheet's 125 mm^2/s is the viscosity itself (890 kg/m^3 x
// 125e-6 m^2/s = 0.11125 Pa s, no Walther fit between), both cage films and the drag; the dry
// Figure 18 campaign has none of it.
TEST(JobScenes, QJ215LubricatedCampaignsCarryTheTestGreasesBaseOil) {
  struct Case {
    std::string campaign;
    std::size_t scenes;
    double revolutions, samples, unbalance;
    std::vector<double> fractions;  // the oil volume fractions the campaign sweeps or sets
  };
  const std::vector<Case> cases{{"qj215_fig18_dry", 12, 20, 100, 0, {0.0}},
                                {"qj215_fig18_lubricated", 24, 20, 100, 0, {0.03, 0.3}},
                                {"qj215_fig18_rtol", 1, 20, 100, 0, {0.03}},
                                {"qj215_speed_lubricated", 10, 60, 600, 50e-6, {0.03}},
                                {"qj215_speed_lubricated_long", 6, 180, 600, 50e-6, {0.03}},
                                {"qj215_speed_lubricated_whirl", 4, 400, 600, 50e-6, {0.03}},
                                {"qj215_speed_lubricated_rtol", 1, 180, 600, 50e-6, {0.03}},
                                {"qj215_axial_lubricated", 10, 60, 600, 50e-6, {0.03}},
                                {"qj215_radial_lubricated", 8, 60, 600, 50e-6, {0.03}}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.campaign);
    const auto campaign = load_campaign((kSourceDir / "jobs" / "campaigns" / (c.campaign + ".toml")).string());
    ASSERT_EQ(campaign.scenes.size(), c.scenes);
    const bool dry = c.fractions[0] == 0.0;
    for (std::size_t n = 0; n < campaign.scenes.size(); ++n) {
      const scene::Scene s = campaign_scene(campaign, campaign.scenes[n]);
      const double turns_per_second = s.inner_ring.speed(0.0) / (2 * pi);
      EXPECT_NEAR(turns_per_second * s.scene.end_time, c.revolutions, 1e-9);
      EXPECT_NEAR(s.scene.output_interval * turns_per_second, 1.0 / c.samples, 1e-12);
      EXPECT_DOUBLE_EQ(s.cage.mass_eccentricity, c.unbalance);
      EXPECT_DOUBLE_EQ(s.lubricant.oil_volume_fraction, c.fractions[n * c.fractions.size() / c.scenes]);
      EXPECT_EQ(s.ball_cage.normal.id, dry ? contact::LawId::hertz : contact::LawId::pocket_film);
      EXPECT_EQ(s.cage_land.normal.id, dry ? contact::LawId::palmgren : contact::LawId::short_bearing);
      EXPECT_NEAR(s.lubricant.viscosity, dry ? 0.0 : 0.11125, 1e-9);
      EXPECT_EQ(s.ball_race.traction.id, contact::LawId::tanh_traction);
      EXPECT_DOUBLE_EQ(s.solver.rtol, c.campaign.ends_with("_rtol") ? 1e-7 : 1e-6);
    }
  }
}

// Every scene of every campaign file over the validation scene (jobs/campaigns/qj215_*.toml), given to
// `check` with its campaign's file name; returns the number of campaign files.
template <class Check>
int for_each_qj215_campaign_scene(Check check) {
  int campaigns = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kSourceDir / "jobs" / "campaigns")) {
    const std::string name = entry.path().filename().string();
    if (!name.starts_with("qj215_") || entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(name);
    ++campaigns;
    const auto campaign = load_campaign(entry.path().string());
    EXPECT_FALSE(campaign.scenes.empty());
    for (const auto& point : campaign.scenes) check(name, campaign_scene(campaign, point));
  }
  return campaigns;
}

// The validation scene stores its segment diagnostics at every 5th sample; every campaign over it
// stores them at every sample, as its recorded tables were taken (their metrics read every series at
// the segment rows: a stride would change them).
TEST(JobScenes, QJ215CampaignsStoreTheSegmentsAtEverySample) {
  const scene::Scene reference = scene::load_scene((kSourceDir / "jobs" / "scenes" / "qj215_validation.toml").string());
  EXPECT_EQ(reference.output.segment_every, 5);
  const int campaigns = for_each_qj215_campaign_scene(
      [](const std::string&, const scene::Scene& s) { EXPECT_EQ(s.output.segment_every, 1); });
  EXPECT_EQ(campaigns, 16);
}

// The validation scene ships the trapezoidal rule with the pocket factor on the touching ball and the
// cage (perf/studies/results/pocket_convergence.md); every campaign over it keeps the solver its stored
// results were made with: Adams of unlimited order, no pocket factor, rtol 1e-6 unless it sweeps or
// sets another. The scene itself must differ, or the pins would be untested.
TEST(JobScenes, QJ215CampaignsKeepTheSolverOfTheirStoredResults) {
  const scene::Scene reference = scene::load_scene((kSourceDir / "jobs" / "scenes" / "qj215_validation.toml").string());
  ASSERT_EQ(reference.solver.max_order, 2);
  ASSERT_GT(reference.solver.pocket_tolerance_factor, 1.0);
  const int campaigns = for_each_qj215_campaign_scene([](const std::string& name, const scene::Scene& s) {
    EXPECT_EQ(s.solver.method, scene::IntegrationMethod::adams);
    EXPECT_EQ(s.solver.max_order, 12);
    EXPECT_EQ(s.solver.pocket_tolerance_factor, 1.0);
    EXPECT_FALSE(s.solver.pocket_tolerance_cage);
    EXPECT_EQ(s.solver.element_velocity_frame, scene::ElementVelocityFrame::bearing);
    if (name.find("rtol") == std::string::npos) {
      EXPECT_EQ(s.solver.rtol, 1e-6);
    }
  });
  EXPECT_EQ(campaigns, 16);
}

}  // namespace
}  // namespace raceway::driver
