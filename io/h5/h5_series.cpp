// raceway HDF5 series writer: the file, its time series, flush and commit (see h5_series.hpp for
// the contract, docs/output_layout.md for the file conventions). Attributes, fixed arrays and the
// time scale are in h5_attributes.cpp.
#include "io/h5/h5_series.hpp"

#include <fcntl.h>
#include <hdf5.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include <fmt/format.h>

#include "io/h5/h5_support.hpp"

namespace raceway::h5 {

static_assert(std::is_same_v<hid_t, std::int64_t>, "raceway needs HDF5 >= 1.10 (64-bit hid_t)");
static_assert(std::is_same_v<hsize_t, unsigned long long>, "unexpected hsize_t");

using h5::ErrorSilencer;
using h5::Handle;

namespace {

// Durability: without it a power loss could leave final_path pointing at an incompletely written
// file, or a checkpoint pointing past the rows on disk. Best effort (a failure does not make the
// data wrong).
void fsync_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return;
  (void)::fsync(fd);
  (void)::close(fd);
}

// Gives back the reserved blocks past the end of the file (truncating to its own size).
void release_disk(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) return;
  struct stat st {};
  if (::fstat(fd, &st) == 0) (void)::ftruncate(fd, st.st_size);
  (void)::close(fd);
}

std::size_t product(const std::vector<std::size_t>& shape) {
  std::size_t n = 1;
  for (const std::size_t d : shape) n *= d;
  return n;
}

// Chunk of about `bytes`: fill the trailing (row) dimensions first, whole rows if they fit, then as
// many rows as the remaining budget allows.
std::vector<hsize_t> chunk_shape(const std::vector<hsize_t>& row_shape, std::size_t bytes) {
  std::size_t budget = std::max<std::size_t>(1, bytes / sizeof(double));
  std::vector<hsize_t> chunk(row_shape.size() + 1);
  for (std::size_t d = row_shape.size(); d-- > 0;) {
    chunk[d + 1] = std::min<std::size_t>(row_shape[d], budget);
    budget = std::max<std::size_t>(1, budget / static_cast<std::size_t>(chunk[d + 1]));
  }
  chunk[0] = budget;
  return chunk;
}

}  // namespace

// ---- the one place where the file access property list is made ----
// Now: the default sec2 driver. Later (parallel output): H5Pset_fapl_mpio(fapl, comm, info) here,
// and H5Pset_dxpl_mpio(dxpl_, H5FD_MPIO_COLLECTIVE) where dxpl_ is made in open_file().
// The library version bounds are left at the default (earliest), so any HDF5 >= 1.8 reader and
// h5py can read the files.
static hid_t make_file_access_plist() {
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  if (fapl < 0) return fapl;
  if (H5Pset_fapl_sec2(fapl) < 0) {
    h5::failed();
    H5Pclose(fapl);
    return -1;
  }
  return fapl;
}

void H5SeriesWriter::reopen_handles() {
  const Handle fapl(make_file_access_plist(), H5Pclose);
  if (!fapl.ok()) fail("making the file access property list", "/");
  file_ = H5Fopen(partial_path_.c_str(), H5F_ACC_RDWR, fapl.get());
  if (file_ < 0) fail("opening the file again after the collective write (H5Fopen)", "/");
  for (auto& [path, s] : series_) {
    s.dataset = H5Dopen2(file_, path.c_str(), H5P_DEFAULT);
    if (s.dataset < 0) fail("opening the series again after the collective write (H5Dopen2)", path);
  }
}

void prepare_hdf5_library() {
  H5dont_atexit();
  H5open();
}

H5SeriesWriter::H5SeriesWriter(std::string final_path, const H5WriterOptions& options)
    : final_path_(std::move(final_path)), partial_path_(final_path_ + ".partial"), options_(options) {}

