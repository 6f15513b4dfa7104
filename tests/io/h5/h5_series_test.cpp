// Tests of raceway::h5::H5SeriesWriter (read back with the HDF5 C API, and h5py when present).
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "io/h5/h5_series.hpp"
#include "tests/support/temp_dir.hpp"

namespace fs = std::filesystem;
using raceway::h5::H5SeriesWriter;

namespace {

using raceway::test::read_text;
using raceway::test::TempDir;

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

// Closes an HDF5 id at scope exit.
struct H5Id {
  hid_t id;
  herr_t (*closer)(hid_t);
  ~H5Id() {
    if (id >= 0) closer(id);
  }
  operator hid_t() const { return id; }
};

struct Array {
  std::vector<hsize_t> dims, max_dims;
  std::vector<double> values;
};

Array read_doubles(hid_t file, const std::string& path) {
  Array a;
  H5Id d{H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose};
  EXPECT_GE(d.id, 0) << path;
  if (d.id < 0) return a;
  H5Id s{H5Dget_space(d), H5Sclose};
  const int rank = H5Sget_simple_extent_ndims(s);
  a.dims.resize(static_cast<std::size_t>(rank));
  a.max_dims.resize(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(s, a.dims.data(), a.max_dims.data());
  a.values.resize(static_cast<std::size_t>(H5Sget_simple_extent_npoints(s)));
  if (!a.values.empty()) {
    EXPECT_GE(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, a.values.data()), 0);
  }
  return a;
}

// Reads a variable-length string attribute (scalar or 1-D) and checks its type.
std::vector<std::string> read_string_attr(hid_t file, const std::string& obj_path, const std::string& name) {
  std::vector<std::string> out;
  H5Id obj{H5Oopen(file, obj_path.c_str(), H5P_DEFAULT), H5Oclose};
  EXPECT_GE(obj.id, 0) << obj_path;
  H5Id attr{H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose};
  EXPECT_GE(attr.id, 0) << obj_path << " " << name;
  if (attr.id < 0) return out;
  H5Id ftype{H5Aget_type(attr), H5Tclose};
  EXPECT_EQ(H5Tget_class(ftype), H5T_STRING);
  EXPECT_GT(H5Tis_variable_str(ftype), 0);
  EXPECT_EQ(H5Tget_cset(ftype), H5T_CSET_UTF8);
  H5Id space{H5Aget_space(attr), H5Sclose};
  const auto n = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space));
  std::vector<char*> ptrs(n, nullptr);
  H5Id mtype{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(mtype, H5T_VARIABLE);
  H5Tset_cset(mtype, H5T_CSET_UTF8);
  if (n > 0) {
    EXPECT_GE(H5Aread(attr, mtype, ptrs.data()), 0);
    for (char* p : ptrs) out.emplace_back(p ? p : "");
    H5Dvlen_reclaim(mtype, space, H5P_DEFAULT, ptrs.data());
  }
  return out;
}

