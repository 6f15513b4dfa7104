// `raceway atlas FILE -o DIR [--resume] [--check] [--ranks N]`: the cage-stability atlas (docs/atlas.md),
// a launcher of the Python driver raceway_atlas.py beside the report's script (io/report/), which runs
// each point with this executable's `raceway run`.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace raceway::driver {

struct AtlasRequest {
  std::string atlas_file, output_dir;
  bool resume = false, check = false;
  int ranks = 1;  ///< points run at a time (each `raceway run` on one rank), the default batch size
};

/// Adds the atlas command to the command line; returns it (parsed: `*command`).
CLI::App* add_atlas_command(CLI::App& app, AtlasRequest& request);

/// Runs the atlas driver and waits for it: its exit code (0 done, 1 a point failed, 2 bad input, 3
/// numpy or scikit-learn missing, 4 stopped by a signal, which this process passes on to it), 1 when
/// it cannot be started. Refused under mpirun (`size` > 1, exit 2 on every rank): the driver starts
/// its own runs, and a child of an MPI job's rank would take itself for that rank.
int atlas_command(const AtlasRequest& request, int rank, int size);

}  // namespace raceway::driver
