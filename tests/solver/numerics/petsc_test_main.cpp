// gtest main of the solver tests: MPI, then PETSc (the petsc-bordered backend needs it), as the
// raceway driver does (solver/driver/main.cpp). Serial: the linear algebra runs on one rank.
#include <gtest/gtest.h>
#include "scheduler/mpi_session.hpp"
#include "solver/numerics/newton_backends.hpp"

int main(int argc, char** argv) {
  const raceway::scheduler::MpiSession mpi(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  const raceway::numerics::PetscRuntime petsc;
  return RUN_ALL_TESTS();
}
