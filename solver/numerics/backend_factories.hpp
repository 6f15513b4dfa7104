// Internal to solver/numerics: what each backend file provides to the backend registry
// (linear_solver_registry.cpp) and to the PETSc options check (petsc_options.cpp).
#pragma once

#include <sundials/sundials_context.h>
#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nvector.h>

#include <string>

#include "solver/numerics/bordered_matrix.hpp"
#include "solver/numerics/linear_solver_registry.hpp"

namespace raceway::numerics::backend {

/// block_elimination_backend.cpp: BorderedMatrix content, BorderedFactorization solver.
NewtonObjects create_block_elimination(SUNContext ctx, N_Vector y, const BorderedLayout& layout);

/// petsc_bordered_backend.cpp: PETSc SeqAIJ content, KSP with PCFIELDSPLIT Schur. Needs a
/// PetscRuntime (std::logic_error without one).
NewtonObjects create_petsc_bordered(SUNContext ctx, N_Vector y, const BorderedLayout& layout);
/// The solver a petsc-bordered linear solver built from the options, in PETSc's words: outer KSP
/// and PC, and each split's KSP, PC and factorisation package.
std::string describe_petsc_bordered(SUNLinearSolver s);

/// sundials_dense_backend.cpp: SUNDIALS' dense matrix and dense LU.
NewtonObjects create_sundials_dense(SUNContext ctx, N_Vector y, const BorderedLayout& layout);
/// Writes J into a SUNDIALS dense matrix.
void load_dense(const BorderedMatrix& j, SUNMatrix a);

}  // namespace raceway::numerics::backend
