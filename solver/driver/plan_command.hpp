// `raceway plan SCENE [--target QUANTITY=TOL ...]`: the fidelity planner. It states what each
// modelling choice of the scene costs and what it changes, from measured data the product ships
// (data/fidelity_table.csv, installed in share/raceway/data; refreshed by
// perf/calibration/fidelity_table.py), and recommends the cheapest combination of choices whose
// predicted change meets every target, printed as `--set section.key=value` overrides; and, from the
// replay model's table (data/rank_table.csv, written by perf/calibration/replay_model.py --table: the
// model is Python and needs a recorded run, so the executable reads its predictions instead of
// porting it), how many ranks the scene deserves. A scene the table has not measured (or one changed
// by --set) is probed: a short run of it measures its cost, and the effects are transferred from
// the table's scene whose options apply to it (solver/driver/plan_probe.hpp).
#pragma once

#include <array>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace raceway::driver {

/// The quantities a target can name, in the table's column order.
inline constexpr std::array<const char*, 3> kQuantities{"cage_speed", "max_load", "pocket_force"};

/// One measured variant of a scene: a row of the fidelity table.
struct FidelityRow {
  std::string scene, duration, choice, option, overrides, note;
  double cpu_s = 0, cost_ratio = 0;         ///< cost_ratio: CPU time / the reference's; 0: the run failed
  std::array<double, 3> change{};           ///< relative change of each of kQuantities against the reference
};

/// A target: the largest relative change of one quantity.
struct Target {
  int quantity = 0;  ///< index in kQuantities
  double tolerance = 0;
};

/// One option chosen per choice (a row each; the shipped settings are no row) and its prediction.
struct Recommendation {
  std::vector<const FidelityRow*> chosen;
  double cost_ratio = 1;           ///< the product of the options' cost ratios, or the measured one
  std::array<double, 3> change{};  ///< the sum of the options' changes (a bound), or the measured ones
  bool measured = false;           ///< the table holds this combination, run as a whole
};

/// The rows of the table at PATH (a CSV file with a header line; '#' lines are comments). Throws
/// numerics::OptionsError naming the file and line when it cannot be read.
std::vector<FidelityRow> read_fidelity_table(const std::string& path);

/// "cage_speed=0.01" or "cage_speed=1%"; throws numerics::OptionsError with the reason.
Target parse_target(const std::string& text);

/// The cheapest combination of one option (or none) per choice whose predicted changes meet every
/// target; ROWS are the scene's rows (the reference rows and failed runs are skipped; a
/// "combination" row replaces the prediction of its set of overrides by its measurement).
Recommendation recommend(const std::vector<FidelityRow>& rows, const std::vector<Target>& targets);

/// The `--set` form of a row's overrides: "a.b=1 c.d=[3, 3]" -> {"a.b=1", "c.d=[3, 3]"}. An override
/// starts at a word followed by '=' after a space outside brackets.
std::vector<std::string> split_overrides(const std::string& text);

/// The shipped fidelity table (fidelity_table.csv of share/raceway/data beside the executable,
/// solver/driver/data_files.hpp), unless --table names another.
std::string fidelity_table_path();

struct PlanOptions {
  std::string scene_path;
  std::vector<std::string> targets;
  std::vector<std::string> overrides;  ///< --set section.key=VALUE
  std::string probe_time;              ///< --probe-time, a time quantity; empty: kDefaultProbeSeconds
  std::string table_path;
  std::string rank_table_path;
};

/// One row of the rank table (data/rank_table.csv, written by perf/calibration/replay_model.py --table):
/// the replay model's prediction for a scene at a rank count on a network.
struct RankRow {
  std::string scene, network;
  int ranks = 1;
  double speedup = 1, efficiency = 1;
};

/// The predicted speed-up of the scene whose rank-table rows are ROWS on RANKS ranks against one
/// rank, on this machine's network ("here"): perf/calibration/replay_model.py's prediction, which `raceway plan`
/// advises ranks by and `raceway campaign` sizes its groups by. The one function and the one table
/// that say it: NaN when the table has no prediction for RANKS, 1 for one rank.
double predicted_speedup(const std::vector<RankRow>& rows, int ranks);

/// The shipped rank table (rank_table.csv of share/raceway/data beside the executable), unless
/// --rank-table names another.
std::string rank_table_path();

/// The rows of the rank table at PATH; throws numerics::OptionsError naming the file and line.
std::vector<RankRow> read_rank_table(const std::string& path);

/// The most ranks whose predicted efficiency on NETWORK is at least 0.7 (1 when none).
int deserved_ranks(const std::vector<RankRow>& rows, const std::string& network);

/// Prints the rank advice for a scene's rows (a note when there are none).
void print_rank_advice(const std::vector<RankRow>& rows, const std::string& path);

/// Adds the `plan` subcommand to APP; the options land in OPTIONS.
CLI::App* add_plan_command(CLI::App& app, PlanOptions& options);

/// Runs `raceway plan`; returns the exit code (bad input throws, exit 2 by the caller's mapping).
int plan_command(const PlanOptions& options);

}  // namespace raceway::driver