std::vector<double> read_double_attr(hid_t file, const std::string& obj_path, const std::string& name) {
  H5Id obj{H5Oopen(file, obj_path.c_str(), H5P_DEFAULT), H5Oclose};
  H5Id attr{H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose};
  EXPECT_GE(attr.id, 0) << obj_path << " " << name;
  if (attr.id < 0) return {};
  H5Id ftype{H5Aget_type(attr), H5Tclose};
  EXPECT_EQ(H5Tget_class(ftype), H5T_FLOAT);
  H5Id space{H5Aget_space(attr), H5Sclose};
  std::vector<double> v(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
  if (!v.empty()) {
    EXPECT_GE(H5Aread(attr, H5T_NATIVE_DOUBLE, v.data()), 0);
  }
  return v;
}

long long read_int_attr(hid_t file, const std::string& obj_path, const std::string& name) {
  H5Id obj{H5Oopen(file, obj_path.c_str(), H5P_DEFAULT), H5Oclose};
  H5Id attr{H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose};
  EXPECT_GE(attr.id, 0) << obj_path << " " << name;
  H5Id ftype{H5Aget_type(attr), H5Tclose};
  EXPECT_EQ(H5Tget_class(ftype), H5T_INTEGER);
  EXPECT_EQ(H5Tget_size(ftype), 8u);
  long long v = 0;
  EXPECT_GE(H5Aread(attr, H5T_NATIVE_LLONG, &v), 0);
  return v;
}

bool bit_equal(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

// A value that exercises the whole double range: tiny, huge, negative zero, subnormal, irrational.
double pattern(std::size_t series, std::size_t row, std::size_t k) {
  const double x = std::sin(0.37 * static_cast<double>(row) + 1.3 * static_cast<double>(k) + static_cast<double>(series));
  switch ((row + k) % 5) {
    case 0: return x * 1e-300;
    case 1: return x * 1e300;
    case 2: return row == 0 ? -0.0 : std::nextafter(x, 2.0);
    case 3: return std::numeric_limits<double>::denorm_min() * static_cast<double>(row + 1);
    default: return x / 3.0;
  }
}

// True if an HDF5 file can be opened; reads nothing else.
bool hdf5_readable(const std::string& path) {
  H5E_auto2_t func = nullptr;
  void* data = nullptr;
  H5Eget_auto2(H5E_DEFAULT, &func, &data);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  H5Eset_auto2(H5E_DEFAULT, func, data);
  if (f < 0) return false;
  H5Fclose(f);
  return true;
}

}  // namespace

// ---------------------------------------------------------------- H5SeriesWriter

using H5Series = TempDir;

namespace {

// Chunked, about 16 KiB per chunk, shuffled and gzip-compressed.
void expect_chunked_about_16k(hid_t file, const std::string& path, std::size_t rank) {
  H5Id d{H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose};
  H5Id dcpl{H5Dget_create_plist(d), H5Pclose};
  EXPECT_EQ(H5Pget_layout(dcpl), H5D_CHUNKED);
  ASSERT_EQ(H5Pget_nfilters(dcpl), 2);
  unsigned flags = 0, values[4] = {};
  std::size_t n = 4;
  EXPECT_EQ(H5Pget_filter2(dcpl, 0, &flags, &n, values, 0, nullptr, nullptr), H5Z_FILTER_SHUFFLE);
  n = 4;
  EXPECT_EQ(H5Pget_filter2(dcpl, 1, &flags, &n, values, 0, nullptr, nullptr), H5Z_FILTER_DEFLATE);
  std::vector<hsize_t> chunk(rank);
  ASSERT_EQ(H5Pget_chunk(dcpl, static_cast<int>(chunk.size()), chunk.data()), static_cast<int>(chunk.size()));
  hsize_t bytes = sizeof(double);
  for (const hsize_t c : chunk) bytes *= c;
  EXPECT_LE(bytes, 16u * 1024u);
  EXPECT_GE(bytes, 8u * 1024u);
}

// A 1-D dataset of variable-length strings, read back (and its type checked).
std::vector<std::string> read_string_dataset(hid_t file, const std::string& path) {
  std::vector<std::string> out;
  H5Id names{H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose};
  EXPECT_GE(names.id, 0) << path;
  if (names.id < 0) return out;
  H5Id ntype{H5Dget_type(names), H5Tclose};
  EXPECT_GT(H5Tis_variable_str(ntype), 0);
  H5Id nspace{H5Dget_space(names), H5Sclose};
  std::vector<char*> ptrs(static_cast<std::size_t>(H5Sget_simple_extent_npoints(nspace)), nullptr);
  H5Id mtype{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(mtype, H5T_VARIABLE);
  if (ptrs.empty()) return out;
  EXPECT_GE(H5Dread(names, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data()), 0);
  for (char* p : ptrs) out.emplace_back(p ? p : "");
  H5Dvlen_reclaim(mtype, nspace, H5P_DEFAULT, ptrs.data());
  return out;
}

}  // namespace

TEST_F(H5Series, RoundTripSeries) {
  const std::string file = path("run.h5");
  struct Def {
    std::string path;
    std::vector<std::size_t> shape;
    std::size_t row_size;
  };
  // Scalar, vector, matrix rows, and a row larger than one chunk (chunked along the row too).
  const std::vector<Def> defs{{"/time", {}, 1},
                              {"/bodies/cage/position", {3}, 3},
                              {"rollers/contact/force", {20, 2}, 40},
                              {"/big/row", {10000}, 10000}};
  const std::vector<std::size_t> n_rows{9000, 5000, 700, 3};  // crosses chunk/block boundaries

  std::vector<std::vector<double>> expected(defs.size());
  {
    auto w = H5SeriesWriter::create(file);
    EXPECT_EQ(w.partial_path(), file + ".partial");
    for (const auto& d : defs) w.define_series(d.path, d.shape, "m", "description of " + d.path);
    for (std::size_t s = 0; s < defs.size(); ++s) {
      std::vector<double> row(defs[s].row_size);
      for (std::size_t r = 0; r < n_rows[s]; ++r) {
        for (std::size_t k = 0; k < row.size(); ++k) row[k] = pattern(s, r, k);
        w.append(defs[s].path, row);
        expected[s].insert(expected[s].end(), row.begin(), row.end());
        if (s == 1 && r == 1234) w.flush();  // a flush in the middle of a block
      }
      EXPECT_EQ(w.rows(defs[s].path), n_rows[s]);
    }
    w.commit();
    EXPECT_FALSE(w.is_open());
  }
  ASSERT_TRUE(fs::exists(file));
  EXPECT_FALSE(fs::exists(file + ".partial"));

  H5Id f{H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  ASSERT_GE(f.id, 0);
  for (std::size_t s = 0; s < defs.size(); ++s) {
    SCOPED_TRACE(defs[s].path);
    const std::string p = defs[s].path[0] == '/' ? defs[s].path : "/" + defs[s].path;
    const Array a = read_doubles(f, p);
    std::vector<hsize_t> dims{n_rows[s]};
    dims.insert(dims.end(), defs[s].shape.begin(), defs[s].shape.end());
    EXPECT_EQ(a.dims, dims);
    EXPECT_EQ(a.max_dims[0], H5S_UNLIMITED);
    EXPECT_TRUE(bit_equal(a.values, expected[s]));
    EXPECT_EQ(read_string_attr(f, p, "units"), std::vector<std::string>{"m"});
    EXPECT_EQ(read_string_attr(f, p, "description"), std::vector<std::string>{"description of " + defs[s].path});
    expect_chunked_about_16k(f, p, dims.size());
  }
}

TEST_F(H5Series, RoundTripAttributes) {
  const std::string file = path("attributes.h5");
  {
    auto w = H5SeriesWriter::create(file);
    w.define_series("/bodies/cage/position", {3}, "m", "cage position");
    w.append("/bodies/cage/position", std::vector<double>{1.0, 2.0, 3.0});
    // Root attributes of every kind, attributes on a new group and on a series.
    w.set_attribute("/", "scene_toml", "[bearing]\nname = \"NU206\" # \u00e9\n");
    w.set_attribute("/", "pi", 3.141592653589793);
    w.set_attribute("/", "steps", 123456789012345LL);
    w.set_attribute("/", "ranks", 2);                  // int -> int64
    w.set_attribute("/", "outputs", std::size_t{42});  // size_t -> int64
    w.set_attribute("/", "gravity", std::vector<double>{0.0, -9.80665, 0.1});
    w.set_attribute("/", "state_names", std::vector<std::string>{"x", "y", "theta", ""});
    w.set_attribute("/", "no_names", std::vector<std::string>{});
    w.set_attribute("/", "no_values", std::vector<double>{});
    w.set_attribute("/build/info", "compiler", "g++ 12");  // groups created
    w.set_attribute("/bodies/cage/position", "frame", "inertial");
    w.set_attribute("/", "replaced", "first");
    w.set_attribute("/", "replaced", 2.5);  // replaces, with another type
    w.commit();
  }
  H5Id f{H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  ASSERT_GE(f.id, 0);
  EXPECT_EQ(read_string_attr(f, "/", "scene_toml"), std::vector<std::string>{"[bearing]\nname = \"NU206\" # \u00e9\n"});
  EXPECT_EQ(read_double_attr(f, "/", "pi"), std::vector<double>{3.141592653589793});
  EXPECT_EQ(read_int_attr(f, "/", "steps"), 123456789012345LL);
  EXPECT_EQ(read_int_attr(f, "/", "ranks"), 2);
  EXPECT_EQ(read_int_attr(f, "/", "outputs"), 42);
  EXPECT_EQ(read_double_attr(f, "/", "gravity"), (std::vector<double>{0.0, -9.80665, 0.1}));
  EXPECT_EQ(read_string_attr(f, "/", "state_names"), (std::vector<std::string>{"x", "y", "theta", ""}));
  EXPECT_TRUE(read_string_attr(f, "/", "no_names").empty());
  EXPECT_TRUE(read_double_attr(f, "/", "no_values").empty());
  EXPECT_EQ(read_string_attr(f, "/build/info", "compiler"), std::vector<std::string>{"g++ 12"});
  EXPECT_EQ(read_string_attr(f, "/bodies/cage/position", "frame"), std::vector<std::string>{"inertial"});
  EXPECT_EQ(read_double_attr(f, "/", "replaced"), std::vector<double>{2.5});
}

// The root's attributes have no 64 KiB limit: 10000 state names (1000 balls of 9 states and the
// border, 16 bytes each in an attribute) are written and read back, as is a 200 kB string.
TEST_F(H5Series, LargeRootAttributes) {
  const std::string file = path("large_attributes.h5");
  std::vector<std::string> names;
  for (int i = 0; i < 10000; ++i) names.push_back("ball[" + std::to_string(i / 9) + "].state" + std::to_string(i % 9));
  const std::string model(200000, 'm');
  {
    auto w = H5SeriesWriter::create(file);
    w.define_series("/time", {}, "s", "times");
    w.set_attribute("/", "state_names", names);
    w.set_attribute("/", "model", model);
    w.set_attribute("/", "after", 1.5);
    w.commit();
  }
  H5Id f{H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  ASSERT_GE(f.id, 0);
  EXPECT_EQ(read_string_attr(f, "/", "state_names"), names);
  EXPECT_EQ(read_string_attr(f, "/", "model"), std::vector<std::string>{model});
  EXPECT_EQ(read_double_attr(f, "/", "after"), std::vector<double>{1.5});
}

TEST_F(H5Series, RoundTripFixedArrays) {
  const std::string file = path("arrays.h5");
  {
    auto w = H5SeriesWriter::create(file);
    const std::vector<double> table{1.5, -2.25, 1e-310, 4.0, 5.0, 6.0};
    w.write_array("/geometry/table", {2, 3}, table, "Pa", "a 2x3 table");
    w.write_array("/geometry/scalar", {}, std::vector<double>{0.1}, "kg", "a scalar");
    w.write_array("/geometry/segment_names", std::vector<std::string>{"inner race", "outer race", "cage\u00e9"},
                  "segment names");
    w.write_array("/geometry/empty_names", std::vector<std::string>{}, "no names");
    w.commit();
  }
  H5Id f{H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  ASSERT_GE(f.id, 0);
  const Array table = read_doubles(f, "/geometry/table");
  EXPECT_EQ(table.dims, (std::vector<hsize_t>{2, 3}));
  EXPECT_TRUE(bit_equal(table.values, {1.5, -2.25, 1e-310, 4.0, 5.0, 6.0}));
  EXPECT_EQ(read_string_attr(f, "/geometry/table", "units"), std::vector<std::string>{"Pa"});
  const Array scalar = read_doubles(f, "/geometry/scalar");
  EXPECT_TRUE(scalar.dims.empty());
  EXPECT_TRUE(bit_equal(scalar.values, {0.1}));

  // The string table: 1-D variable-length UTF-8 strings.
  EXPECT_EQ(read_string_dataset(f, "/geometry/segment_names"),
            (std::vector<std::string>{"inner race", "outer race", "cage\u00e9"}));
  EXPECT_EQ(read_string_attr(f, "/geometry/segment_names", "description"), std::vector<std::string>{"segment names"});
  EXPECT_EQ(read_string_attr(f, "/geometry/segment_names", "units"), std::vector<std::string>{""});
  H5Id empty_names{H5Dopen2(f, "/geometry/empty_names", H5P_DEFAULT), H5Dclose};
  EXPECT_GE(empty_names.id, 0);
  EXPECT_TRUE(read_string_dataset(f, "/geometry/empty_names").empty());
}

TEST_F(H5Series, FlushMakesWholeChunksVisibleToAReader) {
  const std::string file = path("flush.h5");
  auto w = H5SeriesWriter::create(file);
  w.define_series("/x", {2}, "s", "x");
  for (int r = 0; r < 1030; ++r) w.append("/x", std::vector<double>{1.0 * r, 2.0 * r});
  w.flush();
  // One chunk = 1024 rows of 2 doubles: flush() writes it; the 6 rows of the next wait for the end.
  {
    H5Id f{H5Fopen(w.partial_path().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
    ASSERT_GE(f.id, 0);
    const Array a = read_doubles(f, "/x");
    EXPECT_EQ(a.dims, (std::vector<hsize_t>{1024, 2}));
    ASSERT_EQ(a.values.size(), 2048u);
    EXPECT_EQ(a.values[2047], 2046.0);
  }
  w.commit();
  H5Id f{H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  const Array a = read_doubles(f, "/x");
  EXPECT_EQ(a.dims, (std::vector<hsize_t>{1030, 2}));
}

TEST_F(H5Series, ExistingFileUntouchedUntilCommit) {
  const std::string file = path("out.h5");
  write_text(file, "old complete output");
  {
    auto w = H5SeriesWriter::create(file);
    w.define_series("/time", {}, "s", "output times");
    for (int i = 0; i < 100; ++i) w.append("/time", std::vector<double>{0.01 * i});
    w.flush();
    EXPECT_EQ(read_text(file), "old complete output");
    EXPECT_TRUE(fs::exists(file + ".partial"));
    w.commit();
  }
  EXPECT_FALSE(fs::exists(file + ".partial"));
  H5Id f{H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  ASSERT_GE(f.id, 0);
  EXPECT_EQ(read_doubles(f, "/time").dims, std::vector<hsize_t>{100});
}

TEST_F(H5Series, NoCommitLeavesReadablePartialAndOldOutput) {
  const std::string file = path("out.h5");
  write_text(file, "old complete output");
  try {
    auto w = H5SeriesWriter::create(file);
    w.define_series("/bodies/inner/position", {3}, "m", "position");
    for (int i = 0; i < 7; ++i) w.append("/bodies/inner/position", std::vector<double>{1.0 * i, 2.0, 3.0});
    throw std::runtime_error("solver diverged");  // unwinds without commit
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(read_text(file), "old complete output");
  ASSERT_TRUE(fs::exists(file + ".partial"));
  H5Id f{H5Fopen((file + ".partial").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  ASSERT_GE(f.id, 0);
  const Array a = read_doubles(f, "/bodies/inner/position");  // buffered rows were written on close
  EXPECT_EQ(a.dims, (std::vector<hsize_t>{7, 3}));
  EXPECT_EQ(a.values[18], 6.0);
}

TEST_F(H5Series, StalePartialIsTruncated) {
  const std::string file = path("out.h5");
  write_text(file + ".partial", "garbage from a crashed run");
  auto w = H5SeriesWriter::create(file);
  w.define_series("/a", {}, "-", "a");
  w.append("/a", std::vector<double>{1.0});
  w.commit();
  EXPECT_TRUE(hdf5_readable(file));
  EXPECT_FALSE(fs::exists(file + ".partial"));
}

TEST_F(H5Series, MisuseThrowsInvalidArgument) {
  auto w = H5SeriesWriter::create(path("bad.h5"));
  w.define_series("/bodies/cage/position", {3}, "m", "p");
  EXPECT_THROW(w.append("/bodies/cage/position", std::vector<double>{1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(w.append("/bodies/cage/position", std::vector<double>{1.0, 2.0, 3.0, 4.0}), std::invalid_argument);
  EXPECT_THROW(w.append("/nope", std::vector<double>{1.0}), std::invalid_argument);
  EXPECT_THROW(w.define_series("bodies/cage/position", {3}, "m", "again"), std::invalid_argument);
  EXPECT_THROW(w.define_series("/zero", {3, 0}, "m", "zero"), std::invalid_argument);
  EXPECT_THROW(w.write_array("/t", {2, 2}, std::vector<double>{1.0, 2.0, 3.0}, "m", "t"), std::invalid_argument);
  EXPECT_THROW(w.set_attribute("/", "huge", std::numeric_limits<unsigned long long>::max()), std::invalid_argument);
  // A relative path names the same series; the good rows are all kept.
  w.append("bodies/cage/position", std::vector<double>{1.0, 2.0, 3.0});
  EXPECT_EQ(w.rows("/bodies/cage/position"), 1u);
}

TEST_F(H5Series, Hdf5FailuresThrowRuntimeErrorNamingFileAndObjectSilently) {
  H5E_auto2_t func_before = nullptr;
  void* data_before = nullptr;
  H5Eget_auto2(H5E_DEFAULT, &func_before, &data_before);

  const std::string missing_dir = path("no/such/dir/run.h5");
  ::testing::internal::CaptureStderr();
  try {
    (void)H5SeriesWriter::create(missing_dir);
    ADD_FAILURE() << "create in a missing directory did not throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing_dir + ".partial"), std::string::npos) << e.what();
  }
  auto w = H5SeriesWriter::create(path("fail.h5"));
  w.define_series("/time", {}, "s", "t");
  try {
    w.write_array("/time", {1}, std::vector<double>{1.0}, "s", "clash with an existing dataset");
    ADD_FAILURE() << "write_array over an existing dataset did not throw";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path("fail.h5.partial")), std::string::npos) << what;
    EXPECT_NE(what.find("/time"), std::string::npos) << what;
  }
  // A group path below a dataset cannot be made; the HDF5 reason is in the message.
  try {
    w.set_attribute("/time/sub", "a", 1.0);
    ADD_FAILURE() << "set_attribute below a dataset did not throw";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("/time/sub"), std::string::npos) << what;
    EXPECT_NE(what.find("H5"), std::string::npos) << what;
    EXPECT_EQ(what.find("no HDF5 error message"), std::string::npos) << what;
  }
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(err.find("HDF5-DIAG"), std::string::npos) << err;

  H5E_auto2_t func_after = nullptr;
  void* data_after = nullptr;
  H5Eget_auto2(H5E_DEFAULT, &func_after, &data_after);
  EXPECT_EQ(func_after, func_before);  // the writer restored the caller's setting
  EXPECT_EQ(data_after, data_before);
}

TEST_F(H5Series, MoveTransfersTheOpenFile) {
  const std::string a_path = path("a.h5");
  const std::string b_path = path("b.h5");
  auto a = H5SeriesWriter::create(a_path);
  a.define_series("/x", {}, "-", "x");
  a.append("/x", std::vector<double>{1.0});
  H5SeriesWriter moved(std::move(a));
  EXPECT_FALSE(a.is_open());  // NOLINT(bugprone-use-after-move): documented moved-from state
  EXPECT_THROW(a.append("/x", std::vector<double>{2.0}), std::logic_error);
  moved.append("/x", std::vector<double>{2.0});

  auto b = H5SeriesWriter::create(b_path);
  b = std::move(moved);  // b's own file is closed and left as b.h5.partial
  EXPECT_TRUE(fs::exists(b_path + ".partial"));
  EXPECT_TRUE(hdf5_readable(b_path + ".partial"));
  b.commit();
  EXPECT_THROW(b.flush(), std::logic_error);
  EXPECT_THROW(b.commit(), std::logic_error);
  H5Id f{H5Fopen(a_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  ASSERT_GE(f.id, 0);
  EXPECT_EQ(read_doubles(f, "/x").values, (std::vector<double>{1.0, 2.0}));
}

TEST_F(H5Series, H5pyReadsUnitsAsStr) {
  if (!fs::exists("/usr/bin/python3") ||
      std::system("/usr/bin/python3 -c 'import h5py' >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "/usr/bin/python3 with h5py not available";
  }
  const std::string file = path("py.h5");
  {
    auto w = H5SeriesWriter::create(file);
    w.define_series("/bodies/cage/position", {3}, "m", "cage centre");
    w.append("/bodies/cage/position", std::vector<double>{1.0, 2.0, 3.0});
    w.set_attribute("/", "state_names", std::vector<std::string>{"x", "y"});
    w.commit();
  }
  const std::string cmd =
      "/usr/bin/python3 -c \"import h5py, sys\n"
      "f = h5py.File(sys.argv[1], 'r')\n"
      "d = f['bodies/cage/position']\n"
      "u = d.attrs['units']\n"
      "n = list(f.attrs['state_names'])\n"
      "print(type(u).__name__, u, d.shape, d.maxshape, type(n[0]).__name__, ','.join(n))\" '" +
      file + "' 2>&1";
  std::FILE* p = ::popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string out;
  char buf[256];
  while (std::fgets(buf, sizeof buf, p) != nullptr) out += buf;
  ASSERT_EQ(::pclose(p), 0) << out;
  EXPECT_EQ(out, "str m (1, 3) (None, 3) str x,y\n");
}