H5SeriesWriter H5SeriesWriter::open_file(const std::string& final_path, const H5WriterOptions& options, bool resume) {
  ErrorSilencer quiet;
  H5SeriesWriter w(final_path, options);
  const Handle fapl(make_file_access_plist(), H5Pclose);
  if (!fapl.ok()) w.fail("making the file access property list", "/");
  if (resume) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(w.partial_path_, ec) || H5Fis_hdf5(w.partial_path_.c_str()) <= 0)
      throw std::runtime_error(fmt::format("H5SeriesWriter: cannot continue '{}': it is missing or not an HDF5 file",
                                           w.partial_path_));
    w.file_ = H5Fopen(w.partial_path_.c_str(), H5F_ACC_RDWR, fapl.get());
    if (w.file_ < 0) w.fail("H5Fopen", "/");
    w.resuming_ = true;
  } else {
    // The root's attributes in dense storage (a heap, no size limit): a compact attribute lives in
    // one object-header message of at most 64 KiB, which state_names (16 bytes per state) passes
    // above 4096 states (816 rollers, 452 balls). Tracking their creation order gives the root the
    // 1.8 object header that dense storage needs, with the library's bounds left at their default.
    const Handle fcpl(H5Pcreate(H5P_FILE_CREATE), H5Pclose);
    if (!fcpl.ok() || H5Pset_attr_creation_order(fcpl.get(), H5P_CRT_ORDER_TRACKED) < 0 ||
        H5Pset_attr_phase_change(fcpl.get(), 0, 0) < 0 ||
        (options.sealed && H5Pset_userblock(fcpl.get(), kSealBytes) < 0))
      w.fail("making the file creation property list", "/");
    w.file_ = H5Fcreate(w.partial_path_.c_str(), H5F_ACC_TRUNC, fcpl.get(), fapl.get());
    if (w.file_ < 0) w.fail("H5Fcreate", "/");
  }
  w.dxpl_ = H5Pcreate(H5P_DATASET_XFER);  // collective transfer mode goes here later
  if (w.dxpl_ < 0) w.fail("making the data transfer property list", "/");
  if (options.background_compression) w.compressor_ = std::make_unique<ChunkCompressor>(options.compressor_core);
  return w;
}

H5SeriesWriter H5SeriesWriter::create(const std::string& final_path, const H5WriterOptions& options) {
  return open_file(final_path, options, false);
}

H5SeriesWriter H5SeriesWriter::reopen(const std::string& final_path, std::size_t rows,
                                      std::map<std::string, std::vector<double>> unwritten,
                                      const H5WriterOptions& options, std::map<std::string, double> checksums) {
  H5SeriesWriter w = open_file(final_path, options, true);
  w.resume_rows_ = rows;
  w.resume_unwritten_ = std::move(unwritten);
  w.resume_checksums_ = std::move(checksums);
  return w;
}

H5SeriesWriter::H5SeriesWriter(H5SeriesWriter&& other) noexcept
    : final_path_(std::move(other.final_path_)),
      partial_path_(std::move(other.partial_path_)),
      file_(std::exchange(other.file_, -1)),
      dxpl_(std::exchange(other.dxpl_, -1)),
      options_(other.options_),
      resuming_(other.resuming_),
      resume_rows_(other.resume_rows_),
      resume_unwritten_(std::move(other.resume_unwritten_)),
      resume_checksums_(std::move(other.resume_checksums_)),
      buffered_bytes_(std::exchange(other.buffered_bytes_, 0)),
      residual_bytes_(std::exchange(other.residual_bytes_, 0)),
      flushed_(other.flushed_),
      series_(std::move(other.series_)),
      by_id_(std::move(other.by_id_)),
      compressor_(std::move(other.compressor_)),
      shared_writer_(std::move(other.shared_writer_)) {
  other.series_.clear();
  other.by_id_.clear();
}

H5SeriesWriter& H5SeriesWriter::operator=(H5SeriesWriter&& other) noexcept {
  if (this != &other) {
    close_uncommitted();  // as if destroyed: our .partial file stays
    final_path_ = std::move(other.final_path_);
    partial_path_ = std::move(other.partial_path_);
    file_ = std::exchange(other.file_, -1);
    dxpl_ = std::exchange(other.dxpl_, -1);
    options_ = other.options_;
    resuming_ = other.resuming_;
    resume_rows_ = other.resume_rows_;
    resume_unwritten_ = std::move(other.resume_unwritten_);
    resume_checksums_ = std::move(other.resume_checksums_);
    buffered_bytes_ = std::exchange(other.buffered_bytes_, 0);
    residual_bytes_ = std::exchange(other.residual_bytes_, 0);
    flushed_ = other.flushed_;
    series_ = std::move(other.series_);
    by_id_ = std::move(other.by_id_);
    compressor_ = std::move(other.compressor_);
    shared_writer_ = std::move(other.shared_writer_);
    other.series_.clear();
    other.by_id_.clear();
  }
  return *this;
}

