// MPI for a whole process, for programs that only need it started (the test and benchmark mains
// that start PETSc, which runs on MPI_COMM_SELF): MPI_Init on construction, MPI_Finalize on
// destruction. Keeps mpi.h inside scheduler/ for them.
#pragma once

namespace raceway::scheduler {

class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  int rank_ = 0, size_ = 1;
};

}  // namespace raceway::scheduler
