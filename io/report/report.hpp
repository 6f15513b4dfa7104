// raceway post-processing: `raceway report OUT.h5`.
//
// The report itself is Python (io/report/raceway_report.py, through the reader raceway_output.py):
// the metrics of a planar or spatial run (summary.json), the figures, the report page, and on
// request the animation and the ParaView (XDMF) file. This launcher finds the script beside the
// executable (an installed tree: <prefix>/bin/raceway and <prefix>/share/raceway/report/; the build
// tree: build/raceway and build/share/raceway/report/, links to the sources) and runs it with
// /usr/bin/python3 (or $RACEWAY_PYTHON), passing the options through; the script's exit code is the
// command's (0 done, 2 bad input, 3 numpy or h5py missing, 1 other).
//
// Serial and local: call it on one rank only.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace raceway::report {

struct ReportOptions {
  std::string input;                         ///< the run's HDF5 file
  std::string output_dir;                    ///< empty: <input's folder>/<input's stem>_report
  std::optional<double> window_start;        ///< s; default: the second half of the run
  double bin_width_deg = 5;                  ///< azimuth bin width, (0, 360]
  std::optional<double> contact_threshold;   ///< N; default: 1 % of the peak pocket force, >= 1e-3 N
  bool plots = true;                         ///< figures and the report page
  bool animate = false;                      ///< the animation (MP4 with ffmpeg, else GIF)
  bool xdmf = false;                         ///< OUT.xdmf beside the .h5 for ParaView
  bool vtk = false;                          ///< OUT_vtk/OUT.pvd: VTK PolyData files over time
};

/// The command line of the report script for these options (without the interpreter).
std::vector<std::string> report_arguments(const std::string& script, const ReportOptions& options);

/// The report script: $RACEWAY_REPORT_SCRIPT if set, else the first of
/// <exe dir>/../share/raceway/report/raceway_report.py and <exe dir>/share/raceway/report/raceway_report.py
/// that exists (exe dir: the folder of /proc/self/exe). Empty if none exists.
std::string report_script_path();

/// Runs the report; returns its exit code. Says on stderr why when there is no interpreter or no
/// script (exit code 1).
int run_report(const ReportOptions& options);

}  // namespace raceway::report
