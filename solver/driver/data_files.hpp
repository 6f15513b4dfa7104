// The data the product ships (data/ of the source tree: the measured tables that `raceway plan` and
// `raceway campaign` read), found at run time beside the executable itself (/proc/self/exe), never
// through a source path compiled in: <exe dir>/../share/raceway/data (an installed tree, `cmake
// --install`) or <exe dir>/share/raceway/data (the build tree, where CMake links data/ in).
#pragma once

#include <string>
#include <vector>

namespace raceway::driver {

/// Where the shipped data file NAME may be, in the order they are tried: $RACEWAY_DATA_DIR/NAME when
/// that variable is set (a test executable outside the build tree's top, another set of tables),
/// then the installed tree's and the build tree's places beside the executable.
std::vector<std::string> data_file_candidates(const std::string& name);

/// The first of data_file_candidates(NAME) that is a file; when none is, the first candidate (so
/// that the reader's error names where the file was expected), or NAME itself without candidates.
std::string data_file_path(const std::string& name);

}  // namespace raceway::driver
