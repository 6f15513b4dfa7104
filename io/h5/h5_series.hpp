// raceway HDF5 output: time series written at fixed output times, plus fixed arrays and attributes.
//
// H5SeriesWriter knows nothing of physics: it writes named double datasets whose first dimension
// is the output index (time) and grows by one row per append(). The layout conventions of the
// files it writes are in docs/output_layout.md.
//
// Crash safety (one file per run, written as "<final>.partial" then renamed):
//   * create(final_path) writes to final_path + ".partial" (truncating a stale one: the caller
//     holds the output's OutputLock, io/h5/output_lock.hpp, so no other run is writing it); a file
//     that already exists at final_path is never opened or touched by the writer.
//   * Appended rows stay in memory until flush() (or until options.max_buffered_bytes are buffered,
//     which flushes): between two flushes the file on disk is not written at all, so after a hard
//     kill (SIGKILL, out of memory, power loss after the fsync of the last flush) the .partial file
//     is the consistent file of the last flush and opens in h5py.
//   * A flush writes whole chunks only; the rows of a series' last, partly filled chunk stay in
//     memory (unwritten_rows(): a checkpoint keeps them) until commit(). A compressed chunk written
//     once is never written again, so a kill in the middle of a later flush cannot damage the rows
//     of an earlier one (rewriting a compressed chunk in place can: measured, 10 of 37 kills).
//   * commit() writes the buffered rows, flushes, closes the file and renames the .partial file
//     over final_path (std::filesystem::rename: atomic on POSIX, same directory), so final_path is
//     always either the old complete output or the new complete output.
//   * Destroying the writer without commit() (an exception unwinding, an early return) writes
//     the buffered rows as far as it can, closes the file and leaves "<final>.partial" in place.
//   * reopen(final_path, rows, unwritten) continues an interrupted run's .partial file: the series
//     defined afterwards are its existing datasets cut to `rows` rows less the unwritten ones, which
//     are buffered again.
//
// Storage: series are chunked, shuffled and gzip-compressed (options), but those defined
// `compressed = false`, which are chunked alone (full-precision trajectories: deflate shrinks them
// by 10-20 % for a large share of the output's cost); fixed arrays contiguous. A
// chunk of whole rows is filtered on a background thread as soon as its rows are appended and
// stored at the next flush (H5Dwrite_chunk); a series' last, partial chunk is filtered at commit.
// Shared series are filtered by HDF5's pipeline inside the collective write (HDF5 1.10 has no
// H5Dwrite_chunk under MPI-IO), and their chunks are allocated early (see create_series_dataset).
//
// Errors: every HDF5 failure throws std::runtime_error naming the file, the object and the
// innermost HDF5 error message (e.g. "No space left on device" at the flush that hits a full disk);
// after one the writer is closed as far as HDF5 allows and every later call throws. Misuse
// (unknown series, wrong row size, bad shape) throws std::invalid_argument; using a writer after
// commit() or after a move throws std::logic_error. HDF5's automatic error-stack printing is
// switched off while the writer's methods run, so failures are reported once, by the exception.
//
// Paths are absolute or relative to the root ("bodies/cage/position" == "/bodies/cage/position");
// missing intermediate groups are created.
//
// Parallel output (docs/output_layout.md, "Who writes"): series defined `shared` (after
// share_series_with()) are written by several ranks together: each appended row says which of its
// cells are this process's (the others' ranks hold the rest), and at a flush the writer closes its
// own (sec2) handle, hands the rows of every shared series to the shared writer (a collective write
// of all ranks through the MPI-IO driver, h5::write_shared_rows in io/h5/h5_parallel.hpp) and opens the file again. The
// other series, attributes and fixed arrays stay this process's alone, as in a serial run.
#pragma once

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "io/h5/chunk_compressor.hpp"
#include "io/h5/shared_rows.hpp"

