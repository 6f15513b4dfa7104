// The raceway command line: the run driver (the one place besides scheduler/ and io/ where MPI
// lives). `raceway run [SCENE] -o OUT.h5`, `raceway check SCENE`, `raceway report OUT.h5`.
//
// Exit codes: 0 success; 2 bad input (scene, report input file); 3 integration failure (diagnosed); 1 other errors.
#include <mpi.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <memory>
#include <fmt/format.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "io/report.hpp"
#include "io/scene_parser.hpp"
#include "io/summary_json.hpp"
#include "solver/model.hpp"
#include "solver/newton_backends.hpp"
#include "solver/spatial_model.hpp"
#include "solver/run.hpp"

namespace {

using namespace raceway;

io::Scene load(const std::string& path) { return path.empty() ? io::default_scene() : io::load_scene(path); }

std::string clock_text(double s) {
  if (!std::isfinite(s) || s < 0) return "--:--";
  const long t = std::lround(s);
  return t >= 3600 ? fmt::format("{}:{:02}:{:02}", t / 3600, t / 60 % 60, t % 60) : fmt::format("{:02}:{:02}", t / 60, t % 60);
}

/// A progress bar on a terminal; plain log lines (every 10 %) otherwise.
class ProgressReporter {
 public:
  ProgressReporter() : tty_(isatty(STDERR_FILENO) != 0) {}
  void operator()(const solver::Progress& p) {
    const double frac = p.end_time > 0 ? p.time / p.end_time : 1.0;
    const double eta = frac > 0 ? p.wall_seconds * (1 - frac) / frac : NAN;
    if (tty_) {
      const int width = 30, filled = static_cast<int>(frac * width);
      std::fprintf(stderr, "\r[%s%s] %5.1f%%  t %.4g s  %.2f rev  wall %s  eta %s  steps %ld   ",
                   std::string(filled, '#').c_str(), std::string(width - filled, '.').c_str(), 100 * frac, p.time,
                   p.revolutions, clock_text(p.wall_seconds).c_str(), clock_text(eta).c_str(), p.steps);
      if (frac >= 1.0) std::fprintf(stderr, "\n");
      std::fflush(stderr);
    } else if (frac >= next_) {
      spdlog::info("t {:.6g} s of {:.6g} s ({:.0f} %), {:.2f} revolutions, wall {:.2f} s, eta {}, steps {}", p.time,
                   p.end_time, 100 * frac, p.revolutions, p.wall_seconds, clock_text(eta), p.steps);
      while (next_ <= frac) next_ += 0.1;
    }
  }