H5SeriesWriter::~H5SeriesWriter() { close_uncommitted(); }

void H5SeriesWriter::close_uncommitted() noexcept {
  if (!is_open()) return;
  ErrorSilencer quiet;
  try {
    write_all_buffers(false);
    H5Fflush(file_, H5F_SCOPE_LOCAL);
  } catch (...) {
    // Destructors must not throw; the .partial file keeps what was written. (A failed write has
    // already closed the file: see fail().)
  }
  close_all();
}

void H5SeriesWriter::require_open(const char* what) const {
  if (!is_open()) {
    throw std::logic_error(fmt::format("H5SeriesWriter::{}: the writer for '{}' is closed (committed, moved from, "
                                       "or after a failed write)",
                                       what, final_path_));
  }
}

void H5SeriesWriter::fail(const std::string& what, const std::string& object) {
  const std::string message = fmt::format("H5SeriesWriter: {} failed for '{}' in file '{}': {}", what, object,
                                          partial_path_, h5::saved_error().empty() ? h5::error_text()
                                                                                   : h5::saved_error());
  // A failure of the file driver (H5FD: a write or read that the system refused, e.g. a full disk)
  // leaves HDF5 unable to write its cached metadata: abandon the file. Other failures (a bad path
  // inside the file) leave the writer usable.
  if (message.find("H5FD") != std::string::npos) abandon();
  throw std::runtime_error(message);
}

H5SeriesWriter::Hid H5SeriesWriter::create_series_dataset(const std::string& key, const Series& s) {
  std::vector<hsize_t> dims{0};
  std::vector<hsize_t> max_dims{H5S_UNLIMITED};
  dims.insert(dims.end(), s.row_shape.begin(), s.row_shape.end());
  max_dims.insert(max_dims.end(), s.row_shape.begin(), s.row_shape.end());
  const auto parts = h5::split_path(key);
  if (!h5::ensure_groups(file_, parts, parts.size() - 1)) fail("creating the parent groups", key);
  const Handle space(h5::make_dataspace(dims, &max_dims), H5Sclose);
  if (!space.ok()) fail("H5Screate_simple", key);
  const Handle dcpl(h5::make_dcpl(), H5Pclose);
  const std::vector<hsize_t> chunk = chunk_shape(s.row_shape, options_.chunk_bytes);
  const double nan = std::numeric_limits<double>::quiet_NaN();  // unwritten rows read as NaN, not 0
  if (!dcpl.ok() || H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data()) < 0 ||
      H5Pset_fill_value(dcpl.get(), H5T_NATIVE_DOUBLE, &nan) < 0 ||
      (shuffles(s) && H5Pset_shuffle(dcpl.get()) < 0) ||
      (gzip_level(s) > 0 && H5Pset_deflate(dcpl.get(), static_cast<unsigned>(gzip_level(s))) < 0) ||
      // A shared series' chunks are allocated (and filled) when the collective write extends it:
      // HDF5 1.10.8's collective filtered write reads a partly written chunk that was never
      // allocated at an undefined address (the last, edge chunk) and fails.
      (s.shared && H5Pset_alloc_time(dcpl.get(), H5D_ALLOC_TIME_EARLY) < 0)) {
    fail("setting the dataset creation properties", key);
  }
  const hid_t dataset = H5Dcreate2(file_, key.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT);
  if (dataset < 0) fail("H5Dcreate2", key);
  return dataset;
}

