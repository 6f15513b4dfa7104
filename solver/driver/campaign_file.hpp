// A campaign file (jobs/campaigns/*.toml, docs/campaigns.md): a base scene, sweep axes and how long
// each scene runs, expanded into the list of scenes (each a set of --set overrides). No MPI here.
//
//   [campaign]
//   name = "qj215_speed"
//   scene = "../scenes/qj215_validation.toml"   # relative to the campaign file
//   sweep = "product"                          # or "zip" (axes of equal length, taken together)
//   revolutions = 20                           # of the driven ring; or end_time = "0.5 s"
//   settling_revolutions = 10                  # skipped by the metrics; or settling_time = "0.2 s"
//   samples_per_revolution = 600               # output interval (optional; else the scene's)
//   ranks_per_scene = 1                        # optional: else chosen from the predicted speed-up
//   set = { "output.checkpoint_interval" = "20 ms" }   # overrides for every scene
//   [[axis]]
//   key = "inner_ring.speed"
//   values = ["1000 rpm", "2000 rpm"]          # or range = [1000, 8000, 1000] with unit = "rpm"
//
// Every problem is an scene::SceneError naming the campaign file, the line, the key and the reason,
// also a value the scene rejects (the scene's reason follows).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "io/scene/scene.hpp"

namespace raceway::driver {

/// The most scenes a campaign may have: every one is parsed (and its model built) by `campaign
/// check` before anything runs, about a millisecond or more each; a larger sweep is refused (split it).
constexpr double kMaxCampaignScenes = 10000;
/// The most ranks per scene a campaign file may fix.
constexpr int kMaxRanksPerScene = 1 << 20;

struct CampaignAxis {
  std::string key;                  ///< the scene key swept ("inner_ring.speed")
  int line = 1;                     ///< the campaign file's line of the axis
  std::string name;                 ///< the table's column ("speed"; default: the key)
  std::vector<std::string> values;  ///< as --set values ("1000 rpm")
  std::vector<int> lines;           ///< the campaign file's line of each value
};

struct CampaignScene {
  std::string id;                      ///< "s000": the output is DIR/<id>.h5
  std::vector<std::string> axis_values;  ///< one per axis, as given
  std::vector<std::string> overrides;    ///< every --set of the scene, axis values and run length included
  std::vector<int> override_lines;       ///< the campaign file's line of each override
  std::vector<std::string> override_keys;  ///< the campaign key that gives each override ("axis[0].values")
  double end_time = 0, settling_time = 0;  ///< s
  double predicted_steps = 0;              ///< integration steps (solver/driver/campaign_plan.hpp)
  double predicted_cost = 0;               ///< one-rank wall time (s), for the order of dispatch
  double output_bytes = 0;                 ///< predicted output series (campaign_check.hpp); 0: not predicted
};

struct Campaign {
  std::string file, name, scene_path, sweep = "product";
  std::vector<std::string> metrics;
  int ranks_per_scene = 0;  ///< 0: not fixed, chosen from the predicted speed-up at run time
  int ranks_line = 1;       ///< the campaign file's line of ranks_per_scene
  std::vector<CampaignAxis> axes;
  std::vector<CampaignScene> scenes;
  std::string base_text;  ///< the base scene's text
  std::map<std::string, int> key_lines;  ///< the line of each key given ("campaign.name", "axis[0]")
};

/// Reads, expands and validates the campaign: every scene is parsed with its overrides, before
/// anything runs.
Campaign load_campaign(const std::string& path);

/// The scene of one entry, parsed (it was validated by load_campaign).
scene::Scene campaign_scene(const Campaign& campaign, const CampaignScene& scene);

/// The metrics a campaign table can hold (docs/campaigns.md).
const std::vector<std::string>& known_campaign_metrics();

}  // namespace raceway::driver
