// Compression of whole chunks of the output's time series off the run's thread.
//
// H5SeriesWriter stores its series chunked, byte-shuffled and deflated. Through HDF5's filter
// pipeline that work happens inside H5Dwrite/H5Dclose on the calling thread: measured, 30 ms of a
// 0.13 s 6309 R3 run (perf/studies/results/output_overhead.md). The writer therefore compresses each
// chunk as soon as its rows are complete, on a background thread, with the two filters HDF5's
// pipeline applies (shuffle, then a zlib stream at the dataset's level, written by libdeflate),
// and hands the result to H5Dwrite_chunk at the next flush: readers (h5py, h5ls, HDF5 itself)
// inflate it through the dataset's own filters and see the same values.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <future>
#include <mutex>
#include <span>
#include <thread>
#include <vector>

namespace raceway::h5 {

/// One chunk as stored: bytes after the filters, and the filter mask H5Dwrite_chunk takes
/// (0: every filter of the dataset applied).
struct FilteredChunk {
  std::vector<unsigned char> bytes;
  std::uint32_t filter_mask = 0;
};

/// The bytes stored for `values` (a whole chunk, row-major) under HDF5's filters: byte shuffle of
/// 8-byte elements if `shuffle` (H5Z_FILTER_SHUFFLE), then, if `gzip_level` > 0, one zlib stream
/// (H5Z_FILTER_DEFLATE) at that level from libdeflate: it inflates to what HDF5's pipeline would
/// have deflated.
FilteredChunk filter_chunk(std::span<const double> values, bool shuffle, int gzip_level);

/// A single background thread that runs filter_chunk() on submitted chunks, first in first out.
/// Destroying it finishes the queued chunks (their futures stay valid) and joins the thread.
class ChunkCompressor {
 public:
  /// `core` >= 0: the thread is bound to that logical CPU alone (io/h5/thread_core.hpp).
  explicit ChunkCompressor(int core = -1);
  ~ChunkCompressor();
  ChunkCompressor(const ChunkCompressor&) = delete;
  ChunkCompressor& operator=(const ChunkCompressor&) = delete;

  /// Queues a chunk (the values are moved in) and returns its bytes to come: filter_chunk(values,
  /// shuffle, gzip_level), the filters of the chunk's dataset.
  std::future<FilteredChunk> submit(std::vector<double> values, bool shuffle, int gzip_level);

 private:
  void work();

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::packaged_task<FilteredChunk()>> queue_;
  bool stopping_ = false;
  std::thread thread_;  // last: started after the members it uses
};

}  // namespace raceway::h5
