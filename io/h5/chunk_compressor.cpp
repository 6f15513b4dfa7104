#include "io/h5/chunk_compressor.hpp"

#include "io/h5/thread_core.hpp"

#include <zlib.h>

#include <cstring>
#include <stdexcept>

namespace raceway::h5 {

namespace {

/// compress2's work with the deflate state kept per thread: compress2 allocates and sets up about
/// 270 KB of state per call (deflateInit), deflateReset only resets it (measured: 1-3 % of the
/// compressor thread's CPU in 6309 R3 and QJ215 runs; deflate itself is the rest). zlib documents deflateReset as equivalent to deflateEnd
/// followed by deflateInit, and compress2 is deflateInit, one deflate(Z_FINISH) (for inputs below
/// 4 GiB) and deflateEnd: the same bytes (the unit test compares them with HDF5's own).
class Deflater {
 public:
  Deflater() = default;
  Deflater(const Deflater&) = delete;
  Deflater& operator=(const Deflater&) = delete;
  ~Deflater() {
    if (level_ >= 0) deflateEnd(&stream_);
  }
  /// Deflates `in` into `out` (at least compressBound(in) bytes); returns the compressed size.
  std::size_t deflate_all(const std::vector<unsigned char>& in, std::vector<unsigned char>& out, int level) {
    if (level_ != level) {
      if (level_ >= 0) deflateEnd(&stream_);
      level_ = -1;
      stream_ = z_stream{};
      if (deflateInit(&stream_, level) != Z_OK) throw std::runtime_error("zlib deflateInit failed on an output chunk");
      level_ = level;
    } else if (deflateReset(&stream_) != Z_OK) {
      throw std::runtime_error("zlib deflateReset failed on an output chunk");
    }
    stream_.next_in = const_cast<Bytef*>(in.data());  // zlib's API is not const-correct; it only reads
    stream_.avail_in = static_cast<uInt>(in.size());
    stream_.next_out = out.data();
    stream_.avail_out = static_cast<uInt>(out.size());
    if (deflate(&stream_, Z_FINISH) != Z_STREAM_END) throw std::runtime_error("zlib deflate failed on an output chunk");
    return out.size() - stream_.avail_out;
  }

 private:
  z_stream stream_{};
  int level_ = -1;  // the level stream_ was initialised with; -1: none
};

}  // namespace

FilteredChunk filter_chunk(std::span<const double> values, bool shuffle, int gzip_level) {
  const std::size_t n = values.size(), bytes = values.size_bytes();
  std::vector<unsigned char> raw(bytes);
  if (shuffle) {
    // HDF5's shuffle filter (H5Z_FILTER_SHUFFLE) for 8-byte elements: byte j of element i goes to
    // j * n + i. Written here because no library exposes it apart from HDF5's pipeline, which is
    // what this file keeps off the run's thread.
    const auto* in = reinterpret_cast<const unsigned char*>(values.data());
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < sizeof(double); ++j) raw[j * n + i] = in[i * sizeof(double) + j];
  } else {
    std::memcpy(raw.data(), values.data(), bytes);
  }
  if (gzip_level <= 0) return {std::move(raw), 0};
  // HDF5's deflate filter (H5Z_FILTER_DEFLATE): compress2 into a compressBound() buffer.
  if (bytes >= (std::size_t{1} << 31)) throw std::runtime_error("an output chunk of 2 GiB or more");
  thread_local Deflater deflater;
  std::vector<unsigned char> out(compressBound(static_cast<uLong>(bytes)));
  out.resize(deflater.deflate_all(raw, out, gzip_level));
  return {std::move(out), 0};
}

ChunkCompressor::ChunkCompressor(int core) : thread_([this] { work(); }) {
  if (core >= 0) bind_thread_to_core(thread_, core);
}

ChunkCompressor::~ChunkCompressor() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

std::future<FilteredChunk> ChunkCompressor::submit(std::vector<double> values, bool shuffle, int gzip_level) {
  std::packaged_task<FilteredChunk()> task(
      [v = std::move(values), shuffle, gzip_level] { return filter_chunk(v, shuffle, gzip_level); });
  std::future<FilteredChunk> result = task.get_future();
  {
    const std::lock_guard lock(mutex_);
    queue_.push_back(std::move(task));
  }
  wake_.notify_one();
  return result;
}

void ChunkCompressor::work() {
  for (;;) {
    std::packaged_task<FilteredChunk()> task;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping, and every queued chunk done
      task = std::move(queue_.front());
      queue_.pop_front();
    }
    task();  // an exception is stored in the task's future
  }
}

}  // namespace raceway::h5