namespace raceway::h5 {

/// Call once at the start of main(), before MPI_Init: initialises HDF5 without its exit-time cleanup
/// (H5dont_atexit) and before MPI, so that it installs no MPI_Finalize hook either. HDF5 1.10 crashes
/// in that cleanup when a file whose close failed (a full disk) is still open; raceway closes every
/// file it opens itself, so nothing is lost.
void prepare_hdf5_library();

/// How series are stored and how much is kept in memory between flushes.
struct H5WriterOptions {
  int gzip_level = 1;          ///< deflate level of every series (0: no compression)
  bool shuffle = true;         ///< byte shuffle before deflate (doubles compress about 10 % better)
  std::size_t chunk_bytes = 16 * 1024;  ///< target chunk size of a series (whole rows when a row fits)
  /// Rows appended since the last flush beyond this (the partial chunks it left do not count): flush().
  std::size_t max_buffered_bytes = std::size_t{32} << 20;
  /// Filter (shuffle, deflate) each chunk of whole rows on a background thread as soon as its rows
  /// are appended, and store it at the next flush with H5Dwrite_chunk (io/h5/chunk_compressor.hpp):
  /// the same stored bytes as HDF5's pipeline, off the caller's thread. false: HDF5 filters them
  /// inside the flush.
  bool background_compression = true;
  /// The logical CPU the background compressor's thread is bound to (io/h5/thread_core.hpp); -1:
  /// wherever the process may run.
  int compressor_core = -1;
  /// commit() seals the file before it syncs and renames it: a 512-byte user block at its start
  /// (HDF5 starts the file after it) holds the CRC-32 and the size of every byte after it, so that
  /// sealed_file_problem() finds any damage before HDF5 parses a byte (HDF5 1.10 can crash on
  /// damaged metadata). For small files written once (checkpoints).
  bool sealed = false;
};

/// The user block of a sealed file (HDF5's smallest): the seal, then HDF5's file.
inline constexpr std::size_t kSealBytes = 512;

/// Why the sealed file at `path` (H5WriterOptions::sealed) is not as it was committed: "" when its
/// seal reads and the CRC-32 and size of the bytes after it match; else the reason (no seal, cut,
/// another size, another CRC-32). Reads the whole file (h5_checksums.cpp).
std::string sealed_file_problem(const std::string& path);

class H5SeriesWriter {
 public:
  /// Creates (truncates) final_path + ".partial" and returns a writer for it. final_path itself is
  /// only replaced by commit(). Throws std::runtime_error if the file cannot be created.
  static H5SeriesWriter create(const std::string& final_path, const H5WriterOptions& options = {});

  /// Opens final_path + ".partial", the file of an interrupted run, to continue it after `rows`
  /// rows: every define_series() then opens the existing dataset (same row shape, else
  /// std::runtime_error), cuts it to `rows` less the rows of the series in `unwritten` (its
  /// unwritten_rows() when the checkpoint was taken; std::runtime_error if the file has fewer) and
  /// buffers those again. Throws std::runtime_error naming the file if it is missing or not HDF5.
  /// `checksums` (row_checksums() when the checkpoint was taken): each series' rows read back from
  /// the file, followed by its unwritten rows, must have that CRC-32, else std::runtime_error
  /// naming the series as damaged.
  static H5SeriesWriter reopen(const std::string& final_path, std::size_t rows,
                               std::map<std::string, std::vector<double>> unwritten = {},
                               const H5WriterOptions& options = {}, std::map<std::string, double> checksums = {});

  H5SeriesWriter(const H5SeriesWriter&) = delete;
  H5SeriesWriter& operator=(const H5SeriesWriter&) = delete;
  H5SeriesWriter(H5SeriesWriter&& other) noexcept;
  H5SeriesWriter& operator=(H5SeriesWriter&& other) noexcept;
  /// Without commit(): writes buffered rows (best effort, never throws), closes the file and leaves
  /// the .partial file on disk.
  ~H5SeriesWriter();

  /// Defines a time series: an extendible chunked double dataset of shape [0 x row_shape...]
  /// (row_shape empty: one scalar per output, dataset shape [0]). Attributes "units" and
  /// "description" are written as variable-length UTF-8 strings. Throws std::invalid_argument if
  /// the series is already defined or a row dimension is 0. `compressed` false: stored without
  /// the shuffle and deflate filters (a series that does not compress), whichever path writes it.
  /// `stride` > 1: the caller appends a row at every stride-th output only (outputs 0, stride,
  /// 2 stride, ...), so that a reopen() after `rows` outputs keeps ceil(rows / stride) of its rows;
  /// set_time_scale() attaches to it only a scale of the same stride.
  void define_series(const std::string& path, std::vector<std::size_t> row_shape,
                     const std::string& units, const std::string& description, bool shared = false,
                     bool compressed = true, std::size_t stride = 1);

  /// The collective write of the shared series' rows (h5::write_shared_rows on every rank): it
  /// must write them or throw std::runtime_error. Set before the first shared series is defined.
  using SharedWriter = std::function<void(std::vector<SharedRows>&)>;
  void share_series_with(SharedWriter writer) { shared_writer_ = std::move(writer); }

  /// Appends one row (row.size() must be the product of the series' row_shape, else
  /// std::invalid_argument; unknown series: std::invalid_argument). Rows are buffered in memory and
  /// written by the next flush() or commit() (or when max_buffered_bytes are reached).
  void append(const std::string& path, std::span<const double> row);

