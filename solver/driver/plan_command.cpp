#include "solver/driver/plan_command.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "io/scene/scene_parser.hpp"
#include "io/scene/units.hpp"
#include "solver/driver/data_files.hpp"
#include "solver/driver/plan_probe.hpp"
#include "solver/numerics/petsc_runtime.hpp"


namespace raceway::driver {

namespace {

using numerics::OptionsError;

/// An option is recommended only when it saves at least 5 % of the time: the table's timings (the
/// smaller CPU time of two runs) scatter by a few per cent.
constexpr double kLeastSaving = 0.95;
/// A scene deserves the most ranks whose predicted parallel efficiency is at least this (a rank
/// that returns less than 70 % of its time is better spent on another scene of a campaign).
constexpr double kLeastEfficiency = 0.7;

/// The fields of one CSV line. Written by hand: the table is Python's csv output (fields quoted
/// only when they hold a comma or a quote, quotes doubled), and ten lines of splitting do not
/// justify a CSV library as a dependency of the executable.
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') out.back() += '"', ++i;
    else if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) out.emplace_back();
    else if (c != '\r') out.back() += c;
  }
  return out;
}

double number_or_zero(const std::string& text) {
  if (text.empty()) return 0;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  return (*end == '\0' && errno != ERANGE && std::isfinite(v)) ? v : NAN;
}

std::string percent(double relative) { return fmt::format("{:.3g} %", 100 * relative); }

}  // namespace

std::vector<FidelityRow> read_fidelity_table(const std::string& path) {
  std::ifstream in(path);
  if (!in)
    throw OptionsError(
        fmt::format("{}: cannot read the fidelity table (shipped in share/raceway/data beside the executable: reinstall, "
                    "or give --table; written by perf/calibration/fidelity_table.py)", path));
  std::vector<std::string> header;
  std::vector<FidelityRow> rows;
  std::string line;
  const char* wanted[] = {"scene", "duration_s", "choice", "option", "overrides", "cpu_s", "cost_ratio",
                          "cage_speed_change", "max_load_change", "pocket_force_change", "note"};
  std::map<std::string, std::size_t> col;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.empty() || line[0] == '#') continue;
    const auto f = csv_fields(line);
    if (header.empty()) {
      header = f;
      for (const char* name : wanted) {
        const auto it = std::find(header.begin(), header.end(), name);
        if (it == header.end())
          throw OptionsError(fmt::format("{}:{}: the header has no column '{}'", path, number, name));
        col[name] = static_cast<std::size_t>(it - header.begin());
      }
      continue;
    }
    if (f.size() != header.size())
      throw OptionsError(fmt::format("{}:{}: {} fields, the header has {}", path, number, f.size(), header.size()));
    FidelityRow r{f[col["scene"]], f[col["duration_s"]], f[col["choice"]], f[col["option"]],
                  f[col["overrides"]], f[col["note"]]};
    r.cpu_s = number_or_zero(f[col["cpu_s"]]);
    r.cost_ratio = number_or_zero(f[col["cost_ratio"]]);
    r.change = {number_or_zero(f[col["cage_speed_change"]]), number_or_zero(f[col["max_load_change"]]),
                number_or_zero(f[col["pocket_force_change"]])};
    if (!std::isfinite(r.cost_ratio) || !std::isfinite(r.cpu_s) ||
        std::any_of(r.change.begin(), r.change.end(), [](double c) { return !std::isfinite(c); }))
      throw OptionsError(fmt::format("{}:{}: a number column holds something that is not a number", path, number));
    rows.push_back(std::move(r));
  }
  return rows;
}