H5SeriesWriter::Hid H5SeriesWriter::open_series_dataset(const std::string& key, Series& s) {
  const hid_t dataset = H5Dopen2(file_, key.c_str(), H5P_DEFAULT);
  if (dataset < 0) fail("opening the series to continue it (H5Dopen2)", key);
  Handle keep(dataset, H5Dclose);
  const Handle space(H5Dget_space(dataset), H5Sclose);
  const int rank = space.ok() ? H5Sget_simple_extent_ndims(space.get()) : -1;
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 0)));
  if (rank < 0 || H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr) < 0) fail("H5Sget_simple_extent_dims", key);
  if (dims.size() != s.row_shape.size() + 1 || !std::equal(s.row_shape.begin(), s.row_shape.end(), dims.begin() + 1))
    throw std::runtime_error(fmt::format("H5SeriesWriter: cannot continue '{}': series '{}' has another shape than "
                                         "this run writes", partial_path_, key));
  std::vector<double> tail;
  if (const auto u = resume_unwritten_.find(key); u != resume_unwritten_.end()) tail = u->second;
  const std::size_t tail_rows = tail.size() / s.row_size;
  const std::size_t rows = (resume_rows_ + s.stride - 1) / s.stride;  // the outputs 0, stride, ... before resume_rows_
  if (tail.size() % s.row_size != 0 || tail_rows > rows)
    throw std::runtime_error(fmt::format("H5SeriesWriter: cannot continue '{}': the checkpoint's unwritten rows of '{}' "
                                         "do not fit its rows", partial_path_, key));
  const std::size_t file_rows = rows - tail_rows;
  if (dims[0] < file_rows)
    throw std::runtime_error(fmt::format("H5SeriesWriter: cannot continue '{}': series '{}' has {} rows, the "
                                         "checkpoint needs {}", partial_path_, key, dims[0], file_rows));
  if (!s.shared) resume_row_checksum(key, s, stored_rows_crc(dataset, key, file_rows, s.row_size), tail);
  dims[0] = file_rows;
  if (H5Dset_extent(dataset, dims.data()) < 0) fail("cutting the series to the checkpoint (H5Dset_extent)", key);
  s.rows_written = file_rows;
  s.buffer = std::move(tail);
  buffered_bytes_ += s.buffer.size() * sizeof(double);
  residual_bytes_ = buffered_bytes_;  // the partial chunks of the interrupted run's last flush
  return keep.release();
}

void H5SeriesWriter::define_series(const std::string& path, std::vector<std::size_t> row_shape,
                                   const std::string& units, const std::string& description, bool shared,
                                   bool compressed, std::size_t stride) {
  require_open("define_series");
  ErrorSilencer quiet;
  const std::string key = h5::normalize(path);
  if (key == "/") throw std::invalid_argument("H5SeriesWriter::define_series: empty dataset path");
  if (series_.contains(key)) {
    throw std::invalid_argument(fmt::format("H5SeriesWriter::define_series: series '{}' already defined in '{}'",
                                            key, partial_path_));
  }
  if (std::find(row_shape.begin(), row_shape.end(), std::size_t{0}) != row_shape.end()) {
    throw std::invalid_argument(fmt::format("H5SeriesWriter::define_series: series '{}' has a zero row dimension", key));
  }
  if (shared && (!shared_writer_ || row_shape.size() != 1))
    throw std::invalid_argument(fmt::format("H5SeriesWriter::define_series: shared series '{}' needs a shared writer "
                                            "and rows of one dimension", key));
  Series s;
  s.shared = shared;
  s.compressed = compressed;
  s.stride = std::max<std::size_t>(stride, 1);
  s.row_shape.assign(row_shape.begin(), row_shape.end());
  s.row_size = product(row_shape);
  s.chunk_rows = chunk_shape(s.row_shape, options_.chunk_bytes)[0];
  const int exists = resuming_ ? h5::link_exists(file_, key) : 0;
  if (exists < 0) fail("H5Lexists", key);
  s.dataset = exists > 0 ? open_series_dataset(key, s) : create_series_dataset(key, s);
  s.path = key;
  // Chunks of whole rows that start at a chunk boundary (always, but after a partial write at the
  // end) go to the background compressor.
  if (shared) s.mine.assign(s.buffer.size(), 1);  // a resumed series' rows: all this process's
  s.direct = !shared && compressor_ && std::equal(s.row_shape.begin(), s.row_shape.end(),
                                       chunk_shape(s.row_shape, options_.chunk_bytes).begin() + 1) &&
             s.rows_written % s.chunk_rows == 0;
  auto [it, inserted] = series_.emplace(key, std::move(s));  // the map owns the open dataset now
  (void)inserted;
  by_id_.push_back(&it->second);
  submit_whole_chunks(it->second);  // a resumed series' buffered rows
  if (!h5::write_units_description(it->second.dataset, units, description)) fail("writing units/description", key);
}

H5SeriesWriter::SeriesId H5SeriesWriter::series_id(const std::string& path) const {
  require_open("series_id");
  auto it = series_.find(h5::normalize(path));
  if (it == series_.end()) {
    throw std::invalid_argument(fmt::format("H5SeriesWriter::series_id: series '{}' is not defined in '{}'", path,
                                            partial_path_));
  }
  return static_cast<SeriesId>(std::find(by_id_.begin(), by_id_.end(), &it->second) - by_id_.begin());
}

