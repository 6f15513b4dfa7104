// The atlas command (see atlas_command.hpp).
#include "solver/driver/atlas_command.hpp"

#include <signal.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include <fmt/format.h>

#include "io/report/process.hpp"
#include "io/report/report.hpp"
#include "solver/run/stop_signals.hpp"

namespace raceway::driver {

namespace {

/// Runs the atlas driver and waits for it, passing the first stop signal this process takes on to it
/// (it stops its runs and exits 4); a second ends this process (solver/run/stop_signals.hpp). Its
/// exit status, or -1 with `error` saying why.
int run_passing_stop(const std::vector<std::string>& args, std::string& error) {
  run::accept_stop_requests();
  bool passed = false;
  return report::run_process(args, error, [&](pid_t pid) {
    if (const int signal = run::stop_request().load(); signal != 0 && !passed) {
      kill(pid, signal);
      passed = true;
    }
  });
}

}  // namespace

CLI::App* add_atlas_command(CLI::App& app, AtlasRequest& request) {
  CLI::App* atlas = app.add_subcommand("atlas", "map cage stability over scene parameters: adaptive search, "
                                                "certified points, table and map (docs/atlas.md)");
  atlas->add_option("atlas_file", request.atlas_file, "atlas file (TOML)")->required();
  atlas->add_option("-o,--output-dir", request.output_dir, "folder of the atlas: state, points, atlas.csv/json/png");
  atlas->add_flag("--resume", request.resume, "continue the atlas in the folder (no finished point is lost)");
  atlas->add_flag("--check", request.check, "check the atlas file and its scenes, run nothing");
  atlas->add_option("--ranks", request.ranks, "points run at a time, each on one rank (default batch size)")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  return atlas;
}

int atlas_command(const AtlasRequest& request, int rank, int size) {
  namespace fs = std::filesystem;
  if (size > 1) {
    if (rank == 0)
      std::fprintf(stderr, "[raceway] error: atlas: start it without mpirun, which it does not need: it runs its points "
                           "itself, --ranks %d of them at a time\n", size);
    return 2;
  }
  const char* py_env = std::getenv("RACEWAY_PYTHON");
  const std::string python = py_env && *py_env ? py_env : "/usr/bin/python3";
  if (access(python.c_str(), X_OK) != 0) {
    std::fprintf(stderr, "[raceway] error: atlas: no python interpreter at %s (set RACEWAY_PYTHON)\n", python.c_str());
    return 1;
  }
  std::error_code ec;
  const fs::path script = fs::path(report::report_script_path()).parent_path() / "raceway_atlas.py";
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec || !fs::is_regular_file(script, ec)) {
    std::fprintf(stderr, "[raceway] error: atlas: raceway_atlas.py is not in share/raceway/report beside the "
                         "executable (reinstall)\n");
    return 1;
  }
  std::vector<std::string> args{python, script.string(), request.atlas_file, "--raceway", exe.string(),
                                "--ranks", std::to_string(request.ranks)};
  if (!request.output_dir.empty()) args.insert(args.end(), {"-o", request.output_dir});
  if (request.resume) args.emplace_back("--resume");
  if (request.check) args.emplace_back("--check");
  std::string error;
  const int status = request.check ? report::run_process(args, error) : run_passing_stop(args, error);
  if (status < 0) {
    std::fprintf(stderr, "[raceway] error: atlas: cannot run %s: %s\n", script.c_str(), error.c_str());
    return 1;
  }
  return status;
}

}  // namespace raceway::driver