Target parse_target(const std::string& text) {
  const auto eq = text.find('=');
  const std::string names = fmt::format("{}", fmt::join(kQuantities, ", "));
  if (eq == std::string::npos)
    throw OptionsError(fmt::format("--target '{}': expected QUANTITY=TOLERANCE (quantities: {})", text, names));
  const std::string name = text.substr(0, eq);
  std::string value = text.substr(eq + 1);
  Target t;
  const auto it = std::find(kQuantities.begin(), kQuantities.end(), name);
  if (it == kQuantities.end())
    throw OptionsError(fmt::format("--target '{}': unknown quantity '{}' (quantities: {})", text, name, names));
  t.quantity = static_cast<int>(it - kQuantities.begin());
  double scale = 1;
  if (!value.empty() && value.back() == '%') value.pop_back(), scale = 0.01;
  const double v = value.empty() ? NAN : number_or_zero(value);
  if (!(v > 0) || !std::isfinite(v))
    throw OptionsError(
        fmt::format("--target '{}': the tolerance must be a positive number (relative, or with %)", text));
  t.tolerance = v * scale;
  return t;
}

namespace {

/// The measured rows of combinations ("combination" rows: several choices at once, run by
/// perf/calibration/fidelity_table.py for the plans it checks), by their overrides.
std::map<std::string, const FidelityRow*> measured_combinations(const std::vector<FidelityRow>& rows) {
  std::map<std::string, const FidelityRow*> out;
  for (const auto& r : rows)
    if (r.choice == "combination" && r.cost_ratio > 0) out[r.overrides] = &r;
  return out;
}

/// A candidate's cost and changes: measured when the table holds its combination of overrides
/// (rank rows aside: they change nothing and scale the time), else the options' product and sum.
void predict(Recommendation& c, const std::map<std::string, const FidelityRow*>& measured) {
  std::string key;
  double rank_ratio = 1;
  int with_overrides = 0;
  for (const auto* r : c.chosen) {
    c.cost_ratio *= r->cost_ratio;
    for (std::size_t q = 0; q < 3; ++q) c.change[q] += r->change[q];
    if (r->overrides.empty()) rank_ratio *= r->cost_ratio;
    else key += (key.empty() ? "" : " ") + r->overrides, ++with_overrides;
  }
  const auto it = with_overrides > 1 ? measured.find(key) : measured.end();
  if (it == measured.end()) return;
  c.measured = true;
  c.cost_ratio = it->second->cost_ratio * rank_ratio;
  c.change = it->second->change;
}

}  // namespace

Recommendation recommend(const std::vector<FidelityRow>& rows, const std::vector<Target>& targets) {
  // The options per choice, in the table's order; index 0 of each is "as shipped" (nullptr).
  std::vector<std::string> choices;
  std::map<std::string, std::vector<const FidelityRow*>> options;
  for (const auto& r : rows) {
    if (r.choice == "reference" || r.choice == "combination" || r.cost_ratio <= 0 || r.cost_ratio > kLeastSaving)
      continue;
    if (!options.count(r.choice)) choices.push_back(r.choice), options[r.choice] = {nullptr};
    options[r.choice].push_back(&r);
  }
  const auto measured = measured_combinations(rows);
  Recommendation best;
  std::vector<std::size_t> pick(choices.size(), 0);
  // Every combination (an odometer over the choices): a few hundred at most.
  while (true) {
    Recommendation c;
    for (std::size_t i = 0; i < choices.size(); ++i)
      if (const FidelityRow* r = options[choices[i]][pick[i]]) c.chosen.push_back(r);
    predict(c, measured);
    const bool meets = std::all_of(targets.begin(), targets.end(), [&](const Target& t) {
      return c.change[static_cast<std::size_t>(t.quantity)] <= t.tolerance;
    });
    if (meets && (c.cost_ratio < best.cost_ratio ||
                  (c.cost_ratio == best.cost_ratio && c.chosen.size() < best.chosen.size())))
      best = c;
    std::size_t i = 0;
    while (i < choices.size() && ++pick[i] == options[choices[i]].size()) pick[i++] = 0;
    if (i == choices.size()) break;
  }
  return best;
}