void H5SeriesWriter::append(const std::string& path, std::span<const double> row) {
  append(series_id(path), row);
}

void H5SeriesWriter::append(SeriesId id, std::span<const double> row) {
  require_open("append");
  if (id >= by_id_.size())
    throw std::invalid_argument(fmt::format("H5SeriesWriter::append: no series {} in '{}'", id, partial_path_));
  Series& s = *by_id_[id];
  if (row.size() != s.row_size) {
    throw std::invalid_argument(fmt::format("H5SeriesWriter::append: series '{}' in '{}' takes rows of {} values, got {}",
                                            s.path, partial_path_, s.row_size, row.size()));
  }
  if (s.shared && s.mine.size() < s.buffer.size() + row.size()) s.mine.insert(s.mine.end(), row.size(), 1);
  if (!s.shared) s.crc = row_crc(s.crc, row);
  s.buffer.insert(s.buffer.end(), row.begin(), row.end());
  buffered_bytes_ += row.size_bytes();
  submit_whole_chunks(s);
  // The rows left after a flush (the partial chunks) do not count towards the next one: a file of
  // many series would otherwise flush at every row.
  if (buffered_bytes_ >= options_.max_buffered_bytes + residual_bytes_) flush();
}

void H5SeriesWriter::append(SeriesId id, std::span<const double> row, std::span<const unsigned char> mine) {
  require_open("append");
  if (id >= by_id_.size() || !by_id_[id]->shared || mine.size() != row.size())
    throw std::invalid_argument(fmt::format("H5SeriesWriter::append: series {} in '{}' is not shared, or the row's "
                                            "owners do not match it", id, partial_path_));
  Series& s = *by_id_[id];
  s.mine.insert(s.mine.end(), mine.begin(), mine.end());
  append(id, row);
}

void H5SeriesWriter::submit_whole_chunks(Series& s) {
  // The buffer of a direct series starts at a chunk boundary (rows_written and handed_rows are whole
  // chunks), so it holds whole chunks first. They leave it for the compressor: a buffer that is
  // exactly one chunk (rows appended one at a time) is moved there whole, without a copy, and the
  // buffer stays one chunk long instead of growing until the next flush (measured: copies and page
  // faults were about half of the appends' time, perf/studies/results/output_notes.md).
  if (!s.direct) return;
  const std::size_t chunk_values = s.chunk_rows * s.row_size;
  if (s.buffer.size() == chunk_values) {
    std::vector<double> whole;
    whole.reserve(chunk_values);
    std::swap(whole, s.buffer);
    s.filtered.emplace((s.rows_written + s.handed_rows) / s.chunk_rows,
                       submit_chunk(s, std::move(whole)));
    s.handed_rows += s.chunk_rows;
    return;
  }
  std::size_t first = 0;  // several chunks at once (a resumed series' rows): copied out
  for (; s.buffer.size() - first >= chunk_values; first += chunk_values, s.handed_rows += s.chunk_rows) {
    const auto begin = s.buffer.begin() + static_cast<std::ptrdiff_t>(first);
    s.filtered.emplace((s.rows_written + s.handed_rows) / s.chunk_rows,
                       submit_chunk(s, {begin, begin + static_cast<std::ptrdiff_t>(chunk_values)}));
  }
  if (first > 0) s.buffer.erase(s.buffer.begin(), s.buffer.begin() + static_cast<std::ptrdiff_t>(first));
}

std::size_t H5SeriesWriter::rows(const std::string& path) const {
  auto it = series_.find(h5::normalize(path));
  if (it == series_.end()) {
    throw std::invalid_argument(fmt::format("H5SeriesWriter::rows: series '{}' is not defined", path));
  }
  return it->second.rows_written + it->second.handed_rows + it->second.buffer.size() / it->second.row_size;
}

std::size_t H5SeriesWriter::rows_to_write(const Series& s, bool whole_chunks_only) {
  const std::size_t n = s.handed_rows + s.buffer.size() / s.row_size;
  if (!whole_chunks_only) return n;
  const std::size_t end = (s.rows_written + n) / s.chunk_rows * s.chunk_rows;  // the last whole chunk's end
  return end > s.rows_written ? end - s.rows_written : 0;
}

