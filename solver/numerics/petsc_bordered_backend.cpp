// The petsc-bordered backend: J and M are PETSc SeqAIJ matrices preallocated exactly from the
// bordered structure; CVODE's jok path copies the saved J into M (MatCopy SAME_NONZERO_PATTERN) and
// forms M = I - gamma J (MatScale + MatShift); the solve is KSPPREONLY + PCFIELDSPLIT Schur (split 0 =
// rolling-element blocks, exact LU; split 1 = border; Schur complement formed explicitly and
// factored by LU; full factorisation, so the solve is exact). Every choice is a PETSc option, read
// from PETSc's options database (filled and checked by solver/numerics/petsc_options.cpp).
// PETSc's errors are reported through the PetscRuntime the backend was created with.
#include <fmt/format.h>
#include <petscksp.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "solver/numerics/backend_factories.hpp"
#include "solver/numerics/petsc_runtime.hpp"
#include "solver/numerics/sundials_custom.hpp"

namespace raceway::numerics::backend {

namespace {

/// A SeqAIJ matrix with the bordered pattern, entries stored row by row with columns ascending:
/// border rows hold all n columns; a block row holds the border columns then its block's.
class PetscBordered final : public MatrixContent {
 public:
  PetscBordered(const PetscRuntime& petsc, const BorderedLayout& l) : runtime(petsc), layout(l) {
    const PetscInt n = l.size(), nb = l.border, m = l.block_size;
    std::vector<PetscInt> nnz(static_cast<std::size_t>(n));
    for (PetscInt r = 0; r < n; ++r) nnz[static_cast<std::size_t>(r)] = r < nb ? n : nb + m;
    runtime.check(MatCreateSeqAIJ(PETSC_COMM_SELF, n, n, 0, nnz.data(), &a), "MatCreateSeqAIJ");
    // The whole pattern as explicit zeros, so that the values array has a fixed layout and
    // MatCopy(SAME_NONZERO_PATTERN) / MatShift never allocate.
    std::vector<PetscInt> cols;
    std::vector<PetscScalar> zeros(static_cast<std::size_t>(n), 0.0);
    for (PetscInt r = 0; r < n; ++r) {
      cols.clear();
      if (r < nb) {
        for (PetscInt c = 0; c < n; ++c) cols.push_back(c);
      } else {
        const PetscInt first = nb + (r - nb) / m * m;
        for (PetscInt c = 0; c < nb; ++c) cols.push_back(c);
        for (PetscInt c = first; c < first + m; ++c) cols.push_back(c);
      }
      runtime.check(MatSetValues(a, 1, &r, static_cast<PetscInt>(cols.size()), cols.data(), zeros.data(), INSERT_VALUES),
                  "MatSetValues");
    }
    runtime.check(MatAssemblyBegin(a, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    runtime.check(MatAssemblyEnd(a, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    runtime.check(MatSetOption(a, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE), "MatSetOption");
    MatInfo info;
    runtime.check(MatGetInfo(a, MAT_LOCAL, &info), "MatGetInfo");
    const double expected = static_cast<double>(nb) * n + static_cast<double>(n - nb) * static_cast<double>(nb + m);
    if (info.nz_used != expected || info.nz_allocated != expected)
      throw std::logic_error(fmt::format("PETSc bordered matrix: {} entries used, {} allocated, {} expected",
                                         info.nz_used, info.nz_allocated, expected));
  }
  PetscBordered(const PetscBordered& o) : MatrixContent(o), runtime(o.runtime), layout(o.layout) {
    runtime.check(MatDuplicate(o.a, MAT_COPY_VALUES, &a), "MatDuplicate");
  }
  ~PetscBordered() override { MatDestroy(&a); }
  std::unique_ptr<MatrixContent> clone() const override { return std::make_unique<PetscBordered>(*this); }
  void zero() override { runtime.check(MatZeroEntries(a), "MatZeroEntries"); }
  void copy_to(MatrixContent& to) const override {
    runtime.check(MatCopy(a, static_cast<PetscBordered&>(to).a, SAME_NONZERO_PATTERN), "MatCopy");
  }
  void scale_add_identity(double c) override {
    runtime.check(MatScale(a, c), "MatScale");
    runtime.check(MatShift(a, 1.0), "MatShift");
  }
  void multiply(const double* x, double* y) const override {
    const PetscInt n = layout.size();
    Vec vx, vy;
    runtime.check(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, n, x, &vx), "VecCreateSeqWithArray");
    runtime.check(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, n, y, &vy), "VecCreateSeqWithArray");
    runtime.check(MatMult(a, vx, vy), "MatMult");
    VecDestroy(&vx);
    VecDestroy(&vy);
  }
  /// Assembly: the bordered blocks written straight into the CSR values, in the layout of the
  /// constructor (O(nnz), no searching of column indices).
  void load(const BorderedMatrix& j) override {
    const int nb = layout.border, nblocks = layout.blocks, m = layout.block_size;
    PetscScalar* v = nullptr;
    runtime.check(MatSeqAIJGetArrayWrite(a, &v), "MatSeqAIJGetArrayWrite");
    for (int r = 0; r < nb; ++r) {
      for (int c = 0; c < nb; ++c) *v++ = j.border(r, c);
      for (int k = 0; k < nblocks; ++k)
        for (int c = 0; c < m; ++c) *v++ = j.border_to_block[static_cast<std::size_t>(k)](r, c);
    }
    for (int k = 0; k < nblocks; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      for (int r = 0; r < m; ++r) {
        for (int c = 0; c < nb; ++c) *v++ = j.block_to_border[kk](r, c);
        for (int c = 0; c < m; ++c) *v++ = j.block[kk](r, c);
      }
    }
    runtime.check(MatSeqAIJRestoreArrayWrite(a, &v), "MatSeqAIJRestoreArrayWrite");
  }
  const PetscRuntime& runtime;
  BorderedLayout layout;
  Mat a = nullptr;
};

/// Sets up the KSP of the petsc-bordered solver on `a` from the options database.
void configure_ksp(const PetscRuntime& runtime, KSP ksp, const BorderedLayout& l, IS* blocks, IS* border, Mat schur) {
  PC pc;
  runtime.check(KSPGetPC(ksp, &pc), "KSPGetPC");
  runtime.check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
  if (l.border == 0) {
    // No border: the matrix is split 0 alone, so it is solved as split 0 is (options fieldsplit_0_*).
    runtime.check(KSPSetOptionsPrefix(ksp, "fieldsplit_0_"), "KSPSetOptionsPrefix");
    runtime.check(PCSetType(pc, PCLU), "PCSetType");
  } else {
    runtime.check(PCSetType(pc, PCFIELDSPLIT), "PCSetType");
    runtime.check(ISCreateStride(PETSC_COMM_SELF, l.blocks * l.block_size, l.border, 1, blocks), "ISCreateStride");
    runtime.check(ISCreateStride(PETSC_COMM_SELF, l.border, 0, 1, border), "ISCreateStride");
    runtime.check(PCFieldSplitSetIS(pc, "0", *blocks), "PCFieldSplitSetIS");
    runtime.check(PCFieldSplitSetIS(pc, "1", *border), "PCFieldSplitSetIS");
    runtime.check(PCFieldSplitSetType(pc, PC_COMPOSITE_SCHUR), "PCFieldSplitSetType");
    runtime.check(PCFieldSplitSetSchurFactType(pc, PC_FIELDSPLIT_SCHUR_FACT_FULL), "PCFieldSplitSetSchurFactType");
    // The Schur complement S = A11 - A10 inv(A00) A01 is formed explicitly by raceway (see
    // PetscSolver::form_schur_complement) and given to PETSc as the matrix the Schur split's
    // preconditioner is built from, so LU of it makes the Schur solve exact. PETSc's own
    // "-pc_fieldsplit_schur_precondition full" is not used, for two reasons measured on PETSc 3.18:
    // MatSchurComplementComputeExplicitOperator chops entries of inv(A00) A01 below 1e-10
    // (MatChop(PETSC_SMALL)), which in SI units are real entries (the solve residual was 1e-6 to
    // 1e-4 relative on the bearings' Newton matrices instead of 1e-12), and on a re-setup with the
    // same nonzero pattern it keeps the Schur complement of the first matrix.
    runtime.check(PCFieldSplitSetSchurPre(pc, PC_FIELDSPLIT_SCHUR_PRE_USER, schur), "PCFieldSplitSetSchurPre");
  }
  runtime.check(KSPSetFromOptions(ksp), "KSPSetFromOptions");
}

class PetscSolver final : public SolverContent {
 public:
  PetscSolver(PetscRuntime& runtime, const BorderedLayout& l)
      : runtime_(runtime), layout_(l), work_(static_cast<std::size_t>(l.size())) {
    runtime_.check(KSPCreate(PETSC_COMM_SELF, &ksp_), "KSPCreate");
    if (l.border > 0) {
      // Identity until the first setup forms S (PETSc may factor it before that).
      runtime_.check(MatCreateSeqDense(PETSC_COMM_SELF, l.border, l.border, nullptr, &schur_), "MatCreateSeqDense");
      runtime_.check(MatShift(schur_, 1.0), "MatShift");
    }
    configure_ksp(runtime_, ksp_, l, &blocks_, &border_, schur_);
    runtime_.check(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, l.size(), nullptr, &b_), "VecCreateSeqWithArray");
    runtime_.check(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, l.size(), nullptr, &x_), "VecCreateSeqWithArray");
  }
  ~PetscSolver() override {
    KSPDestroy(&ksp_);
    ISDestroy(&blocks_);
    ISDestroy(&border_);
    VecDestroy(&b_);
    VecDestroy(&x_);
    MatDestroy(&schur_);
    MatDestroy(&a01_dense_), MatDestroy(&a00_inv_a01_), MatDestroy(&product_);
  }
  int setup(SUNMatrix a) override {
    Mat m = static_cast<PetscBordered&>(content(a)).a;
    // The same Mat every time: PETSc sees an unchanged nonzero pattern and redoes only the numeric
    // factorisations (sub-matrices, LU of the blocks, explicit Schur complement, LU of it).
    runtime_.clear_last_error();
    PetscErrorCode code = KSPSetOperators(ksp_, m, m);
    if (code == 0) code = KSPSetUp(ksp_);
    std::string singular;
    if (code == 0) code = form_schur_complement(&singular);
    if (code == 0 && !singular.empty()) {
      last_error = "PETSc factorisation failed: " + singular;
      return SUNLS_LUFACT_FAIL;  // recoverable: CVODE retries with a smaller step
    }
    if (code == 0) {
      PC pc;
      PCFailedReason reason = PC_NOERROR;
      KSPGetPC(ksp_, &pc);
      PCGetFailedReason(pc, &reason);
      if (reason != PC_NOERROR) {
        last_error = fmt::format("PETSc preconditioner setup failed ({})", PCFailedReasons[reason]);
        return SUNLS_LUFACT_FAIL;
      }
      return 0;
    }
    last_error = runtime_.last_error();
    // A zero pivot is a singular Newton matrix at this step size: recoverable (smaller step).
    return code == PETSC_ERR_MAT_LU_ZRPVT ? SUNLS_LUFACT_FAIL : SUNLS_PACKAGE_FAIL_UNREC;
  }
  int solve(const double* b, double* x) override {
    // b and x may alias (SUNDIALS allows it): solve from a copy of b.
    const double* rhs = b;
    if (b == x) {
      std::copy(b, b + layout_.size(), work_.begin());
      rhs = work_.data();
    }
    runtime_.clear_last_error();
    PetscErrorCode code = VecPlaceArray(b_, rhs);
    if (code == 0) code = VecPlaceArray(x_, x);
    if (code == 0) code = KSPSolve(ksp_, b_, x_);
    VecResetArray(b_);
    VecResetArray(x_);
    if (code != 0) {
      last_error = runtime_.last_error();
      return SUNLS_PACKAGE_FAIL_UNREC;
    }
    KSPConvergedReason reason;
    KSPGetConvergedReason(ksp_, &reason);
    if (reason < 0) {
      last_error = fmt::format("PETSc solve failed: {}", KSPConvergedReasons[reason]);
      return SUNLS_PACKAGE_FAIL_REC;  // e.g. a zero pivot found late: CVODE retries
    }
    return 0;
  }
  KSP ksp() const { return ksp_; }