  /// A series' handle for append(SeriesId, row): the same as append(path, row) without looking the
  /// path up (a run appends every series at every output time). Valid until commit() or a move.
  using SeriesId = std::size_t;
  SeriesId series_id(const std::string& path) const;
  void append(SeriesId id, std::span<const double> row);
  /// A shared series' row: `mine[i]` != 0 where cell i is this process's to write (the values of the
  /// others are kept too, for unwritten_rows(), but another rank writes them).
  void append(SeriesId id, std::span<const double> row, std::span<const unsigned char> mine);

  /// Makes the series at `scale_path` (a [T] series, e.g. /time) the HDF5 dimension scale of the
  /// first dimension of every series defined so far with the scale's stride (H5DS: h5py's
  /// ds.dims[0][0] is then it).
  void set_time_scale(const std::string& scale_path, const std::string& scale_name);

  /// Number of rows appended to a series so far (written or still buffered).
  std::size_t rows(const std::string& path) const;

  /// Attributes on a group or dataset ("/" is the root); missing groups are created. An existing
  /// attribute of the same name is replaced. Strings are variable-length UTF-8 (h5py reads str).
  void set_attribute(const std::string& object_path, const std::string& name, const std::string& value);
  void set_attribute(const std::string& object_path, const std::string& name, const char* value);
  void set_attribute(const std::string& object_path, const std::string& name, double value);
  void set_attribute(const std::string& object_path, const std::string& name, long long value);
  void set_attribute(const std::string& object_path, const std::string& name,
                     const std::vector<double>& value);
  void set_attribute(const std::string& object_path, const std::string& name,
                     const std::vector<std::string>& value);
  /// Any other integer type (int, std::size_t, ...) is stored as a 64-bit signed integer.
  template <std::integral T>
    requires(!std::same_as<T, bool> && !std::same_as<T, long long>)
  void set_attribute(const std::string& object_path, const std::string& name, T value) {
    if (!std::in_range<long long>(value)) {
      throw std::invalid_argument("H5SeriesWriter: integer attribute '" + name + "' out of range");
    }
    set_attribute(object_path, name, static_cast<long long>(value));
  }

  /// A fixed (non-time) double dataset of the given shape (row-major data; empty shape: scalar),
  /// with "units" and "description" attributes. data.size() must equal the product of shape. An
  /// existing dataset at `path` is replaced.
  void write_array(const std::string& path, std::vector<std::size_t> shape,
                   std::span<const double> data, const std::string& units,
                   const std::string& description);
  /// A 1-D table of variable-length UTF-8 strings (e.g. segment or state names), with a
  /// "description" attribute and an empty "units" attribute.
  void write_array(const std::string& path, const std::vector<std::string>& values,
                   const std::string& description);

  /// Writes the buffered rows of whole chunks, flushes the file (H5Fflush) and, if wait_for_disk,
  /// waits for the disk (fsync). Without the wait the flushed file is complete in the system's
  /// cache: it survives the process being killed, not a power loss (fsync: 5-15 ms here, more on
  /// network file systems).
  void flush(bool wait_for_disk = true);

  /// Bytes of appended rows not yet in the file.
  std::size_t buffered_bytes() const noexcept { return buffered_bytes_; }
  /// After a flush: the appended rows not yet in the file (each series' last, partly filled
  /// chunk), by normalized series path, row-major; series with none are left out. Throws
  /// std::logic_error when whole chunks appended since the last flush are not yet written.
  std::map<std::string, std::vector<double>> unwritten_rows() const;
  /// Per series written by this process alone (not shared), the CRC-32 (zlib) of the bytes of every
  /// row appended since the file was created, in order (those in the file and the unwritten ones):
  /// what a checkpoint keeps so that reopen() can tell a damaged .partial file from a sound one.
  std::map<std::string, double> row_checksums() const;

  /// Writes buffered rows, closes the file and renames the .partial file over the final path.
  /// After commit() the writer is closed; any further call except the destructor throws
  /// std::logic_error.
  void commit();

  bool is_open() const noexcept { return file_ >= 0; }
  const std::string& final_path() const noexcept { return final_path_; }
  const std::string& partial_path() const noexcept { return partial_path_; }

 private:
  using Hid = std::int64_t;           // hid_t of HDF5 >= 1.10 (checked in h5_series.cpp)
  using Hsize = unsigned long long;   // hsize_t (checked in h5_series.cpp)

