// `raceway campaign FILE -o DIR [--resume] [--only SCENE]`, `raceway campaign check FILE [--ranks N]`
// and `raceway campaign report DIR` (docs/campaigns.md).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace raceway::driver {

struct CampaignRequest {
  std::vector<std::string> args;  ///< FILE, or check FILE, or report DIR
  std::string output_dir;
  bool resume = false, check = false;
  std::string only;    ///< one scene (index in sweep order or id): a Slurm array task; no table
  int check_ranks = 0;  ///< check: the group size a campaign on this many ranks would choose
};

/// Adds the campaign command to the command line; returns it (parsed: `*command`).
CLI::App* add_campaign_command(CLI::App& app, CampaignRequest& request);

/// Runs on every rank of MPI_COMM_WORLD (MPI initialised with MPI_THREAD_MULTIPLE); returns the
/// exit code, the same on every rank.
int campaign_command(const CampaignRequest& request);

}  // namespace raceway::driver
