// Tests of the HDF5 writer's run-survival features (io/h5/h5_series.hpp): rows kept in memory until a
// flush, continuing an interrupted file (reopen), the time dimension scale, replacing fixed arrays,
// and the small reader (io/h5/h5_reader.hpp).
#include <gtest/gtest.h>
#include <hdf5.h>
#include <hdf5_hl.h>
#include <unistd.h>
#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "io/h5/h5_reader.hpp"
#include "io/h5/h5_series.hpp"
#include "tests/support/temp_dir.hpp"

namespace fs = std::filesystem;
using raceway::h5::H5Reader;
using raceway::h5::H5SeriesWriter;

namespace {

using H5Writer = raceway::test::TempDir;

std::string bytes_of(const std::string& path) { return raceway::test::read_text(path); }

// Writes rows [first, last) of a [T] series "/time" (value 0.5 * row) and a [T x 2] series "/xy".
void append_rows(H5SeriesWriter& w, int first, int last, double offset = 0) {
  for (int r = first; r < last; ++r) {
    const double t = 0.5 * r + offset;
    const double xy[2] = {t, -t};
    w.append("/time", std::span<const double>(&t, 1));
    w.append("/xy", xy);
  }
}

void define(H5SeriesWriter& w) {
  w.define_series("/time", {}, "s", "time");
  w.define_series("/xy", {2}, "m", "position");
}

}  // namespace

TEST_F(H5Writer, RowsStayInMemoryUntilFlushSoTheFileOnDiskIsTheLastFlushed) {
  auto w = H5SeriesWriter::create(path("a.h5"));
  define(w);
  w.flush();
  const std::string after_flush = bytes_of(path("a.h5.partial"));
  append_rows(w, 0, 5000);
  EXPECT_EQ(w.buffered_bytes(), 5000u * 3 * sizeof(double));
  EXPECT_EQ(bytes_of(path("a.h5.partial")), after_flush) << "the file changed between flushes";
  // Whole chunks are with the compressor until the flush: the unwritten rows are asked after it.
  EXPECT_THROW(w.unwritten_rows(), std::logic_error);
  w.flush();
  EXPECT_NE(bytes_of(path("a.h5.partial")), after_flush);
  // A flush writes whole chunks (16 KiB: 2048 rows of /time, 1024 of /xy); the rest stays buffered.
  const H5Reader r(path("a.h5.partial"));  // readable while the writer has it open
  EXPECT_EQ(r.doubles("/time").size(), 4096u);
  EXPECT_EQ(r.doubles("/xy").size(), 4096u * 2);
  const auto unwritten = w.unwritten_rows();
  ASSERT_EQ(unwritten.size(), 2u);
  EXPECT_EQ(unwritten.at("/time").size(), 904u);
  EXPECT_EQ(unwritten.at("/time").front(), 0.5 * 4096);
  EXPECT_EQ(unwritten.at("/xy").size(), 904u * 2);
  EXPECT_EQ(w.buffered_bytes(), 904u * 3 * sizeof(double));
  const std::string after_second = bytes_of(path("a.h5.partial"));
  w.flush();  // nothing new to write: whole chunks once written are never written again
  EXPECT_EQ(bytes_of(path("a.h5.partial")), after_second);
  w.commit();
  const H5Reader done(path("a.h5"));
  EXPECT_EQ(done.doubles("/time").size(), 5000u);
}

TEST_F(H5Writer, ReopenCutsTheSeriesToTheCheckpointAndContinuesThem) {
  std::map<std::string, std::vector<double>> unwritten;
  {
    auto w = H5SeriesWriter::create(path("r.h5"));
    define(w);
    append_rows(w, 0, 3000);
    w.flush();  // the checkpoint: 3000 rows, of which the file holds 2048 of /time and 2048 of /xy
    unwritten = w.unwritten_rows();
    append_rows(w, 3000, 5000, 100.0);  // after the checkpoint: must go
    w.flush();
  }  // destroyed without commit: an interrupted run (it writes what it has)
  ASSERT_TRUE(fs::exists(path("r.h5.partial")));
  {
    auto w = H5SeriesWriter::reopen(path("r.h5"), 3000, unwritten);
    define(w);
    EXPECT_EQ(w.rows("/time"), 3000u);
    append_rows(w, 3000, 3016);
    w.commit();
  }
  const H5Reader r(path("r.h5"));
  std::vector<std::size_t> shape;
  const auto t = r.doubles("/time", &shape);
  ASSERT_EQ(shape, std::vector<std::size_t>{3016});
  for (int i = 0; i < 3016; ++i) ASSERT_EQ(t[static_cast<std::size_t>(i)], 0.5 * i) << i;
  const auto xy = r.doubles("/xy", &shape);
  EXPECT_EQ(shape, (std::vector<std::size_t>{3016, 2}));
  EXPECT_EQ(xy[2 * 3015 + 1], -0.5 * 3015);
  EXPECT_EQ(r.string_attribute("/xy", "units"), "m");
}

