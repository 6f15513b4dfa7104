// gtest main of the solver tests: MPI, then PETSc (the petsc-bordered backend needs it), as the
// raceway driver does (solver/driver/main.cpp). Serial: the linear algebra runs on one rank.
#include <gtest/gtest.h>
#include <mpi.h>

#include "solver/numerics/newton_backends.hpp"

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  int result = 0;
  {
    raceway::solver::PetscRuntime petsc;
    result = RUN_ALL_TESTS();
  }
  MPI_Finalize();
  return result;
}
