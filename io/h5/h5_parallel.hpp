// The parallel part of the output (docs/output_layout.md, "Who writes"): the rows of the series that
// several ranks share (the segment diagnostics: each rank writes the cells of the segments it
// evaluated), written by every rank of a communicator together through HDF5's MPI-IO driver with
// collective transfers. H5SeriesWriter (rank 0) decides when; the other ranks are brought into the
// call by the executor's output command (scheduler/mpi_executor.hpp).
#pragma once

#include <mpi.h>

#include <functional>
#include <string>
#include <vector>

#include "io/h5/shared_rows.hpp"

namespace raceway::h5 {

/// Collective over `comm`: every rank calls it at the same point. Rank 0's `file` and list (paths,
/// row sizes, first rows, row counts, in its order) are broadcast; on the other ranks `file` and
/// `rows` are replaced by them
/// and `fill` is called for each entry to give that rank's cells. Then every rank opens `file`
/// with the MPI-IO driver, and for each entry in order extends the dataset (H5Dset_extent) and
/// writes its cells (one collective H5Dwrite: HDF5 gathers each chunk's cells on one rank, which
/// filters and stores it), and closes the file. The file must be closed by every other writer of
/// this process (rank 0 closes its own handle first). Returns "" or the first failure, the same
/// text on every rank (naming the rank, the file, the dataset and HDF5's reason); a rank that fails
/// keeps taking part in the remaining collective calls with nothing to write, so none waits for ever.
std::string write_shared_rows(MPI_Comm comm, std::string& file, std::vector<SharedRows>& rows,
                              const std::function<void(SharedRows&)>& fill);

}  // namespace raceway::h5
