#include "solver/numerics/linear_solver_registry.hpp"

#include <array>
#include <stdexcept>

#include "solver/numerics/backend_factories.hpp"

namespace raceway::numerics {

namespace {

using Kind = scene::LinearSolverKind;

const std::array<LinearSolverBackend, 4> kBackends{{
    {Kind::automatic, "auto", nullptr,
     "the block elimination is 2.4-2.9x cheaper per Newton setup + solve than petsc-bordered at every size "
     "measured, 8 to 512 rolling elements, serial",
     nullptr},
    {Kind::petsc_bordered, "petsc-bordered", nullptr,
     "PETSc SeqAIJ with exact preallocation; KSPPREONLY + PCFIELDSPLIT Schur, rolling-element blocks and the "
     "explicit Schur complement factored by LU",
     backend::create_petsc_bordered},
    {Kind::block_elimination, "block-elimination", "bordered",
     "hand-written Schur complement elimination on Eigen blocks (solver/numerics/bordered_matrix.hpp)",
     backend::create_block_elimination},
    {Kind::sundials_dense, "sundials-dense", "dense", "SUNDIALS dense LU, the baseline", backend::create_sundials_dense},
}};

}  // namespace

std::span<const LinearSolverBackend> linear_solver_backends() { return kBackends; }

const LinearSolverBackend& linear_solver_backend(scene::LinearSolverKind kind) {
  for (const LinearSolverBackend& b : kBackends)
    if (b.kind == kind) return b;
  throw std::logic_error("linear_solver_backend: a scene::LinearSolverKind without an entry");
}

// `auto` is the hand-written block elimination. Measured per Newton setup + solve (assembly, M =
// I - gamma J, factorisation, one solve; perf/bench/results/bordered_scaling.txt), both backends are O(N)
// and exact, and the block elimination is 2.4 to 2.9 times cheaper at every N from 8 to 512 (real
// bearings: 6309, 8 balls: 29 vs 85 us; QJ215, 15 balls: 36 vs 90 us; seed 002, 13 rollers: 11 vs
// 31 us). PETSc's fixed and per-block costs: four sub-matrix extractions per setup, a sparse LU of
// split 0 through the generic AIJ kernels (i-nodes of 5 or 9 rows) instead of dense 9x9 LAPACK-style
// blocks, the Schur complement through KSPMatSolve on dense column blocks, and object bookkeeping.
// PETSc earns its place where the hand-written path cannot go: run-time solver choices (MUMPS,
// SuperLU_DIST, hypre, ILU) and, later, the distributed (MPIAIJ) Newton systems of multi-rank runs.
scene::LinearSolverKind resolve_linear_solver(scene::LinearSolverKind kind, const BorderedLayout&) {
  return kind == scene::LinearSolverKind::automatic ? scene::LinearSolverKind::block_elimination : kind;
}

const char* linear_solver_name(scene::LinearSolverKind kind) { return linear_solver_backend(kind).name; }

}  // namespace raceway::numerics
