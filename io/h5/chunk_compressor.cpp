#include "io/h5/chunk_compressor.hpp"

#include "io/h5/thread_core.hpp"

#include <libdeflate.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace raceway::h5 {

namespace {

/// The deflate filter's stream (H5Z_FILTER_DEFLATE: a zlib stream, RFC 1950) of a chunk, whose
/// first `stored` bytes go into stored blocks (RFC 1951 sec. 3.2.4: copied as they are) and the
/// rest is compressed by libdeflate at the dataset's level, its compressor kept per thread and
/// level. libdeflate compresses whole buffers: at level 1 it takes about half the instructions of
/// zlib's deflate at level 1 on the output's shuffled chunks and stores them 0.7 % smaller
/// (perf/studies/results/revolution_instructions.md). The stored blocks come first and are not
/// final, so libdeflate's stream (which ends with the final block) completes the one stream. Any
/// inflate reads it (HDF5's filter inflates with zlib); the bytes differ from zlib's, the values
/// they hold do not.
class Deflater {
 public:
  Deflater() = default;
  Deflater(const Deflater&) = delete;
  Deflater& operator=(const Deflater&) = delete;
  ~Deflater() {
    if (compressor_ != nullptr) libdeflate_free_compressor(compressor_);
  }
  /// The zlib stream of the `size` bytes at `in`, the first `stored` of them stored.
  std::vector<unsigned char> deflate_all(const unsigned char* in, std::size_t size, std::size_t stored, int level) {
    if (level_ != level) {
      if (compressor_ != nullptr) libdeflate_free_compressor(compressor_);
      level_ = -1;
      compressor_ = libdeflate_alloc_compressor(std::min(level, 12));
      if (compressor_ == nullptr) throw std::runtime_error("libdeflate could not set up a compressor for an output chunk");
      level_ = level;
    }
    constexpr std::size_t block = 65535;  // the largest stored block
    const std::size_t rest = size - stored, blocks = (stored + block - 1) / block;
    const std::size_t bound = 2 + blocks * 5 + stored + libdeflate_deflate_compress_bound(compressor_, rest) + 4;
    if (out_.size() < bound) out_.resize(bound);  // grown, never cleared again: the scratch of every chunk
    unsigned char* out = out_.data();
    std::size_t o = 0;
    out[o++] = 0x78, out[o++] = 0x01;  // zlib header: deflate, 32 KiB window, fastest (31 divides 0x7801)
    for (std::size_t done = 0; done < stored; done += block) {
      const auto len = static_cast<std::uint16_t>(std::min(block, stored - done));
      const bool final = rest == 0 && done + len == stored;
      out[o++] = final ? 1 : 0;  // BFINAL, BTYPE 00 (stored), then the byte's padding
      const std::uint16_t nlen = static_cast<std::uint16_t>(~len);
      for (const std::uint16_t v : {len, nlen}) out[o++] = static_cast<unsigned char>(v), out[o++] = static_cast<unsigned char>(v >> 8);
      std::memcpy(out + o, in + done, len);
      o += len;
    }
    if (rest > 0 || stored == 0) {
      const std::size_t n = libdeflate_deflate_compress(compressor_, in + stored, rest, out + o, bound - o);
      if (n == 0) throw std::runtime_error("libdeflate failed on an output chunk");
      o += n;
    }
    const std::uint32_t adler = libdeflate_adler32(1, in, size);
    for (int shift = 24; shift >= 0; shift -= 8) out[o++] = static_cast<unsigned char>(adler >> shift);
    return {out, out + o};
  }