namespace {

/// What the cost ratios multiply: the CPU time of the scene as shipped over a stated span, and where
/// the rows come from.
struct CostBase {
  double cpu_s = 0;       ///< 0: no time to multiply
  std::string span;       ///< "its 20 ms, measured", "its 0.2 s, predicted from the probe"
  std::string reference;  ///< empty: the rows were measured on this scene; else the scene they come from
};

void print_choices(const std::vector<FidelityRow>& rows, const CostBase& base) {
  if (base.reference.empty())
    std::puts("what each modelling choice costs and changes (one change at a time against the scene as shipped):");
  else
    std::printf("what each modelling choice costs and changes, TRANSFERRED from %s (measured there, one change at a\n"
                "time against %s as shipped; the cost here = this scene's probe cost x the cost ratio measured there):\n",
                base.reference.c_str(), base.reference.c_str());
  std::printf("  %-14s %-11s %8s %11s %11s %12s  %s\n", "choice", "option", "cost", "cage speed", "max load",
              "pocket force", "how");
  for (const auto& r : rows) {
    if ((r.choice == "reference" && r.option == "as shipped") || r.choice == "combination") continue;
    std::string how = r.choice == "reference" ? r.note : !r.overrides.empty() ? "--set " + r.overrides : r.note;
    if (r.cost_ratio <= 0) {
      std::printf("  %-14s %-11s %8s  %s (%s)\n", r.choice.c_str(), r.option.c_str(), "failed", how.c_str(),
                  r.note.c_str());
      continue;
    }
    if (!base.reference.empty() && base.cpu_s > 0) how = fmt::format("{:.3g} CPU s; {}", r.cost_ratio * base.cpu_s, how);
    std::printf("  %-14s %-11s %7.2fx %11s %11s %12s  %s\n", r.choice.c_str(), r.option.c_str(), r.cost_ratio,
                percent(r.change[0]).c_str(), percent(r.change[1]).c_str(), percent(r.change[2]).c_str(), how.c_str());
  }
  std::puts("  (cost: CPU time of a one-rank run, the wall time on an idle machine, against the scene as shipped;\n"
            "   changes: relative, of the means over the second half; options saving less than 5 % are within\n"
            "   the timing scatter and never recommended)");
}

}  // namespace