 private:
  /// S = A11 - A10 inv(A00) A01 into schur_, exactly: A00's factorisation (split 0's KSP, set up by
  /// KSPSetUp) applied to the dense columns of A01, then the Schur split's KSP set up on it. Only
  /// when the options keep the Schur preconditioner matrix raceway's (the default, "user").
  PetscErrorCode form_schur_complement(std::string* singular) {
    if (!schur_) return 0;
    PC pc;
    PetscCall(KSPGetPC(ksp_, &pc));
    PetscBool fieldsplit = PETSC_FALSE;
    PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCFIELDSPLIT, &fieldsplit));
    if (!fieldsplit) return 0;
    PCCompositeType type;
    PetscCall(PCFieldSplitGetType(pc, &type));
    if (type != PC_COMPOSITE_SCHUR) return 0;
    PCFieldSplitSchurPreType pre;
    Mat pre_mat = nullptr;
    PetscCall(PCFieldSplitGetSchurPre(pc, &pre, &pre_mat));
    if (pre != PC_FIELDSPLIT_SCHUR_PRE_USER || pre_mat != schur_) return 0;
    Mat s_op, a01, a10, a11;
    PetscCall(PCFieldSplitSchurGetS(pc, &s_op));
    PetscCall(MatSchurComplementGetSubMatrices(s_op, nullptr, nullptr, &a01, &a10, &a11));
    PetscInt count = 0;
    KSP* sub = nullptr;
    PetscCall(PCFieldSplitGetSubKSP(pc, &count, &sub));
    KSP ksp_a00 = sub[0], ksp_schur = sub[count - 1];
    PetscCall(PetscFree(sub));
    // Work matrices kept between setups (the sub-matrices keep their objects when PETSc reuses them).
    const bool reuse = a01_dense_ && a01_source_ == a01 && a10_source_ == a10;
    if (!reuse) {
      MatDestroy(&a01_dense_), MatDestroy(&a00_inv_a01_), MatDestroy(&product_);
      PetscCall(MatConvert(a01, MATDENSE, MAT_INITIAL_MATRIX, &a01_dense_));
      PetscCall(MatDuplicate(a01_dense_, MAT_DO_NOT_COPY_VALUES, &a00_inv_a01_));
      a01_source_ = a01, a10_source_ = a10;
    } else {
      PetscCall(MatConvert(a01, MATDENSE, MAT_REUSE_MATRIX, &a01_dense_));
    }
    // A singular rolling-element block shows here first (PETSc records it as the PC's failed reason).
    PetscCall(KSPSetUp(ksp_a00));
    PC pc_a00;
    PCFailedReason failed = PC_NOERROR;
    PetscCall(KSPGetPC(ksp_a00, &pc_a00));
    PetscCall(PCGetFailedReason(pc_a00, &failed));
    if (failed != PC_NOERROR) {
      *singular = fmt::format("rolling-element blocks: {}", PCFailedReasons[failed]);
      return 0;
    }
    PetscCall(KSPMatSolve(ksp_a00, a01_dense_, a00_inv_a01_));  // inv(A00) A01, no chopping
    PetscCall(MatMatMult(a10, a00_inv_a01_, product_ ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, PETSC_DEFAULT,
                         &product_));
    PetscCall(MatCopy(a11, schur_, DIFFERENT_NONZERO_PATTERN));
    PetscCall(MatAXPY(schur_, -1.0, product_, SAME_NONZERO_PATTERN));
    PetscCall(KSPSetUp(ksp_schur));  // LU of S now, so a singular S fails the setup, not the solve
    PC pc_schur;
    PetscCall(KSPGetPC(ksp_schur, &pc_schur));
    PetscCall(PCGetFailedReason(pc_schur, &failed));
    if (failed != PC_NOERROR) *singular = fmt::format("Schur complement: {}", PCFailedReasons[failed]);
    return 0;
  }

