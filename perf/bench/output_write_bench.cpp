// The cost and size of the output writer's storage settings: every time series of a real output file
// (docs/output_layout.md) written again through h5::H5SeriesWriter, row by row as a run appends
// them, flushed every `flush_every` rows (as checkpoints do), for chunks of 16 and 64 KiB, gzip
// levels 0..9, with and without the byte shuffle. Prints one line per setting: seconds to append and
// write (wall, and CPU time of the calling thread: the run's, robust against other processes'
// load), file bytes, and the ratio of the series' raw bytes (8 per double) to the file's; then the
// default storage with the chunks filtered in HDF5's pipeline and on the writer's background
// thread. perf/studies/run_output_benchmarks.sh records it in perf/bench/results/.
//
//   output_write_bench OUT.h5 [flush_every=100] [repeats=3]
#include <hdf5.h>

#include <chrono>
#include <ctime>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "io/h5/h5_series.hpp"

namespace {

struct Series {
  std::string path;
  std::vector<std::size_t> row_shape;
  std::vector<double> data;  // rows, row-major
  std::size_t rows = 0;
};

// Every chunked double dataset with an unlimited first dimension (a time series).
herr_t collect(hid_t loc, const char* name, const H5O_info_t* info, void* out) {
  if (info->type != H5O_TYPE_DATASET) return 0;
  const hid_t d = H5Dopen2(loc, name, H5P_DEFAULT);
  const hid_t space = H5Dget_space(d);
  const hid_t type = H5Dget_type(d);
  const int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 0))), max(dims.size());
  H5Sget_simple_extent_dims(space, dims.data(), max.data());
  if (rank > 0 && max[0] == H5S_UNLIMITED && H5Tget_class(type) == H5T_FLOAT) {
    Series s{std::string("/") + name, {dims.begin() + 1, dims.end()}, {}, dims[0]};
    s.data.resize(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
    if (!s.data.empty()) H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, s.data.data());
    static_cast<std::vector<Series>*>(out)->push_back(std::move(s));
  }
  H5Tclose(type), H5Sclose(space), H5Dclose(d);
  return 0;
}

struct Cost {
  double wall = 0, thread_cpu = 0;  // s; thread_cpu: the calling thread's CPU time (not the filter thread's)
};

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

Cost write_all(const std::vector<Series>& all, const std::string& path, raceway::h5::H5WriterOptions options,
               std::size_t flush_every) {
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = thread_cpu_seconds();
  auto w = raceway::h5::H5SeriesWriter::create(path, options);
  std::vector<raceway::h5::H5SeriesWriter::SeriesId> ids;
  for (const Series& s : all) w.define_series(s.path, s.row_shape, "-", "benchmark"), ids.push_back(w.series_id(s.path));
  w.flush();
  const std::size_t rows = all.front().rows;
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t i = 0; i < all.size(); ++i) {
      const std::size_t n = all[i].data.size() / all[i].rows;
      w.append(ids[i], std::span<const double>(all[i].data.data() + r * n, n));
    }
    if ((r + 1) % flush_every == 0) w.flush();
  }
  w.commit();
  return {std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
          thread_cpu_seconds() - cpu_start};
}

Cost best_of(const std::vector<Series>& all, const std::string& path, const raceway::h5::H5WriterOptions& options,
             std::size_t flush_every, int repeats) {
  Cost best{1e300, 1e300};
  for (int i = 0; i < repeats; ++i) {
    const Cost c = write_all(all, path, options, flush_every);
    best.wall = std::min(best.wall, c.wall), best.thread_cpu = std::min(best.thread_cpu, c.thread_cpu);
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s OUT.h5 [flush_every=100] [repeats=3]\n", argv[0]);
    return 2;
  }
  const std::size_t flush_every = argc > 2 ? std::stoul(argv[2]) : 100;
  const int repeats = argc > 3 ? std::stoi(argv[3]) : 3;
  std::vector<Series> all;
  const hid_t f = H5Fopen(argv[1], H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return 1;
  H5Ovisit(f, H5_INDEX_NAME, H5_ITER_INC, collect, &all);
  H5Fclose(f);
  if (all.empty()) return 1;
  std::size_t values = 0;
  for (const Series& s : all) values += s.data.size();
  std::printf("%s: %zu series, %zu rows, %.2f MB of doubles, flush every %zu rows, best of %d\n", argv[1], all.size(),
              all.front().rows, 8e-6 * static_cast<double>(values), flush_every, repeats);
  std::printf("%-8s %-8s %-8s %10s %12s %12s %8s\n", "chunkKiB", "gzip", "shuffle", "seconds", "thread_cpu_s", "bytes",
              "ratio");
  const std::string out = (std::filesystem::temp_directory_path() / "raceway_output_write_bench.h5").string();
  const double raw_bytes = 8.0 * static_cast<double>(values);
  for (const std::size_t chunk : {std::size_t{16} << 10, std::size_t{64} << 10})
    for (const bool shuffle : {false, true})
      for (const int level : {0, 1, 2, 4, 6, 9}) {
        if (level == 0 && shuffle) continue;
        const raceway::h5::H5WriterOptions options{.gzip_level = level, .shuffle = shuffle, .chunk_bytes = chunk};
        const Cost best = best_of(all, out, options, flush_every, repeats);
        const auto bytes = static_cast<double>(std::filesystem::file_size(out));
        std::printf("%-8zu %-8d %-8s %10.4f %12.4f %12.0f %8.2f\n", chunk >> 10, level, shuffle ? "yes" : "no", best.wall,
                    best.thread_cpu, bytes, raw_bytes / bytes);
      }
  // The default storage, chunks filtered by HDF5's pipeline in the flushes (the writer before) and on
  // the writer's background thread: the caller's wall and CPU time.
  for (const bool background : {false, true}) {
    const raceway::h5::H5WriterOptions options{.background_compression = background};
    const Cost best = best_of(all, out, options, flush_every, repeats);
    std::printf("default storage, filtering %-26s %10.4f s wall %10.4f s caller's CPU\n",
                background ? "on the background thread:" : "in HDF5's pipeline:", best.wall, best.thread_cpu);
  }
  std::filesystem::remove(out);
  return 0;
}
