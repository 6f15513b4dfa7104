#include "solver/driver/campaign_check.hpp"

#include <fmt/format.h>

#include "io/scene/scene_parser.hpp"
#include "solver/bearing/model.hpp"
#include "solver/run/output_writer.hpp"

namespace raceway::driver {

namespace {

std::string values_of(const Campaign& c, const CampaignScene& s) {
  std::string out;
  for (std::size_t a = 0; a < c.axes.size(); ++a)
    out += fmt::format("{}{} = {}", out.empty() ? "" : ", ", c.axes[a].name, s.axis_values[a]);
  return out.empty() ? s.id : fmt::format("{}, {}", s.id, out);
}

}  // namespace

void check_campaign_outputs(Campaign& c) {
  for (CampaignScene& s : c.scenes) {
    const scene::Scene scene = campaign_scene(c, s);
    run::OutputEstimate estimate;
    try {
      estimate = run::estimate_output(bearing::build_model(scene), scene);
    } catch (const scene::SceneError& e) {
      throw scene::SceneError(c.file, c.key_lines.at("campaign"), "campaign",
                           fmt::format("scene {} cannot be built: {}", values_of(c, s), e.what()));
    }
    s.output_bytes = estimate.bytes;
    try {
      run::check_output_size(estimate, scene);
    } catch (const scene::SceneError& e) {
      // Blamed on what sets the sampling: the override of the output interval (an axis value, set,
      // samples_per_revolution), else the run length.
      std::size_t k = s.overrides.size();
      for (std::size_t i = 0; i < s.overrides.size(); ++i)
        if (s.overrides[i].starts_with("scene.output_interval=") || (k == s.overrides.size() && s.overrides[i].starts_with("scene.end_time=")))
          k = i;
      const bool known = k < s.overrides.size();
      throw scene::SceneError(c.file, known ? s.override_lines[k] : c.key_lines.at("campaign"), known ? s.override_keys[k] : "campaign",
                           fmt::format("scene {}: {} (in a campaign: fewer samples_per_revolution or revolutions, "
                                       "or \"output.max_size\" in set)", values_of(c, s), e.reason()));
    }
  }
}

}  // namespace raceway::driver