std::vector<std::string> split_overrides(const std::string& text) {
  std::vector<std::string> out;
  int depth = 0;
  std::string cur;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    depth += (c == '[') - (c == ']');
    if (c == ' ' && depth == 0 && text.find('=', i) != std::string::npos &&
        text.find('=', i) < text.find(' ', i + 1)) {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
      continue;
    }
    cur += c;
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

namespace {

std::string shell_quoted(const std::string& s) {
  if (s.find_first_of(" \"[]$'") == std::string::npos) return s;
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

void print_recommendation(const std::vector<FidelityRow>& rows, const std::vector<Target>& targets,
                          const CostBase& base, const FidelityRow* uncertainty) {
  const std::string on = base.reference.empty() ? "" : " on " + base.reference;
  for (const auto& t : targets) {
    const auto q = static_cast<std::size_t>(t.quantity);
    std::printf("target: %s within %s of the scene as shipped\n", kQuantities[q], percent(t.tolerance).c_str());
    if (uncertainty && uncertainty->change[q] > t.tolerance)
      std::printf("  note: below the reference's own uncertainty%s (%s at rtol / 10): not resolved by the data\n",
                  on.c_str(), percent(uncertainty->change[q]).c_str());
  }
  const Recommendation best = recommend(rows, targets);
  std::puts("combining choices: their costs multiply and their changes add (a bound when the changes are independent),\n"
            "unless the table holds the combination measured (perf/calibration/fidelity_table.py measures the plans it "
            "checks)");
  const std::string how = best.measured ? "measured" + on + (on.empty() ? "" : ", transferred")
                                        : on.empty() ? "predicted" : "predicted (effects measured" + on + ")";
  std::printf("recommended: %s cost %.2fx the scene as shipped", how.c_str(), best.cost_ratio);
  if (base.cpu_s > 0)
    std::printf(" (%.3g CPU seconds for %s, against %.3g s)", best.cost_ratio * base.cpu_s, base.span.c_str(), base.cpu_s);
  std::puts("");
  for (const auto& t : targets) {
    const auto q = static_cast<std::size_t>(t.quantity);
    std::printf("  %s change of %s %s (target %s)\n", how.c_str(), kQuantities[q],
                ((best.measured ? std::string() : std::string("at most ")) + percent(best.change[q])).c_str(),
                percent(t.tolerance).c_str());
  }
  if (best.chosen.empty()) std::puts("  the scene as shipped: no cheaper choice meets the targets");
  for (const auto* r : best.chosen) {
    std::printf("  %s: %s\n", r->choice.c_str(), r->option.c_str());
    if (r->overrides.empty()) std::printf("    %s\n", r->note.c_str());
    for (const auto& o : split_overrides(r->overrides)) std::printf("    --set %s\n", shell_quoted(o).c_str());
  }
}

}  // namespace

std::vector<RankRow> read_rank_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw OptionsError(fmt::format("{}: cannot read the rank table (shipped in share/raceway/data beside "
                                          "the executable: reinstall, or give --rank-table; written by "
                                          "perf/calibration/replay_model.py --table)", path));
  std::vector<RankRow> rows;
  std::string line;
  bool header = true;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.empty() || line[0] == '#') continue;
    const auto f = csv_fields(line);
    if (header) {
      if (f.size() != 6 || f[0] != "scene" || f[2] != "ranks" || f[5] != "efficiency")
        throw OptionsError(fmt::format("{}:{}: expected the header scene,network,ranks,predicted_wall_s,speedup,"
                                       "efficiency", path, number));
      header = false;
      continue;
    }
    RankRow r;
    const double ranks = f.size() == 6 ? number_or_zero(f[2]) : NAN;
    if (f.size() == 6) r = {f[0], f[1], static_cast<int>(ranks), number_or_zero(f[4]), number_or_zero(f[5])};
    if (f.size() != 6 || !(ranks >= 1) || ranks != std::floor(ranks) || !(r.speedup > 0) || !(r.efficiency > 0))
      throw OptionsError(fmt::format("{}:{}: expected six fields with ranks >= 1 and positive speed-up and "
                                     "efficiency, found '{}'", path, number, line));
    rows.push_back(std::move(r));
  }
  return rows;
}

int deserved_ranks(const std::vector<RankRow>& rows, const std::string& network) {
  int best = 1;
  for (const auto& r : rows)
    if (r.network == network && r.efficiency >= kLeastEfficiency) best = std::max(best, r.ranks);
  return best;
}

void print_rank_advice(const std::vector<RankRow>& rows, const std::string& path) {
  if (rows.empty()) {
    std::printf("ranks: no replay prediction for this scene in %s (perf/calibration/run_scaling_benchmarks.sh)\n", path.c_str());
    return;
  }
  std::set<std::string> networks;
  for (const auto& r : rows) networks.insert(r.network);
  std::printf("ranks (replay model of a recorded one-rank run, %s):\n", path.c_str());
  for (const auto& net : networks) {
    std::string line;
    for (const auto& r : rows)
      if (r.network == net && (r.ranks <= 4 || r.ranks % 8 == 0))
        line += fmt::format(" {}: {:.2f}", r.ranks, r.efficiency);
    std::printf("  network %s: efficiency by ranks%s\n", net.c_str(), line.c_str());
    std::printf("  -> %d rank(s): the most with a predicted efficiency of at least %.2f (each rank beyond gives "
                "back less than that share of its time)\n", deserved_ranks(rows, net), kLeastEfficiency);
  }
}

std::string fidelity_table_path() { return driver::data_file_path("fidelity_table.csv"); }

std::string rank_table_path() { return driver::data_file_path("rank_table.csv"); }

double predicted_speedup(const std::vector<RankRow>& rows, int ranks) {
  if (ranks == 1) return 1;
  for (const auto& r : rows)
    if (r.network == "here" && r.ranks == ranks) return r.speedup;
  return NAN;
}

