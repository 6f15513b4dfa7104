// The rating lives of a run for `raceway run --summary-json` (docs/life.md): the report's own
// calculation (report_life.py over the report's default window, the run's second half), run on the
// finished output file by raceway_life.py beside the report's script, so that the run summary and
// the report say the same lives. Serial and local: rank 0 calls it once the output is complete.
#pragma once

#include <string>

namespace raceway::report {

/// The `life` object of the output file `output` as JSON text, written through `scratch` (a file
/// path the script may use, removed after); empty with `why` saying why when there is none (no
/// interpreter or script, numpy or h5py missing, no race contacts in the output).
std::string life_json(const std::string& output, const std::string& scratch, std::string& why);

}  // namespace raceway::report
