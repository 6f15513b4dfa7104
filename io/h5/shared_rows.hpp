// One shared series' rows of a collective write (io/h5/h5_parallel.hpp), as one rank gives them.
// Without MPI: the serial writer (h5_series.hpp) and the run loop hand these around.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace raceway::h5 {

/// One shared series' rows of one collective write, as one rank gives them.
struct SharedRows {
  std::string path;               ///< the dataset (normalized, e.g. "/segments/ball_pocket/normal_force")
  std::size_t row_size = 0;       ///< values per row (the dataset's columns)
  std::size_t first_row = 0;      ///< rows already in the file
  std::size_t rows = 0;           ///< rows this write appends: the dataset's new extent is first_row + rows
  std::vector<std::size_t> cells; ///< this rank's cells, ascending: (row - first_row) * row_size + column
  std::vector<double> values;     ///< their values, one per cell
};

}  // namespace raceway::h5