void H5SeriesWriter::write_buffer(const std::string& path, Series& s, bool whole_chunks_only) {
  const std::size_t n = rows_to_write(s, whole_chunks_only);
  if (n == 0) return;
  std::vector<hsize_t> new_dims{static_cast<hsize_t>(s.rows_written + n)};
  new_dims.insert(new_dims.end(), s.row_shape.begin(), s.row_shape.end());
  if (H5Dset_extent(s.dataset, new_dims.data()) < 0) fail("H5Dset_extent", path);

  if (s.direct && s.rows_written % s.chunk_rows == 0) {
    write_chunks(path, s, n);
  } else {
    std::vector<hsize_t> start(new_dims.size(), 0);
    start[0] = s.rows_written;
    std::vector<hsize_t> count = new_dims;
    count[0] = n;
    const Handle file_space(H5Dget_space(s.dataset), H5Sclose);
    if (!file_space.ok() ||
        H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr) < 0) {
      fail("selecting the rows to write", path);
    }
    const Handle mem_space(h5::make_dataspace(count), H5Sclose);
    if (!mem_space.ok()) fail("H5Screate_simple", path);
    if (H5Dwrite(s.dataset, H5T_NATIVE_DOUBLE, mem_space.get(), file_space.get(), dxpl_, s.buffer.data()) < 0) {
      fail("H5Dwrite", path);
    }
  }
  s.rows_written += n;
  buffered_bytes_ -= std::min(buffered_bytes_, n * s.row_size * sizeof(double));
  const std::size_t handed = std::min(n, s.handed_rows);  // written from the compressor's chunks
  s.handed_rows -= handed;
  s.buffer.erase(s.buffer.begin(), s.buffer.begin() + static_cast<std::ptrdiff_t>((n - handed) * s.row_size));
}

std::vector<double> H5SeriesWriter::padded_chunk(const Series& s, std::size_t first_row, std::size_t rows) {
  // As HDF5 stores an edge chunk: the rows past the end hold the fill value (NaN).
  std::vector<double> values(s.chunk_rows * s.row_size, std::numeric_limits<double>::quiet_NaN());
  std::copy_n(s.buffer.begin() + static_cast<std::ptrdiff_t>(first_row * s.row_size), rows * s.row_size, values.begin());
  return values;
}

void H5SeriesWriter::write_chunks(const std::string& path, Series& s, std::size_t rows) {
  std::vector<hsize_t> offset(s.row_shape.size() + 1, 0);
  for (std::size_t done = 0; done < rows; done += s.chunk_rows) {
    const std::size_t chunk = (s.rows_written + done) / s.chunk_rows;
    FilteredChunk stored;
    if (auto f = s.filtered.find(chunk); f != s.filtered.end()) {
      stored = f->second.get();
      s.filtered.erase(f);
    } else {  // the last, partial chunk, not handed to the compressor: the buffer's rows after the handed ones
      stored = filter_chunk(padded_chunk(s, done - s.handed_rows, std::min(s.chunk_rows, rows - done)), shuffles(s),
                            gzip_level(s));
    }
    offset[0] = static_cast<hsize_t>(chunk * s.chunk_rows);
    if (H5Dwrite_chunk(s.dataset, dxpl_, stored.filter_mask, offset.data(), stored.bytes.size(), stored.bytes.data()) < 0)
      fail("H5Dwrite_chunk", path);
  }
}

void H5SeriesWriter::write_all_buffers(bool whole_chunks_only) {
  if (!whole_chunks_only && compressor_) {
    // The last, partial chunks are filtered by both threads: the compressor takes those of the
    // second half of the series (last first) while this thread writes from the first.
    std::size_t half = series_.size() / 2;
    for (auto it = series_.rbegin(); it != series_.rend() && half > 0; ++it, --half) {
      Series& s = it->second;
      const std::size_t rows = s.buffer.size() / s.row_size, tail = rows % s.chunk_rows;
      if (!s.direct || s.rows_written % s.chunk_rows != 0 || tail == 0) continue;
      const std::size_t chunk = (s.rows_written + s.handed_rows + rows) / s.chunk_rows;
      if (!s.filtered.contains(chunk))
        s.filtered.emplace(chunk, submit_chunk(s, padded_chunk(s, rows - tail, tail)));
    }
  }
  for (auto& [path, s] : series_)
    if (!s.shared) write_buffer(path, s, whole_chunks_only);
  write_shared(whole_chunks_only);
}