CLI::App* add_plan_command(CLI::App& app, PlanOptions& options) {
  auto* plan = app.add_subcommand("plan", "what each modelling choice of a scene costs and changes, and the cheapest "
                                          "settings meeting --target (measured data: share/raceway/data)");
  plan->add_option("scene", options.scene_path,
                   "scene file (TOML): the table's rows of its file name, or (a scene the table has not measured) "
                   "a probe run of the scene and the effects measured on the table's scenes")
      ->required();
  plan->add_option("--target", options.targets,
                   "QUANTITY=TOLERANCE, relative or with %: cage_speed, max_load (roller/ball loads), pocket_force; "
                   "repeatable");
  plan->add_option("--set", options.overrides,
                   "set a scene key, validated like the file's (repeatable); the scene is then probed")
      ->allow_extra_args(false);
  plan->add_option("--probe-time", options.probe_time,
                   "simulated time of the probe run of a scene the table has not measured")
      ->capture_default_str();
  options.table_path = fidelity_table_path();
  plan->add_option("--table", options.table_path, "the fidelity table")->capture_default_str();
  options.rank_table_path = rank_table_path();
  plan->add_option("--rank-table", options.rank_table_path,
                   "predicted parallel efficiency per scene and rank count (perf/calibration/replay_model.py --table)")
      ->capture_default_str();
  return plan;
}

namespace {

/// --probe-time as seconds: a time quantity ("10 ms"), positive.
double parse_probe_time(const std::string& text) {
  double seconds = 0;
  try {
    seconds = scene::parse_quantity(text, scene::dim::time);
  } catch (const scene::UnitError& e) {
    throw OptionsError(fmt::format("--probe-time '{}': {}", text, e.what()));
  }
  if (!(seconds > 0)) throw OptionsError(fmt::format("--probe-time '{}': the probe needs a positive time", text));
  return seconds;
}

std::string seconds_text(double s) { return s >= 0.1 ? fmt::format("{:.3g} s", s) : fmt::format("{:.3g} ms", 1e3 * s); }

/// What the probe measured on this scene, and what it predicts for the scene's whole run.
void print_probe(const scene::Scene& scene, const Probe& p) {
  std::printf("probe, MEASURED on this scene at its own settings (one rank, %s): %s of simulated time (%.3g "
              "revolutions of the driven ring) in %.3g CPU s%s\n", p.method.c_str(), seconds_text(p.simulated_s).c_str(),
              p.revolutions, p.cpu_s, p.simulated_s >= scene.scene.end_time ? " (the whole run)" : "");
  std::printf("  start-up and the first %s: %.3g CPU s, %ld steps\n", seconds_text(p.window_start_s).c_str(),
              p.cpu_at_window_s, p.steps_at_window);
  std::printf("  over %s..%s: %.4g CPU s and %.4g steps per simulated second\n", seconds_text(p.window_start_s).c_str(),
              seconds_text(p.simulated_s).c_str(), p.cpu_per_second(), p.steps_per_second());
  if (p.revolutions_per_second() > 0)
    std::printf("  per revolution of the driven ring: %.4g CPU s, %.4g steps (%.4g revolutions per second)\n",
                p.cpu_per_second() / p.revolutions_per_second(), p.steps_per_second() / p.revolutions_per_second(),
                p.revolutions_per_second());
  else
    std::puts("  the driven ring does not turn during the probe: no cost per revolution");
  const double end = scene.scene.end_time;
  std::printf("predicted for the whole run (end_time %s): %.3g CPU s, %.4g steps (the probe to %s, then the rates "
              "above: a speed or load that changes after the probe changes them)\n", seconds_text(end).c_str(),
              p.predicted_cpu_s(end), p.predicted_steps(end), seconds_text(p.window_start_s).c_str());
}

/// The plan of a scene the table has measured itself (its file name, no --set).
void plan_measured(const scene::Scene& scene, const PlanOptions& options, const std::vector<FidelityRow>& rows,
                   const std::vector<Target>& targets) {
  const auto find = [&](const char* option) -> const FidelityRow* {
    for (const auto& r : rows)
      if (r.choice == "reference" && r.option == option) return &r;
    return nullptr;
  };
  const FidelityRow* reference = find("as shipped");
  std::printf("plan for %s (%s): MEASURED on this scene over its first %s with perf/calibration/fidelity_table.py\n",
              options.scene_path.c_str(), scene.scene.name.c_str(), reference ? reference->duration.c_str() : "?");
  const CostBase base{reference ? reference->cpu_s : 0, "its " + (reference ? reference->duration : "?"), ""};
  print_choices(rows, base);
  if (!targets.empty()) print_recommendation(rows, targets, base, find("uncertainty"));
}

/// The plan of any other scene: a probe run of it and the effects transferred from a table scene.
void plan_probed(const scene::Scene& scene, const PlanOptions& options, const std::vector<FidelityRow>& table,
                 const std::vector<Target>& targets) {
  const Transfer transfer = transfer_from_table(options.scene_path, options.overrides, table);
  const Probe probe = probe_scene(scene, options.probe_time.empty() ? kDefaultProbeSeconds
                                                                    : parse_probe_time(options.probe_time));
  std::printf("plan for %s (%s): not a scene of the fidelity table%s; a probe run of it, and the effects of the\n"
              "modelling choices measured on the table's scenes\n", options.scene_path.c_str(), scene.scene.name.c_str(),
              options.overrides.empty() ? "" : " (--set changes it)");
  print_probe(scene, probe);
  std::puts("which table scene the effects come from (an option applies when this scene with its --set is valid and "
            "differs):");
  for (const auto& line : transfer.reasons) std::printf("  %s\n", line.c_str());
  if (transfer.reference.empty()) {
    std::puts("no measured option applies to this scene: the probe's cost only, no recommendation");
    return;
  }
  std::printf("  -> %s; its changes are taken as they are, its cost ratios scale this scene's predicted cost\n",
              transfer.reference.c_str());
  const CostBase base{probe.predicted_cpu_s(scene.scene.end_time),
                      "its " + seconds_text(scene.scene.end_time) + ", predicted from the probe", transfer.reference};
  print_choices(transfer.rows, base);
  const FidelityRow* uncertainty = nullptr;
  for (const auto& r : transfer.rows)
    if (r.choice == "reference" && r.option == "uncertainty") uncertainty = &r;
  if (!targets.empty()) print_recommendation(transfer.rows, targets, base, uncertainty);
}

}  // namespace

