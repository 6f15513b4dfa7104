// The campaign's cost model and group sizes (solver/driver/campaign_plan.hpp): the predicted steps
// against the recorded QJ215 speed sweep, and the group size against makespans worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "solver/driver/campaign_file.hpp"
#include "solver/driver/campaign_plan.hpp"

namespace raceway::driver {
namespace {

const std::filesystem::path kSourceDir = RACEWAY_SOURCE_DIR;

/// perf/studies/results/replay_model.txt, qj215_validation on this machine: 1.26 at 2 ranks, 1.42 at 4, 1.46 at 8.
double qj215_speedup(int ranks) { return ranks == 2 ? 1.26 : ranks == 4 ? 1.42 : ranks == 8 ? 1.46 : NAN; }

TEST(CampaignGroups, ManyScenesOnFewRanksRunOneRankEach) {
  // 8 equal scenes on 2 ranks: 2 groups of 1 finish in 4 units, 1 group of 2 in 8 / 1.26 = 6.3.
  const auto choice = choose_group_size(2, std::vector<double>(8, 1.0), qj215_speedup);
  EXPECT_EQ(choice.ranks_per_group, 1);
  ASSERT_EQ(choice.reasons.size(), 3u);  // sizes 1 and 2, then the choice
  EXPECT_NE(choice.reasons[1].find("speed-up 1.26 (efficiency 0.63)"), std::string::npos) << choice.reasons[1];
}

TEST(CampaignGroups, FewScenesOnManyRanksShareThem) {
  // 2 equal scenes on 8 ranks: groups of 1: 1 unit (6 groups idle); of 2: 1 / 1.26; of 4: 1 / 1.42
  // (the shortest); of 8: 2 / 1.46.
  const auto choice = choose_group_size(8, {1.0, 1.0}, qj215_speedup);
  EXPECT_EQ(choice.ranks_per_group, 4);
  EXPECT_NE(choice.reasons.back().find("chosen: 4 ranks per scene"), std::string::npos) << choice.reasons.back();
  // Sizes without a prediction are skipped: without 4, groups of 2 (1 / 1.26 against 2 / 1.46).
  const auto without4 = choose_group_size(8, {1.0, 1.0}, [](int p) { return p == 4 ? NAN : qj215_speedup(p); });
  EXPECT_EQ(without4.ranks_per_group, 2);
  EXPECT_EQ(without4.reasons.size(), 5u);  // sizes 1, 2 and 8; the sizes without a prediction; the choice
  EXPECT_NE(without4.reasons[3].find("without a predicted speed-up, not considered: 3, 4, 5, 6, 7"), std::string::npos)
      << without4.reasons[3];
}

TEST(CampaignGroups, OneLongSceneAmongShortOnesGetsTheRanks) {
  // Costs 10, 1, 1, 1 on 4 ranks, speed-up 1.8 at 2 and 3 at 4: groups of 1 end with the long scene
  // at 10; of 2 at 10 / 1.8 = 5.6; one group of 4 runs all in 13 / 3 = 4.3.
  const auto choice = choose_group_size(4, {10, 1, 1, 1}, [](int p) { return p == 2 ? 1.8 : p == 4 ? 3.0 : NAN; });
  EXPECT_EQ(choice.ranks_per_group, 4);
  // No prediction at all: 1 rank per scene.
  EXPECT_EQ(choose_group_size(4, {10, 1, 1, 1}, [](int) { return NAN; }).ranks_per_group, 1);
}

/// Rows of a campaign table: scene -> column -> text.
std::map<std::string, std::map<std::string, std::string>> read_table(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line, cell;
  std::vector<std::string> header;
  std::map<std::string, std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream fields(line);
    while (std::getline(fields, cell, ',')) cells.push_back(cell);
    if (header.empty()) {
      header = cells;
      continue;
    }
    for (std::size_t i = 0; i < cells.size() && i < header.size(); ++i) rows[cells[0]][header[i]] = cells[i];
  }
  return rows;
}

TEST(CampaignCost, PredictedStepsFollowTheRecordedSpeedSweep) {
  // docs/campaigns/qj215_speed: 20 revolutions at 1000..8000 r/min, the steps fall from 123121 to
  // 18054 (about 1 / speed). The model predicts each within 8 %.
  const Campaign c = load_campaign((kSourceDir / "jobs/campaigns/qj215_speed.toml").string());
  const auto table = read_table(kSourceDir / "docs/campaigns/qj215_speed/campaign_table.csv");
  ASSERT_EQ(table.size(), c.scenes.size());
  for (std::size_t i = 0; i < c.scenes.size(); ++i) {
    const double recorded = std::stod(table.at(c.scenes[i].id).at("steps"));
    EXPECT_NEAR(c.scenes[i].predicted_steps / recorded, 1.0, 0.08) << c.scenes[i].id;
    if (i > 0) {
      EXPECT_LT(c.scenes[i].predicted_steps, c.scenes[i - 1].predicted_steps);
    }
  }
  // The old model (revolutions x rolling elements) gave every scene the same cost; this one puts the
  // slowest scene, the longest recorded (86 s of 290 s), first.
  EXPECT_GT(c.scenes[0].predicted_cost, c.scenes[7].predicted_cost);
  // Twice the revolutions, twice the steps; a ring at rest still takes steps.
  EXPECT_DOUBLE_EQ(predict_scene_cost(40, 3000, 15).steps, 2 * predict_scene_cost(20, 3000, 15).steps);
  EXPECT_GT(predict_scene_cost(1, 0, 15).steps, 0);
  EXPECT_DOUBLE_EQ(predict_scene_cost(1, 3000, 15).wall_seconds, 0.5 * predict_scene_cost(1, 3000, 30).wall_seconds);
}

TEST(CampaignCost, TheModelIsTheShippedTable) {
  // data/campaign_cost_model.csv holds the constants; a model read from another file predicts by
  // its own (twice the steps per revolution, twice the steps; twice the reference elements, half
  // the wall time).
  const CostModel shipped = read_cost_model((kSourceDir / "data/campaign_cost_model.csv").string());
  EXPECT_DOUBLE_EQ(shipped.steps_per_revolution, 6.17e3);
  EXPECT_DOUBLE_EQ(shipped.wall_exponent, 0.541);
  CostModel other = shipped;
  other.steps_per_revolution *= 2;
  other.reference_elements *= 2;
  const SceneCost a = predict_scene_cost(shipped, 20, 3000, 15), b = predict_scene_cost(other, 20, 3000, 15);
  EXPECT_DOUBLE_EQ(b.steps, 2 * a.steps);
  EXPECT_DOUBLE_EQ(b.wall_seconds, a.wall_seconds);
  EXPECT_DOUBLE_EQ(predict_scene_cost(20, 3000, 15).steps, a.steps);  // the shipped model, found by RACEWAY_DATA_DIR
}

TEST(CampaignCost, ABadTableIsRefusedNamingFileAndLine) {
  const auto path = std::filesystem::temp_directory_path() / "raceway_bad_cost_model.csv";
  const auto refused = [&](const std::string& text, const std::string& expected) {
    std::ofstream(path) << text;
    try {
      read_cost_model(path.string());
      ADD_FAILURE() << "accepted: " << text;
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  const std::string header =
      "reference_rpm,reference_rolling_elements,steps_per_revolution,steps_per_revolution_exponent,wall_per_step_s,"
      "wall_per_step_exponent\n";
  refused("# c\nrpm,elements\n1,2\n", path.string() + ":2: expected the header");
  refused(header + "1000,15,6.17e3,-0.905,4.21e-4\n", path.string() + ":2: expected six numbers");
  refused(header + "1000,15,-6.17e3,-0.905,4.21e-4,0.5\n", ":2: expected six numbers");
  refused(header + "1000,15,6.17e3,nan,4.21e-4,0.5\n", ":2: expected six numbers");
  refused(header, "no line of values");
  std::filesystem::remove(path);
  refused("", "no line of values");
  std::filesystem::remove(path);
  try {
    read_cost_model(path.string());
    ADD_FAILURE() << "a missing file was read";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("cannot read the campaign cost model"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace raceway::driver
