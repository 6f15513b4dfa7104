// MPI ping-pong between ranks 0 and 1: one-way latency and bandwidth for message sizes from 8 B
// to 4 MB (median of repetitions), the network parameters of the replay model (perf/calibration/replay_model.py).
//   mpirun -np 2 build/perf/bench/pingpong
#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <vector>

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size != 2) {
    if (rank == 0) std::fprintf(stderr, "pingpong needs exactly 2 ranks\n");
    MPI_Finalize();
    return 1;
  }
  if (rank == 0) std::printf("# bytes  one_way_us(median)  bandwidth_GB_s\n");
  for (std::size_t bytes = 8; bytes <= (4u << 20); bytes *= 4) {
    std::vector<char> buf(bytes);
    const int reps = bytes < 65536 ? 2000 : 100;
    std::vector<double> one_way;
    for (int r = 0; r < reps + 10; ++r) {
      MPI_Barrier(MPI_COMM_WORLD);
      const double t0 = MPI_Wtime();
      if (rank == 0) {
        MPI_Send(buf.data(), static_cast<int>(bytes), MPI_CHAR, 1, 0, MPI_COMM_WORLD);
        MPI_Recv(buf.data(), static_cast<int>(bytes), MPI_CHAR, 1, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      } else {
        MPI_Recv(buf.data(), static_cast<int>(bytes), MPI_CHAR, 0, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        MPI_Send(buf.data(), static_cast<int>(bytes), MPI_CHAR, 0, 0, MPI_COMM_WORLD);
      }
      if (r >= 10) one_way.push_back((MPI_Wtime() - t0) / 2);
    }
    std::nth_element(one_way.begin(), one_way.begin() + one_way.size() / 2, one_way.end());
    const double t = one_way[one_way.size() / 2];
    if (rank == 0) std::printf("%9zu  %10.3f  %8.3f\n", bytes, 1e6 * t, static_cast<double>(bytes) / t / 1e9);
  }
  MPI_Finalize();
  return 0;
}