std::map<std::string, std::vector<double>> H5SeriesWriter::unwritten_rows() const {
  std::map<std::string, std::vector<double>> rows;
  for (const auto& [path, s] : series_) {
    if (s.handed_rows > 0)  // whole chunks with the compressor: only a flush() leaves none
      throw std::logic_error(fmt::format("H5SeriesWriter::unwritten_rows: '{}' has whole chunks not yet written; "
                                         "call flush() first", path));
    if (!s.buffer.empty()) rows.emplace(path, s.buffer);
  }
  return rows;
}

void H5SeriesWriter::reserve_for_flush() {
  // The buffered rows (at most: compressed they take less) and the metadata.
  const std::size_t bytes = buffered_bytes_ + (std::size_t{256} << 10);
  if (const std::string error = h5::reserve_disk(partial_path_, bytes); !error.empty()) {
    const std::string message = fmt::format("H5SeriesWriter: no room to write the next {:.1f} MB of '{}': {}; {}",
                                            static_cast<double>(bytes) / 1e6, partial_path_, error,
                                            flushed_ ? "the file keeps the rows of its last flush"
                                                     : "the file was never complete (nothing to keep)");
    abandon();
    throw std::runtime_error(message);
  }
}

void H5SeriesWriter::flush(bool wait_for_disk) {
  require_open("flush");
  ErrorSilencer quiet;
  reserve_for_flush();
  write_all_buffers(true);
  if (H5Fflush(file_, H5F_SCOPE_LOCAL) < 0) fail("writing to disk (H5Fflush)", "/");
  release_disk(partial_path_);
  if (wait_for_disk) fsync_file(partial_path_);
  flushed_ = true;
  residual_bytes_ = buffered_bytes_;
}

void H5SeriesWriter::abandon() noexcept {
  if (file_ < 0) return;
  // After a failed write (a full disk, a quota) HDF5's dirty metadata cannot reach the file, and an
  // open file whose close fails crashes HDF5's own shutdown (at exit, at MPI_Finalize). So nothing
  // more goes to the file: its descriptor is pointed at /dev/null and every object closed. The
  // .partial file keeps what it had on disk (its last flush, when the reservation found the disk full).
  void* handle = nullptr;
  const int null_fd = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
  if (null_fd >= 0 && H5Fget_vfd_handle(file_, H5P_DEFAULT, &handle) >= 0 && handle != nullptr)
    (void)::dup2(null_fd, *static_cast<int*>(handle));
  if (null_fd >= 0) (void)::close(null_fd);
  for (auto& [path, s] : series_) s.buffer.clear(), s.handed_rows = 0, s.filtered.clear();
  buffered_bytes_ = 0;
  close_all();
}

void H5SeriesWriter::close_all() noexcept {
  for (auto& [path, s] : series_) {
    if (s.dataset >= 0) H5Dclose(s.dataset);
    s.dataset = -1;
  }
  series_.clear();
  by_id_.clear();
  if (dxpl_ >= 0) H5Pclose(dxpl_);
  dxpl_ = -1;
  if (file_ >= 0) H5Fclose(file_);
  file_ = -1;
}

void H5SeriesWriter::commit() {
  require_open("commit");
  {
    ErrorSilencer quiet;
    reserve_for_flush();
    write_all_buffers(false);
    for (auto& [path, s] : series_) {
      if (H5Dclose(s.dataset) < 0) fail("H5Dclose", path);
      s.dataset = -1;
    }
    series_.clear();
    by_id_.clear();
    H5Pclose(dxpl_);
    dxpl_ = -1;
    if (H5Fclose(file_) < 0) fail("H5Fclose", "/");  // fail() abandons the still open file
    file_ = -1;
  }
  release_disk(partial_path_);
  if (options_.sealed) seal(partial_path_);
  fsync_file(partial_path_);
  std::error_code ec;
  std::filesystem::rename(partial_path_, final_path_, ec);
  if (ec) {
    throw std::runtime_error(fmt::format("H5SeriesWriter::commit: renaming '{}' to '{}' failed: {}", partial_path_,
                                         final_path_, ec.message()));
  }
  const std::filesystem::path folder = std::filesystem::path(final_path_).parent_path();
  fsync_file(folder.empty() ? "." : folder.string());  // the rename itself on disk
}

}  // namespace raceway::h5
