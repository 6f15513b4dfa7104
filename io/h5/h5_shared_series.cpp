// H5SeriesWriter's shared series: their rows written by all ranks together at a flush (see
// h5_series.hpp, "Parallel output", and io/h5/h5_parallel.hpp).
#include <hdf5.h>

#include <fmt/format.h>

#include "io/h5/h5_series.hpp"
#include "io/h5/h5_support.hpp"

namespace raceway::h5 {

void H5SeriesWriter::close_handles() noexcept {
  for (auto& [path, s] : series_) {
    if (s.dataset >= 0) H5Dclose(s.dataset);
    s.dataset = -1;
  }
  if (file_ >= 0) H5Fclose(file_);
  file_ = -1;
}

void H5SeriesWriter::write_shared(bool whole_chunks_only) {
  std::vector<SharedRows> rows;
  std::vector<Series*> written;
  bool any = false;
  for (auto& [path, s] : series_) {
    if (!s.shared) continue;
    SharedRows r{path, s.row_size, s.rows_written, rows_to_write(s, whole_chunks_only), {}, {}};
    for (std::size_t c = 0; c < r.rows * s.row_size; ++c)
      if (s.mine[c] != 0) r.cells.push_back(c), r.values.push_back(s.buffer[c]);
    any = any || r.rows > 0;
    rows.push_back(std::move(r));
    written.push_back(&s);
  }
  if (!any) return;  // the other ranks are brought in only when there is something to write
  // This process's (sec2) handle is closed while every rank has the file open with the MPI-IO
  // driver: HDF5 would otherwise hand the collective open this handle's file, with its driver.
  if (H5Fflush(file_, H5F_SCOPE_LOCAL) < 0) fail("writing to disk before the collective write (H5Fflush)", "/");
  close_handles();
  try {
    shared_writer_(rows);
  } catch (const std::exception& e) {
    close_all();  // the writer is closed: nothing more of this run reaches the file
    throw std::runtime_error(fmt::format("H5SeriesWriter: {} (the file '{}' is left as that write left it)", e.what(),
                                         partial_path_));
  }
  h5::ErrorSilencer quiet;
  reopen_handles();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    Series& s = *written[i];
    const auto values = static_cast<std::ptrdiff_t>(rows[i].rows * s.row_size);
    s.rows_written += rows[i].rows;
    buffered_bytes_ -= std::min(buffered_bytes_, static_cast<std::size_t>(values) * sizeof(double));
    s.buffer.erase(s.buffer.begin(), s.buffer.begin() + values);
    s.mine.erase(s.mine.begin(), s.mine.begin() + values);
  }
}

}  // namespace raceway::h5
