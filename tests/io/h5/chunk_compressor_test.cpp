// Tests of the chunk filter (io/h5/chunk_compressor.hpp): the bytes it stores inflate (zlib's
// inflate, as HDF5's deflate filter reads them) to the chunk's values shuffled as HDF5 shuffles them,
// whatever share of the byte planes goes into stored blocks.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "io/h5/chunk_compressor.hpp"

namespace {

using raceway::h5::filter_chunk;

std::vector<unsigned char> inflated(const std::vector<unsigned char>& bytes, std::size_t size) {
  std::vector<unsigned char> out(size + 1);
  uLongf n = out.size();
  if (uncompress(out.data(), &n, bytes.data(), static_cast<uLong>(bytes.size())) != Z_OK) return {};
  out.resize(n);
  return out;
}

// HDF5's shuffle of 8-byte elements, written out plainly: byte j of element i at j n + i.
std::vector<unsigned char> shuffled(const std::vector<double>& v) {
  const std::size_t n = v.size();
  std::vector<unsigned char> out(n * 8);
  for (std::size_t i = 0; i < n; ++i) {
    unsigned char b[8];
    std::memcpy(b, &v[i], 8);
    for (std::size_t j = 0; j < 8; ++j) out[j * n + i] = b[j];
  }
  return out;
}

}  // namespace

// Smooth values (compressible high planes, noise in the low ones), random bit patterns (every plane
// noise: the stream is stored blocks only, the last one final), chunks of more than one stored
// block (over 64 KiB of noise planes), a short chunk (no planes stored), constants: each inflates
// to the shuffled values, shuffled or not, at levels 1 and 6; shuffled, noise costs at most 5 bytes
// per 64 KiB stored block and the stream's 6 more than the raw bytes.
TEST(ChunkFilter, InflatesToTheShuffledValues) {
  std::mt19937_64 rng(7);
  std::vector<std::vector<double>> chunks;
  for (const std::size_t n : {2048u, 40003u, 100u}) {  // 40003: eight at a time and a remainder
    std::vector<double> smooth(n), random_bits(n), constant(n, 0.25);
    for (std::size_t i = 0; i < n; ++i) {
      smooth[i] = std::sin(1e-3 * static_cast<double>(i)) * 1e3;
      const std::uint64_t r = rng();  // any bits (NaNs too: the filter copies bytes)
      std::memcpy(&random_bits[i], &r, 8);
    }
    chunks.insert(chunks.end(), {smooth, random_bits, constant});
  }
  for (const int level : {1, 6})
    for (const bool shuffle : {true, false})
      for (const auto& values : chunks) {
        const auto stored = filter_chunk(values, shuffle, level);
        EXPECT_EQ(stored.filter_mask, 0u);
        std::vector<unsigned char> expected(values.size() * 8);
        if (shuffle)
          expected = shuffled(values);
        else
          std::memcpy(expected.data(), values.data(), expected.size());
        EXPECT_EQ(inflated(stored.bytes, expected.size()), expected) << values.size() << " values, level " << level;
        const std::size_t bound = expected.size() + 5 * (expected.size() / 65535 + 1) + 6;
        if (shuffle) {
          EXPECT_LE(stored.bytes.size(), bound) << values.size() << " values";
        }
      }
}
