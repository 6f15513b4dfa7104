// What `raceway campaign check` adds to reading a campaign file (solver/driver/campaign_file.hpp):
// each scene's model is built and its output predicted from the sampling and the model, and held
// against the scene's [output] max_size, so a scene that would fail it deterministically is refused
// before any scene runs. No MPI here.
#pragma once

#include "solver/driver/campaign_file.hpp"

namespace raceway::driver {

/// Fills every scene's output_bytes (run::estimate_output, the estimate run_scene holds against
/// max_size before it creates the file). Throws scene::SceneError naming the campaign file, the line and
/// key that set the scene's output interval (an axis value, `set`, samples_per_revolution; else its
/// run length), the first scene over its limit with its axis values, the size and the limit.
void check_campaign_outputs(Campaign& campaign);

}  // namespace raceway::driver