 private:
  std::vector<unsigned char> out_;
  libdeflate_compressor* compressor_ = nullptr;
  int level_ = -1;  // the level compressor_ was made for; -1: none
};

/// The shuffled chunk's leading byte planes (plane j: byte j of every element, the least
/// significant first) that deflate could not shrink: each of `planes` planes of `n` bytes whose
/// bytes carry more than 7.5 bits of (order-0) entropy, up to the first that carries less. On the
/// output's series these are the low bytes of the mantissas, about a fifth of the bytes: storing
/// them saves a fifth of the deflate's work for files 0.7 % smaller (deflate's Huffman codes
/// spend more on them than they are).
std::size_t noise_planes(const unsigned char* raw, std::size_t n, std::size_t planes) {
  thread_local std::vector<double> c_log_c;  // c log2 c for the counts 0 .. n
  for (std::size_t c = c_log_c.size(); c <= n; ++c) c_log_c.push_back(c == 0 ? 0.0 : static_cast<double>(c) * std::log2(static_cast<double>(c)));
  const double limit = static_cast<double>(n) * (std::log2(static_cast<double>(n)) - 7.5);
  std::size_t j = 0;
  for (; j < planes; ++j) {
    std::array<std::uint32_t, 256> count{};
    const unsigned char* plane = raw + j * n;
    for (std::size_t i = 0; i < n; ++i) ++count[plane[i]];
    double sum = 0;  // entropy = log2 n - sum / n bits per byte
    for (const std::uint32_t c : count) sum += c_log_c[c];
    if (!(sum < limit)) break;
  }
  return j;
}


/// HDF5's shuffle filter (H5Z_FILTER_SHUFFLE) for 8-byte elements: byte j of element i goes to
/// j n + i. Written here because no library exposes it apart from HDF5's pipeline, which is what
/// this file keeps off the run's thread. Eight elements at a time as an 8 x 8 byte transpose of
/// their words (three rounds of swapping halves: bytes, byte pairs, byte quadruples), each plane's
/// eight bytes stored in one word; the rest one byte at a time. A word's byte j is its bits
/// 8j..8j+7 on a little-endian machine.
void shuffle_8(const unsigned char* in, std::size_t n, unsigned char* out) {
  static_assert(std::endian::native == std::endian::little, "the shuffle reads bytes little-endian");
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    std::uint64_t r[8];
    std::memcpy(r, in + i * 8, sizeof r);
    auto swap_round = [&r](int step, std::uint64_t mask) {  // rows k and k + step swap byte groups
      const int bits = 8 * step;
      for (int k = 0; k < 8; ++k) {
        if ((k & step) != 0) continue;
        const std::uint64_t t = ((r[k] >> bits) ^ r[k + step]) & mask;
        r[k + step] ^= t;
        r[k] ^= t << bits;
      }
    };
    swap_round(1, 0x00FF00FF00FF00FFull);
    swap_round(2, 0x0000FFFF0000FFFFull);
    swap_round(4, 0x00000000FFFFFFFFull);
    for (std::size_t j = 0; j < 8; ++j) std::memcpy(out + j * n + i, &r[j], 8);
  }
  for (; i < n; ++i)
    for (std::size_t j = 0; j < 8; ++j) out[j * n + i] = in[i * 8 + j];
}

}  // namespace

FilteredChunk filter_chunk(std::span<const double> values, bool shuffle, int gzip_level) {
  const std::size_t n = values.size(), bytes = values.size_bytes();  // n elements
  thread_local std::vector<unsigned char> scratch;  // grown, never cleared again
  if (scratch.size() < bytes) scratch.resize(bytes);
  const auto* in = reinterpret_cast<const unsigned char*>(values.data());
  const unsigned char* raw = in;
  if (shuffle) {
    shuffle_8(in, n, scratch.data());
    raw = scratch.data();
  }
  if (gzip_level <= 0) return {std::vector<unsigned char>(raw, raw + bytes), 0};
  // HDF5's deflate filter (H5Z_FILTER_DEFLATE): one zlib stream of the whole chunk.
  if (bytes >= (std::size_t{1} << 31)) throw std::runtime_error("an output chunk of 2 GiB or more");
  thread_local Deflater deflater;
  const std::size_t stored = shuffle && n >= 256 ? noise_planes(raw, n, sizeof(double)) * n : 0;
  return {deflater.deflate_all(raw, bytes, stored, gzip_level), 0};
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
