#include "solver/driver/plan_probe.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <map>
#include <set>

#include "io/scene/scene_parameters.hpp"
#include "io/scene/scene_parser.hpp"
#include "solver/run/run.hpp"

namespace raceway::driver {

namespace {

namespace fs = std::filesystem;

/// CPU time of the whole process (the run's thread and the output's compressor), as the fidelity
/// table measures a run (user + system time of the child process).
double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// A temporary folder for the probe's output, removed with everything in it at the end of scope.
class TemporaryFolder {
 public:
  TemporaryFolder() {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = (fs::path(tmp && *tmp ? tmp : "/tmp") / "raceway-plan-XXXXXX").string();
    if (!mkdtemp(pattern.data()))
      throw std::runtime_error(fmt::format("plan: cannot create a temporary folder {} for the probe run", pattern));
    path_ = pattern;
  }
  ~TemporaryFolder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

/// Every resolved parameter of a scene as one line each, to tell whether an option changes it.
std::set<std::string> parameter_lines(const scene::Scene& scene) {
  std::set<std::string> out;
  for (const auto& p : scene::scene_parameters(scene)) {
    std::string line = p.key + "=" + (p.number ? fmt::format("{}", *p.number) : "") + p.word.value_or("");
    for (const double t : p.times) line += fmt::format(" t{}", t);
    for (const double v : p.values) line += fmt::format(" {}", v);
    out.insert(std::move(line));
  }
  return out;
}

}  // namespace

Probe probe_scene(const scene::Scene& scene, double probe_seconds) {
  scene::Scene shortened = scene;
  const double end = std::min(scene.scene.end_time, std::max(probe_seconds, 2 * scene.scene.output_interval));
  shortened.scene.end_time = end;
  const TemporaryFolder folder;
  run::RunOptions options;
  options.output_path = (folder.path() / "probe.h5").string();
  options.output_thread = false;  // as the fidelity table's runs (--output-thread off)
  options.on_info = [](const std::string&) {};
  Probe probe;
  const double cpu_start = process_cpu_seconds();
  // The window starts at the first output time at or after half the probe.
  options.on_progress = [&](const run::Progress& p) {
    if (probe.window_start_s > 0 || p.time < 0.5 * end - 1e-12 || p.time >= end - 1e-12) return;
    probe.window_start_s = p.time;
    probe.cpu_at_window_s = process_cpu_seconds() - cpu_start;
    probe.steps_at_window = p.steps;
    probe.revolutions_at_window = p.revolutions;
  };
  const run::RunSummary summary = run::run_scene(shortened, options);
  probe.cpu_s = process_cpu_seconds() - cpu_start;
  probe.simulated_s = summary.simulated_time_s;
  probe.steps = summary.stats.steps;
  probe.revolutions = summary.driven_ring_revolutions;
  probe.method = summary.method;
  return probe;
}

Transfer transfer_from_table(const std::string& scene_path, const std::vector<std::string>& overrides,
                             const std::vector<FidelityRow>& table) {
  const std::set<std::string> own = parameter_lines(scene::load_scene(scene_path, overrides));
  // Whether the option's overrides give a valid scene that differs from this one.
  const auto applies = [&](const FidelityRow& r) {
    std::vector<std::string> with(overrides);
    for (const auto& o : split_overrides(r.overrides)) with.push_back(o);
    try {
      return parameter_lines(scene::load_scene(scene_path, with)) != own;
    } catch (const std::exception&) {
      return false;  // not a key of this bearing, or a value this scene refuses
    }
  };
  std::vector<std::string> order;
  std::map<std::string, std::vector<FidelityRow>> applicable;
  std::map<std::string, int> options;
  for (const auto& r : table) {
    if (!applicable.count(r.scene)) order.push_back(r.scene), applicable[r.scene] = {};
    const bool option = r.choice != "reference" && r.choice != "combination" && !r.overrides.empty();
    options[r.scene] += option;
    if (r.choice == "reference" && r.option == "as shipped") applicable[r.scene].push_back(r);
    else if (!r.overrides.empty() && applies(r)) applicable[r.scene].push_back(r);
  }
  Transfer t;
  std::size_t best = 0;
  for (const auto& name : order) {
    const std::size_t n = static_cast<std::size_t>(std::count_if(
        applicable[name].begin(), applicable[name].end(),
        [](const FidelityRow& r) { return r.choice != "reference" && r.choice != "combination"; }));
    t.reasons.push_back(fmt::format("{}: {} of its {} measured options apply to this scene", name, n, options[name]));
    if (n > best) best = n, t.reference = name;
  }
  if (!t.reference.empty()) t.rows = applicable[t.reference];
  return t;
}

}  // namespace raceway::driver
