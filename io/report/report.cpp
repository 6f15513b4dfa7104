// raceway report: the whole report of a spatial run: summary.json and the plots (see report.hpp;
// reading is in report_reader.cpp, the metrics in report_summary.cpp).
#include "io/report/report.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

extern char** environ;  // NOLINT: POSIX, for posix_spawn

#ifndef RACEWAY_SOURCE_DIR
#define RACEWAY_SOURCE_DIR "."
#endif

namespace raceway::io {

namespace {

namespace fs = std::filesystem;

bool executable(const std::string& p) { return !p.empty() && access(p.c_str(), X_OK) == 0; }

// Runs argv[0] with argv (no shell) and waits; returns the exit status, -1 if it could not start.
int run_process(const std::vector<std::string>& args, std::string& error) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ);
  if (rc != 0) {
    error = std::strerror(rc);
    return -1;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      error = std::strerror(errno);
      return -1;
    }
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  error = WIFSIGNALED(status) ? fmt::format("killed by signal {}", WTERMSIG(status)) : "ended abnormally";
  return -1;
}

// The output folder (created): options.output_dir, or <input's folder>/<input's stem>_report.
fs::path make_output_dir(const ReportOptions& options) {
  fs::path dir = options.output_dir;
  if (dir.empty()) {
    const fs::path in(options.input);
    dir = in.parent_path() / (in.stem().string() + "_report");
  }
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error(fmt::format("report: cannot create folder '{}': {}", dir.string(), ec.message()));
  return dir;
}

// The PNG files in dir, sorted.
std::vector<std::string> png_files(const fs::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (entry.path().extension() == ".png") out.push_back(entry.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

// Runs the plotting script into res.output_dir; fills res.plots, or res.plot_message with why not.
void draw_plots(const ReportOptions& options, ReportResult& res) {
  const char* py_env = std::getenv("RACEWAY_PYTHON");
  const std::string python = py_env && *py_env ? py_env : "/usr/bin/python3";
  const std::string script = plot_script_path();
  const std::string install =
      "install python3, python3-matplotlib, python3-h5py and python3-numpy (scripts/bootstrap.sh)";
  std::error_code ec;
  if (!executable(python)) {
    res.plot_message = fmt::format("plots skipped: no python interpreter at {}; {}", python, install);
    return;
  }
  if (!fs::is_regular_file(script, ec)) {
    res.plot_message = fmt::format("plots skipped: plotting script {} not found (set RACEWAY_PLOT_SCRIPT)", script);
    return;
  }
  // Remove stale plots so that the list below holds only what this run drew.
  for (const auto& stale : png_files(res.output_dir)) fs::remove(stale, ec);
  std::string error;
  const int status = run_process({python, script, options.input, res.summary_path, res.output_dir}, error);
  if (status == 3) {
    res.plot_message = fmt::format("plots skipped: {} lacks matplotlib, h5py or numpy; {}", python, install);
  } else if (status != 0) {
    res.plot_message = status < 0 ? fmt::format("plots failed: cannot run {} {}: {}", python, script, error)
                                  : fmt::format("plots failed: {} {} exited with code {}", python, script, status);
  }
  res.plots = png_files(res.output_dir);
  if (status == 0 && res.plots.empty()) res.plot_message = "plots failed: the plotting script wrote no PNG";
}

}  // namespace

std::string plot_script_path() {
  if (const char* env = std::getenv("RACEWAY_PLOT_SCRIPT"); env && *env) return env;
  return std::string(RACEWAY_SOURCE_DIR) + "/io/report/plot_report.py";
}

ReportResult make_report(const ReportOptions& options) {
  const SpatialRun run = read_spatial_run(options.input);
  ReportResult res;
  res.notes = run.notes;
  res.summary = summarize_spatial_run(run, options, &res.headlines);
  if (!res.notes.empty()) {
    std::string all;
    for (const auto& note : res.notes) all += (all.empty() ? "" : "; ") + note;
    res.summary.add("notes", all);
  }
  const fs::path dir = make_output_dir(options);
  res.output_dir = dir.string();
  res.summary_path = (dir / "summary.json").string();
  write_json_file(res.summary_path, res.summary);
  if (options.plots)
    draw_plots(options, res);
  else
    res.plot_message = "plots skipped (--no-plots)";
  return res;
}

}  // namespace raceway::io
