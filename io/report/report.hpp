// raceway post-processing: `raceway report OUT.h5`.
//
// Reads a spatial (ball-bearing) output file (layout: docs/output_layout.md, "Spatial (ball-bearing)
// runs"), computes the cage and ball metrics of io/report/cage_metrics.hpp over a time window,
// writes them to <dir>/summary.json and runs io/report/plot_report.py (/usr/bin/python3 with
// matplotlib, h5py and numpy) to draw PNGs into the same folder. <dir> defaults to <stem>_report
// beside the input. Reading: report_reader.cpp; the summary: report_summary.cpp; the rest:
// report.cpp.
//
// Serial and local: the file is opened read-only with the default (sec2) driver, so a report can run
// while no MPI job is around; call it on one rank only.
//
// Errors: a bad input (missing file, not HDF5, not a spatial run, a missing or malformed dataset)
// throws ReportInputError naming the file and the dataset; other failures (cannot write the
// summary, bad options, metrics that cannot be computed on the data) throw std::runtime_error or
// std::invalid_argument. Failing to draw the plots is not an error: ReportResult says why.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/json/summary_json.hpp"

namespace raceway::io {

/// The input file cannot be used for a report (exit code 2 of `raceway report`).
class ReportInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ReportOptions {
  std::string input;                         ///< the run's HDF5 file
  std::string output_dir;                    ///< empty: <input's folder>/<input's stem>_report
  std::optional<double> window_start;        ///< s; default: the second half of the run
  double bin_width_deg = 5;                  ///< azimuth bin width, (0, 360]
  std::optional<double> contact_threshold;   ///< N; default: 1 % of the peak pocket force, >= 1e-3 N
  bool plots = true;                         ///< run the plotting script
};

/// One segment kind's columns: ball index per column and the diagnostics read ([T x s], row-major).
struct SegmentColumns {
  std::vector<int> ball;
  std::map<std::string, std::vector<double>> diagnostic;
  std::size_t columns() const { return ball.size(); }
};

/// The series of a spatial run the report uses (row-major, T rows).
struct SpatialRun {
  std::string path;
  std::vector<double> time;                    ///< [T] s
  std::size_t balls = 0;
  std::vector<double> cage_position;           ///< [T x 3] m
  std::vector<double> cage_velocity;           ///< [T x 3] m/s
  std::vector<double> cage_angular_velocity;   ///< [T x 3] rad/s
  std::vector<double> epicyclic_speed;         ///< [T] rad/s
  std::vector<double> rolling_speed;           ///< [T] rad/s, at the loaded contact angle; empty in older files
  std::vector<double> ball_position;           ///< [T x balls x 3] m
  std::map<std::string, SegmentColumns> segments;  ///< by kind (ball_inner_groove, ball_pocket, ...)
  double pitch_radius = 0, pocket_clearance = 0, land_clearance = 0;  ///< m; NaN if not in the file
  std::vector<std::string> notes;              ///< what was missing or trimmed on reading
};

/// Reads a spatial run. Throws ReportInputError (see the file comment). Series of unequal length (a
/// .partial file) are cut to the shortest; a note says so.
SpatialRun read_spatial_run(const std::string& path);

/// The metrics of a run as the summary.json object. headlines (if given) receives a few one-line
/// texts of the main numbers for a log.
JsonObject summarize_spatial_run(const SpatialRun& run, const ReportOptions& options,
                                 std::vector<std::string>* headlines = nullptr);

struct ReportResult {
  std::string output_dir;
  std::string summary_path;
  JsonObject summary;
  std::vector<std::string> plots;   ///< PNG files written
  std::string plot_message;         ///< why there are no plots (empty when they were drawn)
  std::vector<std::string> notes;   ///< remarks on the input (missing optional datasets, ...)
  std::vector<std::string> headlines;  ///< the main numbers, one line each, for a log
};

/// The whole report: read, summarize, write summary.json, plot.
ReportResult make_report(const ReportOptions& options);

/// The plotting script: $RACEWAY_PLOT_SCRIPT if set, else <source dir>/io/report/plot_report.py.
std::string plot_script_path();

}  // namespace raceway::io