  struct Series {
    Hid dataset = -1;
    std::vector<Hsize> row_shape;
    std::size_t row_size = 1;              // product of row_shape
    std::size_t chunk_rows = 1;            // rows per chunk
    std::size_t rows_written = 0;          // rows in the file
    std::vector<double> buffer;            // rows not yet written nor handed on, row-major
    std::size_t handed_rows = 0;           // direct: rows after rows_written, in whole chunks handed to the
                                           // compressor (out of buffer), not yet written
    std::string path;                      // normalized
    bool direct = false;                   // chunks of whole rows, written with H5Dwrite_chunk
    std::map<std::size_t, std::future<FilteredChunk>> filtered;  // by chunk index, until written
    bool shared = false;                   // written by all ranks together (share_series_with)
    bool compressed = true;                // shuffled and deflated (options); false: stored as they are
    std::size_t stride = 1;                // a row at every stride-th output (define_series)
    std::vector<unsigned char> mine;       // shared: per buffered value, whether this process writes it
    unsigned long crc = 0;                 // CRC-32 of the bytes of every row appended (row_checksums)
  };

  H5SeriesWriter(std::string final_path, const H5WriterOptions& options);
  static H5SeriesWriter open_file(const std::string& final_path, const H5WriterOptions& options, bool resume);
  Hid create_series_dataset(const std::string& key, const Series& s);
  Hid open_series_dataset(const std::string& key, Series& s);
  void require_open(const char* what) const;
  void write_buffer(const std::string& path, Series& s, bool whole_chunks_only);
  /// The series' filters: the options' shuffle and deflate, none for a series defined uncompressed.
  bool shuffles(const Series& s) const { return s.compressed && options_.shuffle; }
  int gzip_level(const Series& s) const { return s.compressed ? options_.gzip_level : 0; }
  /// The series' chunk of `values` to the background compressor.
  std::future<FilteredChunk> submit_chunk(const Series& s, std::vector<double> values) {
    return compressor_->submit(std::move(values), shuffles(s), gzip_level(s));
  }
  static std::size_t rows_to_write(const Series& s, bool whole_chunks_only);
  void write_shared(bool whole_chunks_only);  // h5_shared_series.cpp
  void close_handles() noexcept;              // the datasets and the file; the series stay defined
  void reopen_handles();
  void write_chunks(const std::string& path, Series& s, std::size_t rows);  // H5Dwrite_chunk from rows_written
  void submit_whole_chunks(Series& s);  // to the background compressor
  /// A whole chunk's values from `rows` buffered rows starting at buffer row `first_row`.
  static std::vector<double> padded_chunk(const Series& s, std::size_t first_row, std::size_t rows);
  void write_all_buffers(bool whole_chunks_only);
  void close_all() noexcept;
  void abandon() noexcept;     // after a failed write: nothing more reaches the file; close
  void reserve_for_flush();    // disk for the next flush, or abandon() and throw
  void close_uncommitted() noexcept;  // destructor body: best-effort write, close, keep .partial
  void put_attribute(const std::string& object_path, const std::string& name, Hid file_type, Hid mem_type,
                     Hid space, const void* buf);
  /// Throws the HDF5 failure as std::runtime_error; a failure while writing data closes the file
  /// first (best effort), so a full disk never leaves HDF5 half-open at exit.
  [[noreturn]] void fail(const std::string& what, const std::string& object);
  /// The dataset `key` of a write_array with its parent groups (no timestamps); the caller closes it.
  Hid create_array(const std::string& key, Hid type, Hid space);

  std::string final_path_;
  std::string partial_path_;
  Hid file_ = -1;
  Hid dxpl_ = -1;  // data transfer property list for every H5Dwrite (collective later)
  H5WriterOptions options_;
  bool resuming_ = false;       // reopen(): define_series opens existing datasets
  std::size_t resume_rows_ = 0;
  std::map<std::string, std::vector<double>> resume_unwritten_;
  std::map<std::string, double> resume_checksums_;
  /// Resuming: the CRC-32 of the `rows` first rows of `dataset` as stored, read back in blocks
  /// (h5_checksums.cpp); std::runtime_error naming the series when they cannot be read.
  unsigned long stored_rows_crc(Hid dataset, const std::string& key, std::size_t rows, std::size_t row_size);
  /// Resuming: `stored` continued over the checkpoint's unwritten `tail` becomes s.crc; throws
  /// std::runtime_error naming the series when a checksum was given for it and differs.
  void resume_row_checksum(const std::string& key, Series& s, unsigned long stored, std::span<const double> tail);
  static unsigned long row_crc(unsigned long crc, std::span<const double> values);
  /// The user block of a sealed file (H5WriterOptions::sealed) filled in: magic, CRC-32, size.
  static void seal(const std::string& path);
  std::size_t buffered_bytes_ = 0;
  std::size_t residual_bytes_ = 0;  // buffered after the last flush (its partial chunks)
  bool flushed_ = false;        // a flush() completed: the file on disk is consistent
  std::map<std::string, Series, std::less<>> series_;
  std::vector<Series*> by_id_;  // SeriesId -> series_ node (map nodes do not move)
  std::unique_ptr<ChunkCompressor> compressor_;  // background_compression
  SharedWriter shared_writer_;
};

}  // namespace raceway::h5