  PetscRuntime& runtime_;  ///< where PETSc's error messages are recorded
  BorderedLayout layout_;
  KSP ksp_ = nullptr;
  IS blocks_ = nullptr, border_ = nullptr;
  Mat schur_ = nullptr;  ///< the explicit Schur complement, border x border, dense
  Mat a01_dense_ = nullptr, a00_inv_a01_ = nullptr, product_ = nullptr;  ///< its work matrices
  Mat a01_source_ = nullptr, a10_source_ = nullptr;  ///< PETSc's sub-matrices they were made for
  Vec b_ = nullptr, x_ = nullptr;
  std::vector<double> work_;
};

}  // namespace

NewtonObjects create_petsc_bordered(SUNContext ctx, N_Vector, const BorderedLayout& layout) {
  PetscRuntime& runtime = PetscRuntime::current();
  auto solver = std::make_unique<PetscSolver>(runtime, layout);
  NewtonObjects o;
  o.matrix = make_custom_matrix(ctx, std::make_unique<PetscBordered>(runtime, layout));
  o.solver = make_custom_solver(ctx, std::move(solver));
  return o;
}

std::string describe_petsc_bordered(SUNLinearSolver s) {
  KSP ksp = static_cast<PetscSolver&>(solver_content(s)).ksp();
  PC pc;
  KSPGetPC(ksp, &pc);
  KSPType kt;
  PCType pt;
  KSPGetType(ksp, &kt);
  PCGetType(pc, &pt);
  std::string description = fmt::format("ksp {}, pc {}", kt, pt);
  PetscBool is_fs = PETSC_FALSE;
  PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCFIELDSPLIT, &is_fs);
  PetscInt count = 0;
  KSP* sub = nullptr;
  if (!is_fs || PCFieldSplitGetSubKSP(pc, &count, &sub) != 0) return description;
  for (PetscInt i = 0; i < count; ++i) {
    PC sp;
    KSPGetType(sub[i], &kt);
    KSPGetPC(sub[i], &sp);
    PCGetType(sp, &pt);
    MatSolverType st = nullptr;
    PetscBool is_factor = PETSC_FALSE;
    PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(sp), &is_factor, PCLU, PCILU, PCCHOLESKY, PCICC, "");
    if (is_factor) PCFactorGetMatSolverType(sp, &st);
    description += fmt::format("; split {} ({}): ksp {}, pc {}{}", i, i == 0 ? "rolling elements" : "Schur, border", kt,
                               pt, st ? fmt::format(" ({})", st) : "");
  }
  PetscFree(sub);
  return description;
}

}  // namespace raceway::numerics::backend