 private:
  bool tty_;
  double next_ = 0.1;
};

int run_command(const std::string& scene_path, const std::string& output, const std::string& summary_json) {
  const io::Scene scene = load(scene_path);
  spdlog::info("scene '{}' from {}", scene.scene.name, scene.source);
  solver::RunOptions options;
  options.output_path = output;
  ProgressReporter progress;
  options.on_progress = [&](const solver::Progress& p) { progress(p); };
  options.on_info = [](const std::string& s) { spdlog::info("{}", s); };
  const auto sum = solver::run_scene(scene, options);
  const auto json = sum.to_json();
  spdlog::info("done: {:.4g} s simulated ({:.2f} revolutions) in {:.2f} s wall; {} steps, {} rhs, {} jacobians, "
               "{} newton failures, {} error-test failures",
               sum.simulated_time_s, sum.driven_ring_revolutions, sum.wall_time_s, sum.stats.steps,
               sum.model_rhs_evaluations, sum.model_jacobian_evaluations, sum.stats.newton_failures,
               sum.stats.error_test_failures);
  spdlog::info("cage speed {:.3f} rpm (second half), epicyclic {:.3f} rpm, slip {:.3f} %", sum.cage_speed_rpm,
               sum.epicyclic_cage_speed_rpm, 100 * sum.cage_slip);
  spdlog::info("output written to {}", output);
  if (!summary_json.empty()) {
    io::write_json_file(summary_json, json);
    spdlog::info("summary written to {}", summary_json);
  }
  return 0;
}

/// `raceway report OUT.h5`: cage and ball metrics of a spatial run into <dir>/summary.json, plus PNGs.
int report_command(const io::ReportOptions& options) {
  const io::ReportResult res = io::make_report(options);
  for (const auto& note : res.notes) spdlog::warn("{}", note);
  for (const auto& line : res.headlines) spdlog::info("{}", line);
  spdlog::info("summary written to {}", res.summary_path);
  if (!res.plot_message.empty()) {
    if (options.plots) spdlog::warn("{}", res.plot_message);
    else spdlog::info("{}", res.plot_message);
  }
  if (!res.plots.empty()) spdlog::info("{} plots written to {}", res.plots.size(), res.output_dir);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  spdlog::set_default_logger(spdlog::stderr_color_mt("raceway"));  // messages on stderr, data on stdout
  spdlog::set_pattern("[raceway] %v");

  CLI::App app{"raceway: rolling-bearing dynamics (rings, rollers, cage) with CVODE"};
  app.require_subcommand(1);
  std::string scene_path, output = "raceway.h5", summary_json, petsc_options;
  auto* run = app.add_subcommand("run", "simulate a scene (the built-in default when none is given)");
  run->add_option("scene", scene_path, "scene file (TOML)");
  run->add_option("-o,--output", output, "HDF5 output file")->capture_default_str();
  run->add_option("--summary-json", summary_json, "write the run summary as JSON");
  run->add_option("--petsc-options", petsc_options,
                  "PETSc options for the petsc-bordered linear solver, e.g. \"-fieldsplit_1_pc_factor_mat_solver_type "
                  "mumps\"; override the scene's [solver] petsc_options");
  auto* check = app.add_subcommand("check", "validate a scene and print the model it would build");
  check->alias("plan");
  check->add_option("scene", scene_path, "scene file (TOML); the built-in default when none is given");
  check->add_option("--petsc-options", petsc_options, "PETSc options to validate with the scene's");
  io::ReportOptions report_options;
  double window_start = NAN;
  bool no_plots = false;
  auto* report = app.add_subcommand("report", "cage and ball metrics and plots of a spatial run's output file");
  report->add_option("output_file", report_options.input, "HDF5 output of a spatial run")->required();
  report->add_option("-o,--output-dir", report_options.output_dir, "folder for summary.json and the PNGs "
                     "(default: <stem>_report beside the file)");
  report->add_option("--window-start", window_start, "start of the analysis window in s (default: second half)");
  report->add_option("--bin-width", report_options.bin_width_deg, "azimuth bin width in deg")->capture_default_str();
  report->add_flag("--no-plots", no_plots, "write summary.json only");
  int code = 0;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    code = app.exit(e);
    MPI_Finalize();
    return code;
  }
  if (size > 1 && rank == 0)
    spdlog::warn("{} ranks: this build evaluates contacts on rank 0 only (the MPI executor is issue 4)", size);
  if (rank != 0) {
    MPI_Finalize();
    return 0;
  }
  // PETSc after MPI (so it leaves MPI_Finalize to us), on the master only: the linear algebra runs
  // there (DESIGN.md 5). Destroyed before MPI_Finalize.
  auto petsc = std::make_unique<solver::PetscRuntime>(petsc_options);
  try {
    if (*check) {
      const io::Scene scene = load(scene_path);
      solver::BorderedLayout layout;
      if (scene.scene.model == io::ModelKind::spatial) {
        const auto model = solver::build_spatial_model(scene);
        std::fputs(model.describe().c_str(), stdout);
        layout = {model.border_size, model.ball_count, solver::SpatialModel::ball_block_size};
      } else {
        const auto model = solver::build_model(scene);
        std::fputs(model.describe().c_str(), stdout);
        layout = {model.border_size, model.roller_count, (model.state_size - model.border_size) / model.roller_count};
      }
      std::puts(solver::prepare_linear_solver(scene.solver, layout).c_str());
      std::puts("scene OK");
    } else if (*report) {
      if (!std::isnan(window_start)) report_options.window_start = window_start;
      report_options.plots = !no_plots;
      code = report_command(report_options);
    } else {
      code = run_command(scene_path, output, summary_json);
    }
  } catch (const io::ReportInputError& e) {
    spdlog::error("{}", e.what());
    code = 2;
  } catch (const io::SceneError& e) {
    spdlog::error("{}", e.what());
    code = 2;
  } catch (const solver::OptionsError& e) {
    spdlog::error("{}", e.what());
    code = 2;
  } catch (const solver::IntegrationFailure& e) {
    spdlog::error("{}", e.what());
    code = 3;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    code = 1;
  }
  petsc.reset();
  MPI_Finalize();
  return code;
}
