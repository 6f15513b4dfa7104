// The run summary's rating lives (see life.hpp).
#include "io/report/life.hpp"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "io/report/process.hpp"
#include "io/report/report.hpp"

namespace raceway::report {

std::string life_json(const std::string& output, const std::string& scratch, std::string& why) {
  namespace fs = std::filesystem;
  const char* py_env = std::getenv("RACEWAY_PYTHON");
  const std::string python = py_env && *py_env ? py_env : "/usr/bin/python3";
  if (access(python.c_str(), X_OK) != 0) {
    why = fmt::format("no python interpreter at {} (set RACEWAY_PYTHON)", python);
    return {};
  }
  const std::string report_script = report_script_path();
  const fs::path script = fs::path(report_script).parent_path() / "raceway_life.py";
  std::error_code ec;
  if (report_script.empty() || !fs::is_regular_file(script, ec)) {
    why = "the life script raceway_life.py is not in share/raceway/report beside the executable";
    return {};
  }
  std::string error;
  const int status = run_process({python, script.string(), output, scratch}, error);
  if (status != 0) {
    why = status < 0    ? fmt::format("cannot run {}: {}", script.string(), error)
          : status == 3 ? fmt::format("{} lacks numpy or h5py", python)
                        : fmt::format("{} exited with {}", script.string(), status);
    return {};
  }
  std::ifstream in(scratch, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  in.close();
  fs::remove(scratch, ec);
  if (text.str().empty()) why = fmt::format("{} wrote nothing", script.string());
  return text.str();
}

}  // namespace raceway::report
