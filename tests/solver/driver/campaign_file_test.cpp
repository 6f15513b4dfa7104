// Campaign files refused before any scene runs (solver/driver/campaign_file.hpp, campaign_check.hpp,
// campaign_record.hpp): one test per mistake, each checking the file, line, key and reason of the
// error; a valid file beside each (the check is not a blanket refusal); and random mutations of a
// valid file, each read or refused with a SceneError, never another exception.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>

#include "io/scene/scene_parser.hpp"
#include "solver/driver/campaign_check.hpp"
#include "solver/driver/campaign_file.hpp"
#include "solver/driver/campaign_record.hpp"

namespace raceway::driver {
namespace {

namespace fs = std::filesystem;

const std::string kScene = std::string(RACEWAY_SOURCE_DIR) + "/jobs/scenes/default.toml";

/// A scratch folder of the test, removed at its end.
class CampaignFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / fmt_name(info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  static std::string fmt_name(const std::string& test) { return "raceway_campaign_file_" + test + "_" + std::to_string(getpid()); }

  /// Writes the campaign text (the header below, then `body`) and returns its path.
  std::string write(const std::string& body, const std::string& name = "c.toml") const {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << "[campaign]\nscene = \"" << kScene << "\"\n" << body;
    return path;
  }
  /// Expects load_campaign (and the output check) to refuse the file naming line, key and reason.
  void refused(const std::string& body, int line, const std::string& key, const std::string& reason) const {
    const std::string path = write(body);
    try {
      Campaign c = load_campaign(path);
      check_campaign_outputs(c);
      FAIL() << "accepted:\n" << body;
    } catch (const scene::SceneError& e) {
      EXPECT_EQ(e.file(), path);
      EXPECT_EQ(e.line(), line) << e.what();
      EXPECT_EQ(e.key(), key) << e.what();
      EXPECT_NE(e.reason().find(reason), std::string::npos) << "expected '" << reason << "' in: " << e.what();
    }
  }
  Campaign accepted(const std::string& body) const {
    Campaign c = load_campaign(write(body));
    check_campaign_outputs(c);
    return c;
  }
  fs::path dir_;
};

// Lines: 1 [campaign], 2 scene, then the body's.
const std::string kRun = "end_time = \"10 ms\"\n";  // line 3

TEST_F(CampaignFileTest, RangeToInfinityIsRefusedBeforeItsFirstValue) {
  refused(kRun + "[[axis]]\nkey = \"inner_ring.speed\"\nrange = [1000, inf, 1000]\nunit = \"rpm\"\n", 6, "axis[0].range",
          "must be finite numbers, got [1000, inf, 1000]");
  refused(kRun + "[[axis]]\nkey = \"inner_ring.speed\"\nrange = [-inf, 1000, 1000]\nunit = \"rpm\"\n", 6, "axis[0].range",
          "must be finite");
  refused(kRun + "[[axis]]\nkey = \"inner_ring.speed\"\nrange = [1000, 2000, nan]\nunit = \"rpm\"\n", 6, "axis[0].range",
          "must be finite");
  EXPECT_EQ(accepted(kRun + "[[axis]]\nkey = \"inner_ring.speed\"\nrange = [1000, 2000, 500]\nunit = \"rpm\"\n").scenes.size(), 3u);
}

TEST_F(CampaignFileTest, TooManyScenesAreRefusedBeforeTheyAreListed) {
  refused(kRun + "[[axis]]\nkey = \"inner_ring.speed\"\nrange = [1, 1e9, 1]\nunit = \"rpm\"\n", 6, "axis[0].range",
          "1e+09 values (1 to 1000000000 in steps of 1); a campaign has at most 10000 scenes");
  // Two axes of 200 values each: 40000 scenes in the product.
  refused(kRun + "[[axis]]\nkey = \"inner_ring.speed\"\nrange = [1, 200, 1]\nunit = \"rpm\"\n"
                 "[[axis]]\nkey = \"inner_ring.load.fy\"\nrange = [-200, -1, 1]\nunit = \"N\"\n",
          1, "campaign.sweep", "the product of the axes is 4e+04 scenes (200 x 200); a campaign has at most 10000");
  // A step too small to move the value: the same value twice.
  refused(kRun + "[[axis]]\nkey = \"inner_ring.speed\"\nrange = [1e17, 1.000000000000001e17, 1]\nunit = \"rpm\"\n", 6,
          "axis[0].values", "is given twice");
}

TEST_F(CampaignFileTest, NegativeSettlingIsRefused) {
  refused(kRun + "settling_revolutions = -0.5\n", 4, "campaign.settling_revolutions", "expected a number of at least 0");
  refused(kRun + "settling_time = \"-1 ms\"\n", 4, "campaign.settling_time", "must not be negative");
  refused(kRun + "settling_time = \"1 ms\"\nsettling_revolutions = 1\n", 4, "campaign.settling_time",
          "give either settling_revolutions or settling_time");
  refused(kRun + "settling_time = \"10 ms\"\n", 4, "campaign.settling_time", "is not shorter than the run");
  EXPECT_EQ(accepted(kRun + "settling_time = \"0 s\"\n").scenes[0].settling_time, 0.0);
  EXPECT_EQ(accepted("revolutions = 1\nsettling_revolutions = 0\n").scenes[0].settling_time, 0.0);
}

TEST_F(CampaignFileTest, RanksPerSceneIsAWholeNumber) {
  for (const std::string bad : {"1e10", "0.5", "0", "-1", "\"2\"", "10000000000"})
    refused(kRun + "ranks_per_scene = " + bad + "\n", 4, "campaign.ranks_per_scene", "expected a whole number from 1 to 1048576");
  EXPECT_EQ(accepted(kRun + "ranks_per_scene = 2\n").ranks_per_scene, 2);
}

TEST_F(CampaignFileTest, TwoAxesWithOneNameAreRefused) {
  refused(kRun + "[[axis]]\nkey = \"inner_ring.speed\"\nname = \"x\"\nvalues = [\"1000 rpm\"]\n"
                 "[[axis]]\nkey = \"inner_ring.load.fy\"\nname = \"x\"\nvalues = [\"-100 N\"]\n",
          8, "axis[1].name", "axis[0] and axis[1] have one column name 'x'");
  // A name that is another axis's SI column, or a column of the table, or not a file name.
  refused(kRun + "[[axis]]\nkey = \"inner_ring.speed\"\nname = \"x\"\nvalues = [\"1000 rpm\"]\n"
                 "[[axis]]\nkey = \"inner_ring.load.fy\"\nname = \"x_si\"\nvalues = [\"-100 N\"]\n",
          8, "axis[1].name", "one column name");
  refused(kRun + "[[axis]]\nkey = \"inner_ring.speed\"\nname = \"status\"\nvalues = [\"1000 rpm\"]\n", 4, "axis[0].name",
          "'status' is a column of the table already");
  refused(kRun + "[[axis]]\nkey = \"inner_ring.speed\"\nname = \"a/b\"\nvalues = [\"1000 rpm\"]\n", 6, "axis[0].name",
          "cannot name a column");
}

TEST_F(CampaignFileTest, OneKeySweptByTwoAxesIsRefused) {
  refused(kRun + "[[axis]]\nkey = \"inner_ring.speed\"\nvalues = [\"1000 rpm\"]\n"
                 "[[axis]]\nkey = \"inner_ring.speed\"\nname = \"again\"\nvalues = [\"2000 rpm\"]\n",
          7, "axis[1].key", "'inner_ring.speed' is swept by axis[0] ('inner_ring.speed') already");
  // A table and a key inside it set the same value.
  refused(kRun + "[[axis]]\nkey = \"inner_ring.load\"\nname = \"load\"\nvalues = [\"{ fy = \\\"-1 N\\\" }\"]\n"
                 "[[axis]]\nkey = \"inner_ring.load.fy\"\nvalues = [\"-2 N\"]\n",
          8, "axis[1].key", "is swept by axis[0] ('inner_ring.load') already");
  refused(kRun + "[[axis]]\nkey = \"speed\"\nvalues = [\"1000 rpm\"]\n", 5, "axis[0].key", "is not a scene key");
  // A unit beside values would be ignored.
  refused(kRun + "[[axis]]\nkey = \"inner_ring.speed\"\nvalues = [1000]\nunit = \"rpm\"\n", 7, "axis[0].unit",
          "unit applies to a range");
}

TEST_F(CampaignFileTest, SetFixingASweptKeyIsRefused) {
  refused(kRun + "set = { \"output.segments\" = false, \"inner_ring.speed\" = \"10 rpm\" }\n"
                 "[[axis]]\nkey = \"inner_ring.speed\"\nvalues = [\"1000 rpm\"]\n",
          4, "campaign.set", "'inner_ring.speed' is swept by axis[0] (line 5): `set` would fix a swept key");
  refused(kRun + "set = { \"scene.end_time\" = \"1 s\" }\n", 4, "campaign.set",
          "'scene.end_time' cannot be set: 'scene.end_time' is set by the campaign's run length (campaign.end_time)");
  refused("revolutions = 1\nsamples_per_revolution = 10\nset = { \"scene.output_interval\" = \"1 ms\" }\n", 5,
          "campaign.set", "'scene.output_interval' cannot be set");
  refused(kRun + "[[axis]]\nkey = \"scene.end_time\"\nvalues = [\"1 s\"]\n", 4, "axis[0].key", "cannot be swept");
  // Without samples_per_revolution the output interval is the scene's: `set` may give it.
  EXPECT_EQ(accepted(kRun + "set = { \"scene.output_interval\" = \"1 ms\" }\n").scenes.size(), 1u);
}

TEST_F(CampaignFileTest, AnOutputBeyondMaxSizeIsRefused) {
  // 1500 rpm: 1 revolution is 40 ms; 1e7 samples per revolution of the 8-roller model's hundreds of
  // values are tens of GB, beyond the default 4 GB.
  refused("revolutions = 1\nsamples_per_revolution = 1e7\n", 4, "campaign.samples_per_revolution",
          "scene s000: the output would be");
  // One scene of a sweep over its limit: named with its axis value, on the value's line.
  refused("end_time = \"40 ms\"\nset = { \"output.max_size\" = \"1 MB\" }\n[[axis]]\nkey = \"scene.output_interval\"\n"
          "name = \"dt\"\nvalues = [\"1 ms\", \"0.01 ms\"]\n",
          8, "axis[0].values", "scene s001, dt = 0.01 ms: the output would be");
  const Campaign c = accepted("end_time = \"40 ms\"\n[[axis]]\nkey = \"scene.output_interval\"\nvalues = [\"1 ms\", \"0.5 ms\"]\n");
  ASSERT_EQ(c.scenes.size(), 2u);
  EXPECT_GT(c.scenes[0].output_bytes, 0);
  // 41 and 81 samples of the same values.
  EXPECT_NEAR(c.scenes[1].output_bytes / c.scenes[0].output_bytes, 81.0 / 41.0, 1e-12);
}

TEST_F(CampaignFileTest, AResumeWithAnEditedCampaignIsRefusedNamingTheDifference) {
  const std::string sweep = "[[axis]]\nkey = \"inner_ring.speed\"\nname = \"speed\"\nvalues = [\n\"500 rpm\",\n\"1000 rpm\"]\n";
  const Campaign before = accepted(kRun + sweep);
  const std::string folder = (dir_ / "out").string();
  fs::create_directories(folder);
  record_identity(before, folder);
  EXPECT_NO_THROW(check_identity(before, folder));
  EXPECT_NO_THROW(check_identity(accepted("# a comment\n" + kRun + sweep), folder));  // the same campaign
  std::string edited = sweep;
  edited.replace(edited.find("1000 rpm"), 8, "3000 rpm");
  try {
    check_identity(accepted(kRun + edited), folder);
    FAIL() << "an edited campaign was accepted";
  } catch (const scene::SceneError& e) {
    EXPECT_EQ(e.line(), 9) << e.what();
    EXPECT_EQ(e.key(), "axis[0].values");
    EXPECT_NE(e.reason().find("s001 --set inner_ring.speed: '3000 rpm' here, '1000 rpm' in the folder"), std::string::npos)
        << e.what();
  }
  // Another run length; another name.
  EXPECT_THROW(check_identity(accepted("end_time = \"20 ms\"\n" + sweep), folder), scene::SceneError);
  EXPECT_THROW(check_identity(accepted("name = \"other\"\n" + kRun + sweep), folder), scene::SceneError);
  // An edited base scene.
  std::string base;
  {
    std::ifstream in(kScene);
    base.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string line11 = "end_time = \"0.1 s\"";
  base.replace(base.find(line11), line11.size(), "end_time = \"0.2 s\"");
  std::ofstream((dir_ / "base.toml").string()) << base;
  const std::string other = (dir_ / "other.toml").string();
  std::ofstream(other) << "[campaign]\nname = \"c\"\nscene = \"base.toml\"\n" << kRun << sweep;
  try {
    check_identity(load_campaign(other), folder);
    FAIL() << "an edited base scene was accepted";
  } catch (const scene::SceneError& e) {
    EXPECT_EQ(e.key(), "campaign.scene");
    EXPECT_NE(e.reason().find("base scene line 11: 'end_time = \"0.2 s\""), std::string::npos) << e.what();
  }
  // Outputs without a record are not taken for this campaign's.
  const std::string bare = (dir_ / "bare").string();
  fs::create_directories(bare);
  std::ofstream(bare + "/s000.h5.partial") << "";
  EXPECT_THROW(check_identity(before, bare), scene::SceneError);
  fs::remove(bare + "/s000.h5.partial");
  EXPECT_NO_THROW(check_identity(before, bare));
}

// Random mutations of a valid campaign file (a line dropped, doubled or swapped, a number or word
// replaced by an extreme one): each is read, or refused with a SceneError naming the file.
TEST_F(CampaignFileTest, MutationsAreReadOrRefusedWithAReason) {
  const std::vector<std::string> lines{
      "[campaign]", "scene = \"" + kScene + "\"", "sweep = \"product\"", "revolutions = 1",
      "settling_revolutions = 0.5", "samples_per_revolution = 40", "ranks_per_scene = 1",
      "set = { \"output.checkpoint_interval\" = \"5 ms\", \"scene.gravity\" = true }", "[[axis]]",
      "key = \"inner_ring.speed\"", "name = \"speed\"", "values = [\"1000 rpm\", \"1500 rpm\"]", "[[axis]]",
      "key = \"inner_ring.load.fy\"", "name = \"radial_load\"", "range = [-600, -300, 300]", "unit = \"N\""};
  const std::vector<std::string> extremes{"inf", "-inf", "nan", "0", "-1", "1e9", "1e308", "0.5", "1e-300",
                                          "\"\"", "\"x\"", "[]", "{}", "\"inner_ring.speed\"", "true", "[1, inf, 1]"};
  std::mt19937 random(20261127);
  int read = 0, refused_count = 0;
  for (int n = 0; n < 300; ++n) {
    std::vector<std::string> m = lines;
    for (int edits = 1 + static_cast<int>(random() % 3); edits > 0; --edits) {
      const std::size_t i = random() % m.size(), j = random() % m.size();
      switch (random() % 4) {
        case 0: m.erase(m.begin() + static_cast<long>(i)); break;
        case 1: m.insert(m.begin() + static_cast<long>(i), m[j]); break;
        case 2: std::swap(m[i], m[j]); break;
        default: {
          const std::size_t eq = m[i].find(" = ");
          if (eq != std::string::npos) m[i] = m[i].substr(0, eq + 3) + extremes[random() % extremes.size()];
        }
      }
    }
    std::string text;
    for (const std::string& l : m) text += l + "\n";
    const std::string path = (dir_ / "fuzz.toml").string();
    std::ofstream(path) << text;
    try {
      Campaign c = load_campaign(path);
      check_campaign_outputs(c);
      ++read;
    } catch (const scene::SceneError& e) {
      ++refused_count;
      EXPECT_FALSE(e.reason().empty()) << text;
      EXPECT_FALSE(e.file().empty()) << e.what() << "\n" << text;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not a SceneError: " << e.what() << "\n" << text;
    }
  }
  EXPECT_GT(read, 10);  // the mutations are not all fatal: the test sees both outcomes
  EXPECT_GT(refused_count, 100);
}

}  // namespace
}  // namespace raceway::driver
