// Collective writes of shared series through HDF5's MPI-IO driver (see h5_parallel.hpp).
#include "io/h5/h5_parallel.hpp"

#include <hdf5.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <cerrno>

#include <algorithm>
#include <cstring>

#include <fmt/format.h>

#include "io/h5/h5_support.hpp"

namespace raceway::h5 {

namespace {

using h5::Handle;

/// Rank 0's file and list to every rank: the file and the paths as one string, the numbers as doubles.
void broadcast_list(MPI_Comm comm, int rank, std::string& file, std::vector<SharedRows>& rows) {
  std::string paths = file + '\n';
  std::vector<double> numbers;
  if (rank == 0)
    for (const SharedRows& r : rows) {
      paths += r.path + '\n';
      numbers.insert(numbers.end(), {static_cast<double>(r.row_size), static_cast<double>(r.first_row),
                                     static_cast<double>(r.rows)});
    }
  long long sizes[2] = {static_cast<long long>(paths.size()), static_cast<long long>(numbers.size())};
  MPI_Bcast(sizes, 2, MPI_LONG_LONG, 0, comm);
  paths.resize(static_cast<std::size_t>(sizes[0]));
  numbers.resize(static_cast<std::size_t>(sizes[1]));
  MPI_Bcast(paths.data(), static_cast<int>(paths.size()), MPI_CHAR, 0, comm);
  MPI_Bcast(numbers.data(), static_cast<int>(numbers.size()), MPI_DOUBLE, 0, comm);
  if (rank == 0) return;
  rows.assign(numbers.size() / 3, {});
  std::size_t start = paths.find('\n') + 1;
  file = paths.substr(0, start - 1);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::size_t end = paths.find('\n', start);
    rows[i].path = paths.substr(start, end - start);
    start = end + 1;
    rows[i].row_size = static_cast<std::size_t>(numbers[3 * i]);
    rows[i].first_row = static_cast<std::size_t>(numbers[3 * i + 1]);
    rows[i].rows = static_cast<std::size_t>(numbers[3 * i + 2]);
  }
}

/// This rank's cells as a file selection: one hyperslab per run of adjacent cells in a row.
bool select_cells(hid_t space, const SharedRows& r) {
  if (H5Sselect_none(space) < 0) return false;
  for (std::size_t i = 0; i < r.cells.size();) {
    std::size_t j = i + 1;
    const std::size_t row = r.cells[i] / r.row_size;
    while (j < r.cells.size() && r.cells[j] == r.cells[j - 1] + 1 && r.cells[j] / r.row_size == row) ++j;
    const hsize_t start[2] = {r.first_row + row, r.cells[i] % r.row_size}, count[2] = {1, j - i};
    if (H5Sselect_hyperslab(space, H5S_SELECT_OR, start, nullptr, count, nullptr) < 0) return false;
    i = j;
  }
  return true;
}

/// One entry: extend and write. Returns "" or HDF5's failure. `write` false: take part with nothing.
/// Every rank makes the same collective calls whatever fails on it (a rank that skipped one would
/// leave the others waiting in it): a failed step only empties what this rank writes.
std::string write_entry(hid_t file, hid_t dxpl, const SharedRows& r, bool write) {
  const Handle dataset(H5Dopen2(file, r.path.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dataset.ok()) return "opening the dataset (H5Dopen2): " + h5::error_text();
  std::string error;
  const hsize_t dims[2] = {r.first_row + r.rows, r.row_size};
  if (H5Dset_extent(dataset.get(), dims) < 0) error = "H5Dset_extent: " + h5::error_text();
  const Handle file_space(H5Dget_space(dataset.get()), H5Sclose);
  const hsize_t n = write && error.empty() ? r.cells.size() : 0;
  const Handle mem_space(H5Screate_simple(1, &n, nullptr), H5Sclose);
  if (!file_space.ok() || !mem_space.ok()) return "making the dataspaces: " + h5::error_text();
  bool selected = n > 0 ? select_cells(file_space.get(), r) : H5Sselect_none(file_space.get()) >= 0;
  if (!selected && error.empty()) error = "selecting the cells: " + h5::error_text();
  if (!selected || n == 0) {
    H5Sselect_none(file_space.get());
    H5Sselect_none(mem_space.get());
  }
  const double none = 0;
  const double* values = selected && n > 0 ? r.values.data() : &none;
  if (H5Dwrite(dataset.get(), H5T_NATIVE_DOUBLE, mem_space.get(), file_space.get(), dxpl, values) < 0 && error.empty())
    error = "H5Dwrite (collective): " + h5::error_text();
  return error;
}

/// Why this process cannot add `bytes` to `file`: its file-size limit (RLIMIT_FSIZE, which a
/// reservation beyond the end of the file does not check), a full disk; "" if it can.
std::string no_room(const std::string& file, std::size_t bytes) {
  struct rlimit limit {};
  struct stat st {};
  if (::getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY && ::stat(file.c_str(), &st) == 0 &&
      static_cast<std::size_t>(st.st_size) + bytes > limit.rlim_cur)
    return fmt::format("{} (this process's file-size limit is {} bytes, the file has {})", std::strerror(EFBIG),
                       limit.rlim_cur, st.st_size);
  return h5::reserve_disk(file, bytes);
}

/// The first failure over all ranks (the lowest failing rank's text), the same on every rank.
std::string agree_on_error(MPI_Comm comm, int rank, const std::string& mine) {
  int failing[2] = {mine.empty() ? 1 << 30 : rank, rank}, lowest[2] = {0, 0};
  MPI_Allreduce(failing, lowest, 1, MPI_2INT, MPI_MINLOC, comm);
  if (lowest[0] == 1 << 30) return "";
  std::string text = mine;
  long long size = static_cast<long long>(text.size());
  MPI_Bcast(&size, 1, MPI_LONG_LONG, lowest[0], comm);
  text.resize(static_cast<std::size_t>(size));
  MPI_Bcast(text.data(), static_cast<int>(size), MPI_CHAR, lowest[0], comm);
  return text;
}

}  // namespace

std::string write_shared_rows(MPI_Comm comm, std::string& file, std::vector<SharedRows>& rows,
                              const std::function<void(SharedRows&)>& fill) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  broadcast_list(comm, rank, file, rows);
  std::string error;
  if (rank != 0 && fill) {
    try {
      for (SharedRows& r : rows) fill(r);
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  // Every rank reserves the disk its part may take (the rows uncompressed, twice: the chunks are
  // allocated filled, then stored again) before any rank writes: a full disk or a file-size limit
  // on one rank is then said before the collective calls, inside which a rank that fails half-way
  // would leave the others waiting.
  std::size_t bytes = std::size_t{256} << 10;
  for (const SharedRows& r : rows) bytes += 2 * r.rows * r.row_size * sizeof(double);
  if (const std::string reason = error.empty() ? no_room(file, bytes) : ""; !reason.empty())
    error = fmt::format("no room for the next {:.1f} MB: {}", static_cast<double>(bytes) / 1e6, reason);
  if (const std::string before = agree_on_error(comm, rank, error.empty() ? "" : fmt::format(
          "rank {} of {}: writing the shared series of '{}' failed: {}", rank, size, file, error)); !before.empty())
    return before + "; nothing was written, the file keeps its last flush";
  h5::ErrorSilencer quiet;
  const Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  const Handle dxpl(H5Pcreate(H5P_DATASET_XFER), H5Pclose);
  // Metadata read collectively (rank 0 reads, broadcasts): every rank's metadata cache then takes
  // the same steps, which HDF5's collective metadata operations (H5Dset_extent) rely on.
  if (!fapl.ok() || !dxpl.ok() || H5Pset_fapl_mpio(fapl.get(), comm, MPI_INFO_NULL) < 0 ||
      H5Pset_all_coll_metadata_ops(fapl.get(), true) < 0 || H5Pset_coll_metadata_write(fapl.get(), true) < 0 ||
      H5Pset_dxpl_mpio(dxpl.get(), H5FD_MPIO_COLLECTIVE) < 0)
    error = "making the MPI-IO property lists: " + h5::error_text();
  // Opening is collective: every rank opens, even one that failed above (it then writes nothing).
  Handle f(H5Fopen(file.c_str(), H5F_ACC_RDWR, fapl.get()), H5Fclose);
  if (!f.ok() && error.empty()) error = "opening the file with the MPI-IO driver (H5Fopen): " + h5::error_text();
  if (f.ok())
    for (const SharedRows& r : rows) {
      const std::string e = write_entry(f.get(), dxpl.get(), r, error.empty());
      if (!e.empty() && error.empty()) error = fmt::format("'{}': {}", r.path, e);
    }
  Handle open_file(f.release(), H5Fclose);
  if (open_file.ok() && H5Fclose(open_file.release()) < 0 && error.empty())
    error = "closing the file (H5Fclose): " + h5::error_text();
  const std::string local =
      error.empty() ? "" : fmt::format("rank {} of {}: writing the shared series of '{}' failed: {}", rank, size, file, error);
  return agree_on_error(comm, rank, local);
}

}  // namespace raceway::h5
