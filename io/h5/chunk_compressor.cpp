#include "io/h5/chunk_compressor.hpp"

#include "io/h5/thread_core.hpp"

#include <libdeflate.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace raceway::h5 {

namespace {

/// The deflate filter's stream (H5Z_FILTER_DEFLATE: a zlib stream, RFC 1950) written by libdeflate
/// at the dataset's level, its compressor kept per thread and level. libdeflate compresses whole
/// buffers: at level 1 it takes about half the instructions of zlib's deflate at level 1 on the
/// output's shuffled chunks and stores them 0.7 % smaller (perf/studies/results/
/// revolution_instructions.md). Any inflate reads the stream (HDF5's filter inflates with zlib);
/// the bytes differ from zlib's, the values they hold do not.
class Deflater {
 public:
  Deflater() = default;
  Deflater(const Deflater&) = delete;
  Deflater& operator=(const Deflater&) = delete;
  ~Deflater() {
    if (compressor_ != nullptr) libdeflate_free_compressor(compressor_);
  }
  /// Deflates `in` into `out` (sized here); returns the compressed size.
  std::size_t deflate_all(const std::vector<unsigned char>& in, std::vector<unsigned char>& out, int level) {
    if (level_ != level) {
      if (compressor_ != nullptr) libdeflate_free_compressor(compressor_);
      level_ = -1;
      compressor_ = libdeflate_alloc_compressor(std::min(level, 12));
      if (compressor_ == nullptr) throw std::runtime_error("libdeflate could not set up a compressor for an output chunk");
      level_ = level;
    }
    out.resize(libdeflate_zlib_compress_bound(compressor_, in.size()));
    const std::size_t n = libdeflate_zlib_compress(compressor_, in.data(), in.size(), out.data(), out.size());
    if (n == 0) throw std::runtime_error("libdeflate failed on an output chunk");
    return n;
  }

 private:
  libdeflate_compressor* compressor_ = nullptr;
  int level_ = -1;  // the level compressor_ was made for; -1: none
};

}  // namespace

FilteredChunk filter_chunk(std::span<const double> values, bool shuffle, int gzip_level) {
  const std::size_t n = values.size(), bytes = values.size_bytes();
  std::vector<unsigned char> raw(bytes);
  if (shuffle) {
    // HDF5's shuffle filter (H5Z_FILTER_SHUFFLE) for 8-byte elements: byte j of element i goes to
    // j * n + i. Written here because no library exposes it apart from HDF5's pipeline, which is
    // what this file keeps off the run's thread.
    // An element's bytes are taken in one load: on a little-endian machine byte j in memory is
    // bits 8j..8j+7 of the load.
    static_assert(std::endian::native == std::endian::little, "the shuffle below reads bytes little-endian");
    const auto* in = reinterpret_cast<const unsigned char*>(values.data());
    for (std::size_t i = 0; i < n; ++i) {
      std::uint64_t v;
      std::memcpy(&v, in + i * sizeof(double), sizeof v);
      for (std::size_t j = 0; j < sizeof(double); ++j, v >>= 8) raw[j * n + i] = static_cast<unsigned char>(v);
    }
  } else {
    std::memcpy(raw.data(), values.data(), bytes);
  }
  if (gzip_level <= 0) return {std::move(raw), 0};
  // HDF5's deflate filter (H5Z_FILTER_DEFLATE): one zlib stream of the whole chunk.
  if (bytes >= (std::size_t{1} << 31)) throw std::runtime_error("an output chunk of 2 GiB or more");
  thread_local Deflater deflater;
  std::vector<unsigned char> out;
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
