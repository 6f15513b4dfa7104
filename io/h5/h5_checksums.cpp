// Checksums of the files raceway continues from (h5_series.hpp). The CRC-32 gzip uses throughout:
// zlib's crc32, or libdeflate's (the same function) for the rows appended.
//
// The rows of a .partial file (row_checksums, reopen): a checkpoint keeps, per series, the CRC-32
// of every row appended; a resume reads the rows back from the file (through HDF5, so a chunk that
// no longer inflates is found too), continues the CRC over the checkpoint's unwritten rows and
// compares. A flipped byte in the stored rows of a .partial file is so refused rather than
// carried into the finished output.
//
// Sealed files (H5WriterOptions::sealed, sealed_file_problem): the whole file after a 512-byte
// user block, checked before HDF5 reads any of it. HDF5 keeps no checksum of raw data or of
// attributes, and HDF5 1.10.8 crashed (SIGSEGV in H5Aiterate2) on one of 32 checkpoints with a
// random byte flipped in an object header: only a check before HDF5 parses the file refuses every
// damaged one.
#include <hdf5.h>
#include <libdeflate.h>
#include <zlib.h>

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <fstream>

#include "io/h5/h5_series.hpp"
#include "io/h5/h5_support.hpp"

namespace raceway::h5 {

using h5::Handle;

unsigned long H5SeriesWriter::row_crc(unsigned long crc, std::span<const double> values) {
  // libdeflate's CRC-32 is zlib's (the same polynomial and chaining), in fewer instructions per row.
  // An empty span may have no data pointer, and both libraries answer a null buffer with the
  // initial value 0, not the running checksum: a resumed series with no rows past its last stored
  // chunk lost its checksum that way.
  if (values.empty()) return crc;
  return libdeflate_crc32(static_cast<std::uint32_t>(crc), values.data(), values.size_bytes());
}

std::map<std::string, double> H5SeriesWriter::row_checksums() const {
  std::map<std::string, double> out;
  for (const auto& [path, s] : series_)
    if (!s.shared) out.emplace(path, static_cast<double>(s.crc));
  return out;
}

unsigned long H5SeriesWriter::stored_rows_crc(Hid dataset, const std::string& key, std::size_t rows,
                                              std::size_t row_size) {
  unsigned long crc = crc32(0L, Z_NULL, 0);
  if (rows == 0) return crc;
  const Handle space(H5Dget_space(dataset), H5Sclose);
  if (!space.ok()) fail("reading the series back to check it (H5Dget_space)", key);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 1)));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  // Blocks of about 4 MiB of rows, so that a large file is checked in bounded memory.
  const std::size_t block = std::max<std::size_t>(1, (std::size_t{4} << 20) / (row_size * sizeof(double)));
  std::vector<double> values;
  for (std::size_t first = 0; first < rows; first += block) {
    const std::size_t count = std::min(block, rows - first);
    std::vector<hsize_t> start(dims.size(), 0), size = dims;
    start[0] = first, size[0] = count;
    const Handle memory(H5Screate_simple(static_cast<int>(size.size()), size.data(), nullptr), H5Sclose);
    values.resize(count * row_size);
    if (!memory.ok() ||
        H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start.data(), nullptr, size.data(), nullptr) < 0 ||
        H5Dread(dataset, H5T_NATIVE_DOUBLE, memory.get(), space.get(), dxpl_, values.data()) < 0)
      throw std::runtime_error(fmt::format("H5SeriesWriter: cannot continue '{}': the rows {}..{} of series '{}' cannot "
                                           "be read back (a damaged chunk): {}",
                                           partial_path_, first, first + count - 1, key,
                                           h5::saved_error().empty() ? h5::error_text() : h5::saved_error()));
    crc = row_crc(crc, values);
  }
  return crc;
}

void H5SeriesWriter::resume_row_checksum(const std::string& key, Series& s, unsigned long stored,
                                         std::span<const double> tail) {
  s.crc = row_crc(stored, tail);
  const auto expected = resume_checksums_.find(key);
  if (expected == resume_checksums_.end() || expected->second == static_cast<double>(s.crc)) return;
  throw std::runtime_error(fmt::format("H5SeriesWriter: cannot continue '{}': series '{}' is damaged: its rows have "
                                       "the CRC-32 {}, the checkpoint's record says {}",
                                       partial_path_, key, s.crc, expected->second));
}

namespace {

constexpr const char* kSealMagic = "raceway sealed HDF5 file\n";

/// CRC-32 and byte count of `in` from its position to its end.
std::pair<unsigned long, unsigned long long> crc_of_rest(std::istream& in) {
  unsigned long crc = crc32(0L, Z_NULL, 0);
  unsigned long long bytes = 0;
  std::vector<char> block(std::size_t{1} << 20);
  while (in) {
    in.read(block.data(), static_cast<std::streamsize>(block.size()));
    const auto got = static_cast<std::size_t>(in.gcount());
    crc = crc32(crc, reinterpret_cast<const Bytef*>(block.data()), static_cast<uInt>(got));
    bytes += got;
  }
  return {crc, bytes};
}

}  // namespace

void H5SeriesWriter::seal(const std::string& path) {
  std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
  if (!file) throw std::runtime_error(fmt::format("H5SeriesWriter: cannot open '{}' to seal it", path));
  file.seekg(static_cast<std::streamoff>(kSealBytes));
  const auto [crc, bytes] = crc_of_rest(file);
  file.clear();
  std::string block = fmt::format("{}crc32 {:08x} bytes {}\n", kSealMagic, crc, bytes);
  block.resize(kSealBytes, '\0');
  file.seekp(0);
  file.write(block.data(), static_cast<std::streamsize>(block.size()));
  file.flush();
  if (!file) throw std::runtime_error(fmt::format("H5SeriesWriter: cannot seal '{}' (writing its user block)", path));
}

std::string sealed_file_problem(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return "it cannot be opened";
  std::string block(kSealBytes, '\0');
  file.read(block.data(), static_cast<std::streamsize>(block.size()));
  if (static_cast<std::size_t>(file.gcount()) != block.size() || !block.starts_with(kSealMagic))
    return "it carries no seal (not a checkpoint of this raceway version, or its first bytes are damaged)";
  unsigned long crc = 0;
  unsigned long long bytes = 0;
  if (std::sscanf(block.c_str() + std::char_traits<char>::length(kSealMagic), "crc32 %lx bytes %llu", &crc, &bytes) != 2)
    return "its seal does not read (its first bytes are damaged)";
  const auto [actual_crc, actual_bytes] = crc_of_rest(file);
  if (actual_bytes != bytes)
    return fmt::format("it has {} bytes after its seal, the seal says {} (a cut or extended file)", actual_bytes, bytes);
  if (actual_crc != crc)
    return fmt::format("the CRC-32 of its bytes is {:08x}, its seal says {:08x}: the file is damaged", actual_crc, crc);
  return "";
}

}  // namespace raceway::h5