int plan_command(const PlanOptions& options) {
  // Everything is checked before anything is printed: the scene, the targets, the tables.
  const scene::Scene scene = scene::load_scene(options.scene_path, options.overrides);
  std::vector<Target> targets;
  for (const auto& t : options.targets) targets.push_back(parse_target(t));
  if (!options.probe_time.empty()) parse_probe_time(options.probe_time);
  const std::string name = std::filesystem::path(options.scene_path).stem().string();
  const std::vector<FidelityRow> table = read_fidelity_table(options.table_path);
  std::vector<FidelityRow> rows;
  for (const auto& r : table)
    if (r.scene == name && options.overrides.empty()) rows.push_back(r);
  std::vector<RankRow> ranks;
  for (auto& r : read_rank_table(options.rank_table_path))
    if (r.scene == name && options.overrides.empty()) ranks.push_back(std::move(r));
  if (rows.empty()) plan_probed(scene, options, table, targets);
  else plan_measured(scene, options, rows, targets);
  std::printf("planar or spatial: %s; a %s bearing is built %s only\n",
              scene.scene.model == scene::ModelKind::spatial ? "spatial" : "planar",
              scene.bearing.is_ball_bearing() ? "ball" : "cylindrical roller",
              scene.bearing.is_ball_bearing() ? "spatial" : "planar");
  print_rank_advice(ranks, options.rank_table_path);
  if (targets.empty())
    std::puts("no --target given: add e.g. --target cage_speed=1% for the cheapest settings that meet it");
  return 0;
}

}  // namespace raceway::driver
