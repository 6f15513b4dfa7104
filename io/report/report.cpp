// raceway report: the launcher of the Python report (see report.hpp).
#include "io/report/report.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>

#include "io/report/process.hpp"

namespace raceway::report {

namespace {

namespace fs = std::filesystem;

std::string number(double v) { return fmt::format("{:.17g}", v); }

}  // namespace

std::vector<std::string> report_arguments(const std::string& script, const ReportOptions& options) {
  std::vector<std::string> args{script, options.input};
  if (!options.output_dir.empty()) args.insert(args.end(), {"-o", options.output_dir});
  if (options.window_start) args.insert(args.end(), {"--window-start", number(*options.window_start)});
  args.insert(args.end(), {"--bin-width", number(options.bin_width_deg)});
  if (options.contact_threshold) args.insert(args.end(), {"--contact-threshold", number(*options.contact_threshold)});
  if (!options.plots) args.emplace_back("--no-plots");
  if (options.animate) args.emplace_back("--animate");
  if (options.xdmf) args.emplace_back("--xdmf");
  if (options.vtk) args.emplace_back("--vtk");
  return args;
}

std::string report_script_path() {
  if (const char* env = std::getenv("RACEWAY_REPORT_SCRIPT"); env && *env) return env;
  std::error_code ec;
  const fs::path exe_dir = fs::read_symlink("/proc/self/exe", ec).parent_path();
  if (ec) return {};
  for (const fs::path& candidate : {exe_dir / ".." / "share" / "raceway" / "report" / "raceway_report.py",
                                    exe_dir / "share" / "raceway" / "report" / "raceway_report.py"})
    if (fs::is_regular_file(candidate, ec)) return fs::weakly_canonical(candidate, ec).string();
  return {};
}

int run_report(const ReportOptions& options) {
  const char* py_env = std::getenv("RACEWAY_PYTHON");
  const std::string python = py_env && *py_env ? py_env : "/usr/bin/python3";
  const std::string install =
      "install python3, python3-matplotlib, python3-h5py and python3-numpy (scripts/bootstrap.sh)";
  if (access(python.c_str(), X_OK) != 0) {
    std::fprintf(stderr, "[raceway] error: report: no python interpreter at %s (set RACEWAY_PYTHON); %s\n",
                 python.c_str(), install.c_str());
    return 1;
  }
  const std::string script = report_script_path();
  if (script.empty()) {
    std::fprintf(stderr,
                 "[raceway] error: report: the report script raceway_report.py is not in share/raceway/report beside "
                 "the executable (set RACEWAY_REPORT_SCRIPT, or reinstall)\n");
    return 1;
  }
  std::vector<std::string> args = report_arguments(script, options);
  args.insert(args.begin(), python);
  std::string error;
  const int status = run_process(args, error);
  if (status < 0) {
    std::fprintf(stderr, "[raceway] error: report: cannot run %s %s: %s\n", python.c_str(), script.c_str(),
                 error.c_str());
    return 1;
  }
  if (status == 3) std::fprintf(stderr, "[raceway] error: report: %s lacks numpy or h5py; %s\n", python.c_str(),
                                install.c_str());
  return status;
}

}  // namespace raceway::report
