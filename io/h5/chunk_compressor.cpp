#include "io/h5/chunk_compressor.hpp"

#include "io/h5/thread_core.hpp"

#include <zlib.h>

#include <cstring>
#include <stdexcept>

namespace raceway::io {

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
  uLongf size = compressBound(static_cast<uLong>(bytes));
  std::vector<unsigned char> out(size);
  if (compress2(out.data(), &size, raw.data(), static_cast<uLong>(bytes), gzip_level) != Z_OK)
    throw std::runtime_error("zlib compress2 failed on an output chunk");
  out.resize(size);
  return {std::move(out), 0};
}

ChunkCompressor::ChunkCompressor(bool shuffle, int gzip_level, int core)
    : shuffle_(shuffle), gzip_level_(gzip_level), thread_([this] { work(); }) {
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

std::future<FilteredChunk> ChunkCompressor::submit(std::vector<double> values) {
  std::packaged_task<FilteredChunk()> task(
      [v = std::move(values), shuffle = shuffle_, level = gzip_level_] { return filter_chunk(v, shuffle, level); });
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

}  // namespace raceway::io