TEST_F(H5Writer, ReopenRefusesAMissingFileAShorterSeriesOrAnotherShape) {
  EXPECT_THROW((void)H5SeriesWriter::reopen(path("none.h5"), 3), std::runtime_error);
  {
    auto w = H5SeriesWriter::create(path("s.h5"));
    define(w);
    append_rows(w, 0, 4);
    w.flush();
  }
  {
    auto w = H5SeriesWriter::reopen(path("s.h5"), 5);  // the file holds 4 rows (written when destroyed)
    try {
      define(w);
      ADD_FAILURE() << "a series with fewer rows than the checkpoint was continued";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("has 4 rows, the checkpoint needs 5"), std::string::npos) << e.what();
    }
  }
  auto w = H5SeriesWriter::reopen(path("s.h5"), 2);
  w.define_series("/time", {}, "s", "time");
  try {
    w.define_series("/xy", {3}, "m", "another shape");
    ADD_FAILURE() << "a series of another shape was continued";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("another shape"), std::string::npos) << e.what();
  }
}

TEST_F(H5Writer, TimeIsTheDimensionScaleOfEverySeries) {
  {
    auto w = H5SeriesWriter::create(path("d.h5"));
    define(w);
    w.define_series("/g/matrix", {2, 3}, "N", "m");
    w.set_time_scale("/time", "time");
    append_rows(w, 0, 3);
    for (int r = 0; r < 3; ++r) w.append("/g/matrix", std::vector<double>(6, r));
    w.commit();
  }
  const hid_t f = H5Fopen(path("d.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t time = H5Dopen2(f, "/time", H5P_DEFAULT);
  EXPECT_GT(H5DSis_scale(time), 0);
  char name[16] = {};
  H5DSget_scale_name(time, name, sizeof name);
  EXPECT_STREQ(name, "time");
  for (const char* p : {"/xy", "/g/matrix"}) {
    const hid_t d = H5Dopen2(f, p, H5P_DEFAULT);
    EXPECT_GT(H5DSis_attached(d, time, 0), 0) << p;
    EXPECT_EQ(H5DSget_num_scales(d, 1), 0) << p;
    H5Dclose(d);
  }
  H5Dclose(time);
  H5Fclose(f);
}

// A series with a row at every 3rd output only (the segment diagnostics at [output] segment_every = 3):
// a reopen after 3001 outputs keeps ceil(3001 / 3) = 1001 of its rows (outputs 0, 3, ..., 3000), and
// the time scales attach by stride.
TEST_F(H5Writer, AStridedSeriesIsCutToItsRowsAndHasItsOwnScale) {
  auto define_all = [](H5SeriesWriter& w) {
    define(w);
    w.define_series("/coarse_time", {}, "s", "every 3rd output time", false, true, 3);
    w.define_series("/coarse", {2}, "N", "every 3rd output", false, true, 3);
  };
  auto append_all = [](H5SeriesWriter& w, int first, int last, double offset) {
    for (int r = first; r < last; ++r) {
      append_rows(w, r, r + 1, offset);
      if (r % 3 != 0) continue;
      const double t = 0.5 * r + offset, row[2] = {t, 2 * t};
      w.append("/coarse_time", std::span<const double>(&t, 1));
      w.append("/coarse", row);
    }
  };
  std::map<std::string, std::vector<double>> unwritten;
  {
    auto w = H5SeriesWriter::create(path("c.h5"));
    define_all(w);
    append_all(w, 0, 3001, 0);
    w.flush();  // the checkpoint after output 3000
    unwritten = w.unwritten_rows();
    append_all(w, 3001, 4000, 100);  // after the checkpoint: must go
    w.flush();
  }
  {
    auto w = H5SeriesWriter::reopen(path("c.h5"), 3001, unwritten);
    define_all(w);
    w.set_time_scale("/coarse_time", "coarse time");
    w.set_time_scale("/time", "time");
    EXPECT_EQ(w.rows("/time"), 3001u);
    EXPECT_EQ(w.rows("/coarse"), 1001u);
    append_all(w, 3001, 3010, 0);
    w.commit();
  }
  const H5Reader r(path("c.h5"));
  std::vector<std::size_t> shape;
  const auto coarse = r.doubles("/coarse", &shape);
  ASSERT_EQ(shape, (std::vector<std::size_t>{1004, 2}));  // outputs 0, 3, ..., 3009
  for (std::size_t i = 0; i < 1004; ++i) ASSERT_EQ(coarse[2 * i + 1], 3.0 * static_cast<double>(i)) << i;
  EXPECT_EQ(r.doubles("/time").size(), 3010u);
  const hid_t f = H5Fopen(path("c.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t time = H5Dopen2(f, "/time", H5P_DEFAULT), coarse_time = H5Dopen2(f, "/coarse_time", H5P_DEFAULT);
  const hid_t xy = H5Dopen2(f, "/xy", H5P_DEFAULT), strided = H5Dopen2(f, "/coarse", H5P_DEFAULT);
  EXPECT_GT(H5DSis_attached(xy, time, 0), 0);
  EXPECT_EQ(H5DSis_attached(xy, coarse_time, 0), 0);
  EXPECT_GT(H5DSis_attached(strided, coarse_time, 0), 0);
  EXPECT_EQ(H5DSis_attached(strided, time, 0), 0);
  for (const hid_t d : {time, coarse_time, xy, strided}) H5Dclose(d);
  H5Fclose(f);
}

TEST_F(H5Writer, WriteArrayReplacesAFixedArrayButNotASeries) {
  auto w = H5SeriesWriter::create(path("w.h5"));
  define(w);
  w.write_array("/fixed", {2}, std::vector<double>{1, 2}, "s", "first");
  w.write_array("/fixed", {3}, std::vector<double>{4, 5, 6}, "m", "second");
  EXPECT_THROW(w.write_array("/xy", {1}, std::vector<double>{1}, "m", "clash"), std::runtime_error);
  w.commit();
  const H5Reader r(path("w.h5"));
  EXPECT_EQ(r.doubles("/fixed"), (std::vector<double>{4, 5, 6}));
  EXPECT_EQ(r.string_attribute("/fixed", "description"), "second");
  EXPECT_TRUE(r.has("/xy"));
  EXPECT_FALSE(r.has("/nothing/here"));
  EXPECT_THROW((void)r.doubles("/nothing"), std::runtime_error);
}

namespace {

// The zlib stream `bytes` inflated (zlib's inflate, as HDF5's deflate filter reads it); empty if
// it is not one whole stream.
std::vector<char> inflated(const std::vector<char>& bytes) {
  std::vector<char> out(std::size_t{1} << 16);  // the chunks here are 16 KiB
  uLongf size = out.size();
  if (uncompress(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(bytes.data()),
                 static_cast<uLong>(bytes.size())) != Z_OK)
    return {};
  out.resize(size);
  return out;
}

// Every stored chunk of every chunked dataset of a file: filter mask and bytes, by dataset and offset.
std::map<std::string, std::pair<std::uint32_t, std::vector<char>>> stored_chunks(const std::string& file_path) {
  std::map<std::string, std::pair<std::uint32_t, std::vector<char>>> out;
  const hid_t file = H5Fopen(file_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  for (const char* name : {"/time", "/xy", "/wide", "/raw"}) {
    const hid_t d = H5Dopen2(file, name, H5P_DEFAULT);
    const hid_t space = H5Dget_space(d);
    hsize_t chunks = 0;
    H5Dget_num_chunks(d, space, &chunks);
    for (hsize_t i = 0; i < chunks; ++i) {
      hsize_t offset[2] = {0, 0};
      unsigned mask = 0;
      haddr_t address = 0;
      hsize_t size = 0;
      H5Dget_chunk_info(d, space, i, offset, &mask, &address, &size);
      std::vector<char> bytes(size);
      std::uint32_t read_mask = 0;
      H5Dread_chunk(d, H5P_DEFAULT, offset, &read_mask, bytes.data());
      out[std::string(name) + "@" + std::to_string(offset[0]) + "," + std::to_string(offset[1])] = {read_mask,
                                                                                                     std::move(bytes)};
    }
    H5Sclose(space);
    H5Dclose(d);
  }
  H5Fclose(file);
  return out;
}

}  // namespace

// Chunks filtered on the background thread and stored with H5Dwrite_chunk (libdeflate's zlib
// streams) inflate to the bytes of the chunks HDF5's own filter pipeline stores (shuffle + deflate,
// and deflate alone), whole and partial, across flushes, and take no more room (within 1 %); a
// series whose row does not fit a chunk (/wide: 2100 values, 16 KiB chunks) takes HDF5's path;
// at two gzip levels one after the other (each thread keeps its compressor between chunks). A
// series defined uncompressed (/raw) has no filters on either path: its chunks are its values' bytes.
TEST_F(H5Writer, BackgroundCompressionStoresChunksThatInflateToHdf5s) {
  for (const auto& [shuffle, level] : {std::pair{true, 1}, std::pair{false, 1}, std::pair{true, 6}}) {
    std::map<std::string, std::pair<std::uint32_t, std::vector<char>>> chunks[2];
    for (const bool background : {false, true}) {
      raceway::h5::H5WriterOptions options;
      options.shuffle = shuffle;
      options.gzip_level = level;
      options.background_compression = background;
      const std::string out = path(std::string("c") + (background ? "1" : "0") + ".h5");
      auto w = H5SeriesWriter::create(out, options);
      define(w);
      w.define_series("/wide", {2100}, "-", "a row larger than a chunk");
      w.define_series("/raw", {3}, "-", "stored without filters", false, false);
      std::vector<double> wide(2100);
      for (int r = 0; r < 5000; ++r) {
        append_rows(w, r, r + 1, std::sin(0.01 * r));
        const double raw[3] = {std::sin(0.1 * r), 1.0 / (r + 1), 0.5};
        w.append("/raw", raw);
        if (r % 100 == 0) {
          for (std::size_t i = 0; i < wide.size(); ++i) wide[i] = std::cos(0.001 * static_cast<double>(i * r));
          w.append("/wide", wide);
        }
        if (r == 2500) w.flush();
      }
      w.commit();
      chunks[background] = stored_chunks(out);
      EXPECT_EQ(H5Reader(out).doubles("/xy"), H5Reader(path("c0.h5")).doubles("/xy"));
    }
    EXPECT_EQ(chunks[0].size(), 3u + 5u + 100u + 8u) << "chunks of /time, /xy, /wide (2 per row), /raw";
    ASSERT_EQ(chunks[1].size(), chunks[0].size());
    std::size_t stored[2] = {0, 0};
    for (const auto& [key, hdf5] : chunks[0]) {
      const auto& mine = chunks[1].at(key);
      EXPECT_EQ(mine.first, hdf5.first) << key;
      stored[0] += hdf5.second.size(), stored[1] += mine.second.size();
      if (key.starts_with("/raw") || hdf5.first != 0) {  // no filters, or HDF5 skipped one (mask bit)
        EXPECT_TRUE(mine.second == hdf5.second) << key;
        continue;
      }
      const std::vector<char> a = inflated(hdf5.second), b = inflated(mine.second);
      ASSERT_FALSE(a.empty()) << key;
      EXPECT_TRUE(a == b) << key << ", shuffle " << shuffle << ", level " << level;
    }
    EXPECT_LE(static_cast<double>(stored[1]), 1.01 * static_cast<double>(stored[0])) << "level " << level;
    // /raw: 682 rows of 24 bytes to a 16 KiB chunk; the first chunk holds rows 0..681 as they are.
    const auto& first = chunks[1].at("/raw@0,0");
    EXPECT_EQ(first.first, 0u);
    ASSERT_EQ(first.second.size(), 682u * 3u * sizeof(double));
    std::vector<double> values(682u * 3u);
    std::memcpy(values.data(), first.second.data(), first.second.size());
    EXPECT_EQ(values[3 * 681], std::sin(0.1 * 681));
    EXPECT_EQ(values[3 * 681 + 1], 1.0 / 682);
    const hid_t file = H5Fopen(path("c1.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    const hid_t raw = H5Dopen2(file, "/raw", H5P_DEFAULT), xy = H5Dopen2(file, "/xy", H5P_DEFAULT);
    const hid_t raw_plist = H5Dget_create_plist(raw), xy_plist = H5Dget_create_plist(xy);
    EXPECT_EQ(H5Pget_nfilters(raw_plist), 0);
    EXPECT_EQ(H5Pget_nfilters(xy_plist), shuffle ? 2 : 1);
    for (const hid_t h : {raw_plist, xy_plist}) H5Pclose(h);
    for (const hid_t h : {raw, xy}) H5Dclose(h);
    H5Fclose(file);
  }
}
