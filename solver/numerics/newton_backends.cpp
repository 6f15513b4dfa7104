#include "solver/numerics/newton_backends.hpp"

#include <fmt/format.h>
#include <nvector/nvector_serial.h>
#include <petscksp.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "io/scene/scene_parser.hpp"

namespace raceway::solver {

// ---------------------------------------------------------------------------------------------
// Backend names and the automatic choice
// ---------------------------------------------------------------------------------------------

// `auto` is the hand-written block elimination. Measured per Newton setup + solve (assembly, M =
// I - gamma J, factorisation, one solve; perf/results/bordered_scaling.txt), both backends are O(N)
// and exact, and the block elimination is 2.4 to 2.9 times cheaper at every N from 8 to 512 (real
// bearings: 6309, 8 balls: 29 vs 85 us; QJ215, 15 balls: 36 vs 90 us; seed 002, 13 rollers: 11 vs
// 31 us). PETSc's fixed and per-block costs: four sub-matrix extractions per setup, a sparse LU of
// split 0 through the generic AIJ kernels (i-nodes of 5 or 9 rows) instead of dense 9x9 LAPACK-style
// blocks, the Schur complement through KSPMatSolve on dense column blocks, and object bookkeeping.
// PETSc earns its place where the hand-written path cannot go: run-time solver choices (MUMPS,
// SuperLU_DIST, hypre, ILU) and, later, the distributed (MPIAIJ) Newton systems of multi-rank runs.
io::LinearSolverKind resolve_linear_solver(io::LinearSolverKind kind, const BorderedLayout&) {
  return kind == io::LinearSolverKind::automatic ? io::LinearSolverKind::block_elimination : kind;
}

const char* linear_solver_name(io::LinearSolverKind kind) {
  switch (kind) {
    case io::LinearSolverKind::automatic: return "auto";
    case io::LinearSolverKind::petsc_bordered: return "petsc-bordered";
    case io::LinearSolverKind::block_elimination: return "block-elimination";
    case io::LinearSolverKind::sundials_dense: return "sundials-dense";
  }
  return "?";
}

// ---------------------------------------------------------------------------------------------
// PETSc runtime, errors and options
// ---------------------------------------------------------------------------------------------

namespace {

std::string g_command_line_options;
bool g_runtime = false;
std::string g_last_petsc_error;  // first message of the last PETSc error (the handler below)
std::string g_applied_key;       // options last put into the database (cache of configure_petsc_options)
std::string g_applied_summary;

// Records PETSc's message instead of printing a traceback: raceway reports errors itself, once,
// with the context (scene key, command-line option) PETSc does not know.
PetscErrorCode record_error(MPI_Comm, int, const char* function, const char*, PetscErrorCode code,
                            PetscErrorType type, const char* message, void*) {
  if (type == PETSC_ERROR_INITIAL) {
    std::string m = message ? message : "";
    while (!m.empty() && (m.back() == '\n' || m.back() == ' ')) m.pop_back();
    g_last_petsc_error = fmt::format("{} (PETSc error {} in {})", m.empty() ? "PETSc error" : m, static_cast<int>(code),
                                     function ? function : "?");
  }
  return code;
}

/// Throws std::runtime_error with PETSc's message when `code` is an error.
void petsc_check(PetscErrorCode code, const char* what) {
  if (code == 0) return;
  throw std::runtime_error(fmt::format("PETSc: {} failed: {}", what, g_last_petsc_error));
}

void require_runtime() {
  if (!g_runtime)
    throw std::logic_error("the petsc-bordered linear solver needs PETSc initialised: create a "
                           "solver::PetscRuntime after MPI_Init (the raceway driver and the test mains do)");
}

// Options raceway sets when neither the scene nor the command line does: exact block LU on split 0
// and exact LU of the explicit Schur complement, each applied once (preonly). The outer KSP and
// the fieldsplit type are set in code before KSPSetFromOptions, so options override them too.
const std::vector<std::pair<const char*, const char*>> kDefaultOptions = {
    {"-fieldsplit_0_ksp_type", "preonly"},
    {"-fieldsplit_0_pc_type", "lu"},
    {"-fieldsplit_1_ksp_type", "preonly"},
    {"-fieldsplit_1_pc_type", "lu"},
};

}  // namespace

PetscRuntime::PetscRuntime(std::string command_line_options) {
  if (g_runtime) throw std::logic_error("PetscRuntime: one per process");
  // raceway keeps the default crash behaviour (core dumps, sanitizers): no PETSc signal handler.
  PetscOptionsSetValue(nullptr, "-no_signal_handler", nullptr);
  // The Newton systems live on the master alone (DESIGN.md 5), and only the master starts PETSc:
  // PETSc's world is this process, so its collective start-up involves no other rank.
  PETSC_COMM_WORLD = MPI_COMM_SELF;
  if (PetscInitialize(nullptr, nullptr, nullptr, nullptr) != 0) throw std::runtime_error("PetscInitialize failed");
  PetscPushErrorHandler(record_error, nullptr);
  g_runtime = true;
  g_command_line_options = std::move(command_line_options);
}

PetscRuntime::~PetscRuntime() {
  g_runtime = false;
  g_applied_key.clear();
  PetscPopErrorHandler();
  PetscFinalize();
}

bool PetscRuntime::active() { return g_runtime; }
void PetscRuntime::set_command_line_options(std::string options) { g_command_line_options = std::move(options); }

// ---------------------------------------------------------------------------------------------
// PETSc matrix and solver
// ---------------------------------------------------------------------------------------------

namespace {

/// Content of the custom SUNMatrix types: a bordered matrix in one representation or another.
class MatrixContent {
 public:
  virtual ~MatrixContent() = default;
  virtual std::unique_ptr<MatrixContent> clone() const = 0;
  virtual void zero() = 0;
  virtual void copy_to(MatrixContent& to) const = 0;
  virtual void scale_add_identity(double c) = 0;
  virtual void multiply(const double* x, double* y) const = 0;
  virtual void load(const BorderedMatrix& j) = 0;
};

MatrixContent& content(SUNMatrix a) { return *static_cast<MatrixContent*>(a->content); }

class EigenBordered final : public MatrixContent {
 public:
  explicit EigenBordered(const BorderedLayout& l) : m(l.border, l.blocks, l.block_size) {}
  std::unique_ptr<MatrixContent> clone() const override { return std::make_unique<EigenBordered>(*this); }
  void zero() override { m.set_zero(); }
  void copy_to(MatrixContent& to) const override { static_cast<EigenBordered&>(to).m = m; }
  void scale_add_identity(double c) override { m.scale_add_identity(c); }
  void multiply(const double* x, double* y) const override { m.multiply(x, y); }
  void load(const BorderedMatrix& j) override { m = j; }
  BorderedMatrix m;
};

/// A SeqAIJ matrix with the bordered pattern, entries stored row by row with columns ascending:
/// border rows hold all n columns; a block row holds the border columns then its block's.
class PetscBordered final : public MatrixContent {
 public:
  explicit PetscBordered(const BorderedLayout& l) : layout(l) {
    const PetscInt n = l.size(), nb = l.border, m = l.block_size;
    std::vector<PetscInt> nnz(static_cast<std::size_t>(n));
    for (PetscInt r = 0; r < n; ++r) nnz[static_cast<std::size_t>(r)] = r < nb ? n : nb + m;
    petsc_check(MatCreateSeqAIJ(PETSC_COMM_SELF, n, n, 0, nnz.data(), &a), "MatCreateSeqAIJ");
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
      petsc_check(MatSetValues(a, 1, &r, static_cast<PetscInt>(cols.size()), cols.data(), zeros.data(), INSERT_VALUES),
                  "MatSetValues");
    }
    petsc_check(MatAssemblyBegin(a, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    petsc_check(MatAssemblyEnd(a, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    petsc_check(MatSetOption(a, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE), "MatSetOption");
    MatInfo info;
    petsc_check(MatGetInfo(a, MAT_LOCAL, &info), "MatGetInfo");
    const double expected = static_cast<double>(nb) * n + static_cast<double>(n - nb) * static_cast<double>(nb + m);
    if (info.nz_used != expected || info.nz_allocated != expected)
      throw std::logic_error(fmt::format("PETSc bordered matrix: {} entries used, {} allocated, {} expected",
                                         info.nz_used, info.nz_allocated, expected));
  }
  PetscBordered(const PetscBordered& o) : MatrixContent(o), layout(o.layout) {
    petsc_check(MatDuplicate(o.a, MAT_COPY_VALUES, &a), "MatDuplicate");
  }
  ~PetscBordered() override { MatDestroy(&a); }
  std::unique_ptr<MatrixContent> clone() const override { return std::make_unique<PetscBordered>(*this); }
  void zero() override { petsc_check(MatZeroEntries(a), "MatZeroEntries"); }
  void copy_to(MatrixContent& to) const override {
    petsc_check(MatCopy(a, static_cast<PetscBordered&>(to).a, SAME_NONZERO_PATTERN), "MatCopy");
  }
  void scale_add_identity(double c) override {
    petsc_check(MatScale(a, c), "MatScale");
    petsc_check(MatShift(a, 1.0), "MatShift");
  }
  void multiply(const double* x, double* y) const override {
    const PetscInt n = layout.size();
    Vec vx, vy;
    petsc_check(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, n, x, &vx), "VecCreateSeqWithArray");
    petsc_check(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, n, y, &vy), "VecCreateSeqWithArray");
    petsc_check(MatMult(a, vx, vy), "MatMult");
    VecDestroy(&vx);
    VecDestroy(&vy);
  }
  /// Assembly: the bordered blocks written straight into the CSR values, in the layout of the
  /// constructor (O(nnz), no searching of column indices).
  void load(const BorderedMatrix& j) override {
    const int nb = layout.border, nblocks = layout.blocks, m = layout.block_size;
    PetscScalar* v = nullptr;
    petsc_check(MatSeqAIJGetArrayWrite(a, &v), "MatSeqAIJGetArrayWrite");
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
    petsc_check(MatSeqAIJRestoreArrayWrite(a, &v), "MatSeqAIJRestoreArrayWrite");
  }
  BorderedLayout layout;
  Mat a = nullptr;
};

SUNMatrix make_custom_matrix(SUNContext ctx, std::unique_ptr<MatrixContent> c);

SUNMatrix_ID cm_getid(SUNMatrix) { return SUNMATRIX_CUSTOM; }
SUNMatrix cm_clone(SUNMatrix a) {
  try {
    return make_custom_matrix(a->sunctx, content(a).clone());
  } catch (...) {
    return nullptr;
  }
}
void cm_destroy(SUNMatrix a) {
  if (!a) return;
  delete static_cast<MatrixContent*>(a->content);
  a->content = nullptr;
  SUNMatFreeEmpty(a);
}
// The ops CVODE calls return a negative flag (unrecoverable) on a PETSc error; its message is kept.
template <class F>
int guarded(F&& f) {
  try {
    f();
    return 0;
  } catch (...) {
    return -1;
  }
}
int cm_zero(SUNMatrix a) { return guarded([&] { content(a).zero(); }); }
int cm_copy(SUNMatrix from, SUNMatrix to) { return guarded([&] { content(from).copy_to(content(to)); }); }
int cm_scaleaddi(sunrealtype c, SUNMatrix a) { return guarded([&] { content(a).scale_add_identity(c); }); }
int cm_matvec(SUNMatrix a, N_Vector x, N_Vector y) {
  return guarded([&] { content(a).multiply(N_VGetArrayPointer(x), N_VGetArrayPointer(y)); });
}

SUNMatrix make_custom_matrix(SUNContext ctx, std::unique_ptr<MatrixContent> c) {
  SUNMatrix a = SUNMatNewEmpty(ctx);
  a->ops->getid = cm_getid;
  a->ops->clone = cm_clone;
  a->ops->destroy = cm_destroy;
  a->ops->zero = cm_zero;
  a->ops->copy = cm_copy;
  a->ops->scaleaddi = cm_scaleaddi;
  a->ops->matvec = cm_matvec;
  a->content = c.release();
  return a;
}

// ---- linear solvers ---------------------------------------------------------------------------

class SolverContent {
 public:
  virtual ~SolverContent() = default;
  virtual int setup(SUNMatrix a) = 0;
  virtual int solve(const double* b, double* x) = 0;
  sunindextype last_flag = 0;
  std::string last_error;
};
SolverContent& solver_content(SUNLinearSolver s) { return *static_cast<SolverContent*>(s->content); }

class BlockEliminationSolver final : public SolverContent {
 public:
  int setup(SUNMatrix a) override {
    const bool ok = factorization_.factor(static_cast<EigenBordered&>(content(a)).m);
    return ok ? 0 : SUNLS_LUFACT_FAIL;  // positive: recoverable, CVODE retries with a smaller step
  }
  int solve(const double* b, double* x) override {
    factorization_.solve(b, x);
    return 0;
  }

 private:
  BorderedFactorization factorization_;
};

/// Sets up the KSP of the petsc-bordered solver on `a` from the options database.
void configure_ksp(KSP ksp, const BorderedLayout& l, IS* blocks, IS* border, Mat schur) {
  PC pc;
  petsc_check(KSPGetPC(ksp, &pc), "KSPGetPC");
  petsc_check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
  if (l.border == 0) {
    // No border: the matrix is split 0 alone, so it is solved as split 0 is (options fieldsplit_0_*).
    petsc_check(KSPSetOptionsPrefix(ksp, "fieldsplit_0_"), "KSPSetOptionsPrefix");
    petsc_check(PCSetType(pc, PCLU), "PCSetType");
  } else {
    petsc_check(PCSetType(pc, PCFIELDSPLIT), "PCSetType");
    petsc_check(ISCreateStride(PETSC_COMM_SELF, l.blocks * l.block_size, l.border, 1, blocks), "ISCreateStride");
    petsc_check(ISCreateStride(PETSC_COMM_SELF, l.border, 0, 1, border), "ISCreateStride");
    petsc_check(PCFieldSplitSetIS(pc, "0", *blocks), "PCFieldSplitSetIS");
    petsc_check(PCFieldSplitSetIS(pc, "1", *border), "PCFieldSplitSetIS");
    petsc_check(PCFieldSplitSetType(pc, PC_COMPOSITE_SCHUR), "PCFieldSplitSetType");
    petsc_check(PCFieldSplitSetSchurFactType(pc, PC_FIELDSPLIT_SCHUR_FACT_FULL), "PCFieldSplitSetSchurFactType");
    // The Schur complement S = A11 - A10 inv(A00) A01 is formed explicitly by raceway (see
    // PetscSolver::form_schur_complement) and given to PETSc as the matrix the Schur split's
    // preconditioner is built from, so LU of it makes the Schur solve exact. PETSc's own
    // "-pc_fieldsplit_schur_precondition full" is not used, for two reasons measured on PETSc 3.18:
    // MatSchurComplementComputeExplicitOperator chops entries of inv(A00) A01 below 1e-10
    // (MatChop(PETSC_SMALL)), which in SI units are real entries (the solve residual was 1e-6 to
    // 1e-4 relative on the bearings' Newton matrices instead of 1e-12), and on a re-setup with the
    // same nonzero pattern it keeps the Schur complement of the first matrix.
    petsc_check(PCFieldSplitSetSchurPre(pc, PC_FIELDSPLIT_SCHUR_PRE_USER, schur), "PCFieldSplitSetSchurPre");
  }
  petsc_check(KSPSetFromOptions(ksp), "KSPSetFromOptions");
}

class PetscSolver final : public SolverContent {
 public:
  explicit PetscSolver(const BorderedLayout& l) : layout_(l), work_(static_cast<std::size_t>(l.size())) {
    require_runtime();
    petsc_check(KSPCreate(PETSC_COMM_SELF, &ksp_), "KSPCreate");
    if (l.border > 0) {
      // Identity until the first setup forms S (PETSc may factor it before that).
      petsc_check(MatCreateSeqDense(PETSC_COMM_SELF, l.border, l.border, nullptr, &schur_), "MatCreateSeqDense");
      petsc_check(MatShift(schur_, 1.0), "MatShift");
    }
    configure_ksp(ksp_, l, &blocks_, &border_, schur_);
    petsc_check(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, l.size(), nullptr, &b_), "VecCreateSeqWithArray");
    petsc_check(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, l.size(), nullptr, &x_), "VecCreateSeqWithArray");
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
    g_last_petsc_error.clear();
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
    last_error = g_last_petsc_error;
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
    g_last_petsc_error.clear();
    PetscErrorCode code = VecPlaceArray(b_, rhs);
    if (code == 0) code = VecPlaceArray(x_, x);
    if (code == 0) code = KSPSolve(ksp_, b_, x_);
    VecResetArray(b_);
    VecResetArray(x_);
    if (code != 0) {
      last_error = g_last_petsc_error;
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

  BorderedLayout layout_;
  KSP ksp_ = nullptr;
  IS blocks_ = nullptr, border_ = nullptr;
  Mat schur_ = nullptr;  ///< the explicit Schur complement, border x border, dense
  Mat a01_dense_ = nullptr, a00_inv_a01_ = nullptr, product_ = nullptr;  ///< its work matrices
  Mat a01_source_ = nullptr, a10_source_ = nullptr;  ///< PETSc's sub-matrices they were made for
  Vec b_ = nullptr, x_ = nullptr;
  std::vector<double> work_;
};

SUNLinearSolver_Type ls_gettype(SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; }
SUNLinearSolver_ID ls_getid(SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; }
int ls_initialize(SUNLinearSolver) { return 0; }
int ls_setup(SUNLinearSolver s, SUNMatrix a) {
  auto& c = solver_content(s);
  try {
    const int flag = c.setup(a);
    c.last_flag = flag;
    return flag;
  } catch (const std::exception& e) {
    c.last_error = e.what();
    c.last_flag = SUNLS_PACKAGE_FAIL_UNREC;
    return SUNLS_PACKAGE_FAIL_UNREC;
  }
}
int ls_solve(SUNLinearSolver s, SUNMatrix, N_Vector x, N_Vector b, sunrealtype) {
  auto& c = solver_content(s);
  try {
    const int flag = c.solve(N_VGetArrayPointer(b), N_VGetArrayPointer(x));
    c.last_flag = flag;
    return flag;
  } catch (const std::exception& e) {
    c.last_error = e.what();
    c.last_flag = SUNLS_PACKAGE_FAIL_UNREC;
    return SUNLS_PACKAGE_FAIL_UNREC;
  }
}
sunindextype ls_lastflag(SUNLinearSolver s) { return solver_content(s).last_flag; }
int ls_free(SUNLinearSolver s) {
  if (!s) return 0;
  delete static_cast<SolverContent*>(s->content);
  s->content = nullptr;
  SUNLinSolFreeEmpty(s);
  return 0;
}

SUNLinearSolver make_custom_solver(SUNContext ctx, std::unique_ptr<SolverContent> c) {
  SUNLinearSolver s = SUNLinSolNewEmpty(ctx);
  s->ops->gettype = ls_gettype;
  s->ops->getid = ls_getid;
  s->ops->initialize = ls_initialize;
  s->ops->setup = ls_setup;
  s->ops->solve = ls_solve;
  s->ops->lastflag = ls_lastflag;
  s->ops->free = ls_free;
  s->content = c.release();
  return s;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// NewtonLinearSystem
// ---------------------------------------------------------------------------------------------

NewtonLinearSystem::NewtonLinearSystem(io::LinearSolverKind kind, SUNContext ctx, N_Vector y,
                                       const BorderedLayout& layout)
    : kind_(kind) {
  switch (kind) {
    case io::LinearSolverKind::block_elimination:
      matrix_ = make_custom_matrix(ctx, std::make_unique<EigenBordered>(layout));
      solver_ = make_custom_solver(ctx, std::make_unique<BlockEliminationSolver>());
      break;
    case io::LinearSolverKind::petsc_bordered: {
      auto solver = std::make_unique<PetscSolver>(layout);  // first: checks the PETSc runtime
      matrix_ = make_custom_matrix(ctx, std::make_unique<PetscBordered>(layout));
      solver_ = make_custom_solver(ctx, std::move(solver));
      break;
    }
    case io::LinearSolverKind::sundials_dense: {
      const auto n = static_cast<sunindextype>(layout.size());
      matrix_ = SUNDenseMatrix(n, n, ctx);
      solver_ = SUNLinSol_Dense(y, matrix_, ctx);
      break;
    }
    case io::LinearSolverKind::automatic:
      throw std::logic_error("NewtonLinearSystem: resolve linear_solver = auto first");
  }
  if (!matrix_ || !solver_) throw std::runtime_error("NewtonLinearSystem: SUNDIALS could not create the matrix or solver");
}

NewtonLinearSystem::~NewtonLinearSystem() {
  if (solver_) SUNLinSolFree(solver_);
  if (matrix_) SUNMatDestroy(matrix_);
}

void NewtonLinearSystem::load_jacobian(const BorderedMatrix& j, SUNMatrix a) {
  if (SUNMatGetID(a) == SUNMATRIX_DENSE) {
    const auto n = static_cast<sunindextype>(j.size());
    const int nb = j.border_size(), m = j.block_size();
    SUNMatZero(a);
    for (sunindextype c = 0; c < n; ++c) {
      sunrealtype* col = SUNDenseMatrix_Column(a, c);
      const int cc = static_cast<int>(c);
      if (cc < nb) {
        for (int r = 0; r < nb; ++r) col[r] = j.border(r, cc);
        for (int k = 0; k < j.block_count(); ++k)
          for (int r = 0; r < m; ++r) col[nb + k * m + r] = j.block_to_border[static_cast<std::size_t>(k)](r, cc);
      } else {
        const int k = (cc - nb) / m, kc = (cc - nb) % m;
        const auto kk = static_cast<std::size_t>(k);
        for (int r = 0; r < nb; ++r) col[r] = j.border_to_block[kk](r, kc);
        for (int r = 0; r < m; ++r) col[nb + k * m + r] = j.block[kk](r, kc);
      }
    }
    return;
  }
  content(a).load(j);
}

std::string NewtonLinearSystem::last_error() const {
  if (kind_ == io::LinearSolverKind::sundials_dense) return {};
  return solver_content(solver_).last_error;
}

// ---------------------------------------------------------------------------------------------
// Options: defaults, validation by a trial solve
// ---------------------------------------------------------------------------------------------

namespace {

struct Trial {
  bool ok = false;
  std::string error;
  double residual = 0;  ///< ||M x - b|| / ||b||
  std::string description;
};

/// Sets up and solves a small well-conditioned bordered system with the database's options.
Trial trial_solve(const BorderedLayout& real) {
  Trial t;
  BorderedLayout l = real;
  l.border = std::max(real.border, 1);
  l.blocks = std::clamp(real.blocks, 1, 3);
  l.block_size = std::max(real.block_size, 1);
  BorderedMatrix j(l.border, l.blocks, l.block_size);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int r = 0; r < l.size(); ++r)
    for (int c = 0; c < l.size(); ++c) {
      const bool coupled = r < l.border || c < l.border || (r - l.border) / l.block_size == (c - l.border) / l.block_size;
      if (coupled) j.add(r, c, u(rng));
    }
  try {
    SUNContext ctx = nullptr;
    SUNContext_Create(nullptr, &ctx);
    struct Guard {
      SUNContext& c;
      ~Guard() { SUNContext_Free(&c); }
    } guard{ctx};
    N_Vector b = N_VNew_Serial(l.size(), ctx), x = N_VNew_Serial(l.size(), ctx), y = N_VNew_Serial(l.size(), ctx);
    struct Vectors {
      N_Vector a, b, c;
      ~Vectors() { N_VDestroy(a), N_VDestroy(b), N_VDestroy(c); }
    } vectors{b, x, y};
    NewtonLinearSystem sys(io::LinearSolverKind::petsc_bordered, ctx, b, l);
    NewtonLinearSystem::load_jacobian(j, sys.matrix());
    SUNMatScaleAddI(-0.05, sys.matrix());  // I - gamma J, diagonally dominant
    if (SUNLinSolSetup(sys.solver(), sys.matrix()) != 0) {
      t.error = sys.last_error();
      return t;
    }
    for (int i = 0; i < l.size(); ++i) NV_Ith_S(b, i) = u(rng);
    if (SUNLinSolSolve(sys.solver(), sys.matrix(), x, b, 0) != 0) {
      t.error = sys.last_error();
      return t;
    }
    SUNMatMatvec(sys.matrix(), x, y);
    N_VLinearSum(1.0, y, -1.0, b, y);
    t.residual = std::sqrt(N_VDotProd(y, y) / N_VDotProd(b, b));
    if (!std::isfinite(t.residual)) {
      t.error = "the trial solve gave a non-finite solution";
      return t;
    }
    // What was built, in PETSc's words: outer KSP/PC and the split solvers.
    KSP ksp = static_cast<PetscSolver&>(solver_content(sys.solver())).ksp();
    PC pc;
    KSPGetPC(ksp, &pc);
    KSPType kt;
    PCType pt;
    KSPGetType(ksp, &kt);
    PCGetType(pc, &pt);
    t.description = fmt::format("ksp {}, pc {}", kt, pt);
    PetscBool is_fs = PETSC_FALSE;
    PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCFIELDSPLIT, &is_fs);
    if (is_fs) {
      PetscInt count = 0;
      KSP* sub = nullptr;
      if (PCFieldSplitGetSubKSP(pc, &count, &sub) == 0) {
        for (PetscInt i = 0; i < count; ++i) {
          PC sp;
          KSPGetType(sub[i], &kt);
          KSPGetPC(sub[i], &sp);
          PCGetType(sp, &pt);
          MatSolverType st = nullptr;
          PetscBool is_factor = PETSC_FALSE;
          PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(sp), &is_factor, PCLU, PCILU, PCCHOLESKY, PCICC, "");
          if (is_factor) PCFactorGetMatSolverType(sp, &st);
          t.description += fmt::format("; split {} ({}): ksp {}, pc {}{}", i, i == 0 ? "rolling elements" : "Schur, border",
                                       kt, pt, st ? fmt::format(" ({})", st) : "");
        }
        PetscFree(sub);
      }
    }
    t.ok = true;
  } catch (const std::exception& e) {
    t.error = e.what();
  }
  return t;
}

/// Names of options nobody read, apart from raceway's own defaults.
std::vector<std::string> unused_options(const std::vector<std::string>& ignore) {
  PetscInt n = 0;
  char** names = nullptr;
  char** values = nullptr;
  std::vector<std::string> out;
  if (PetscOptionsLeftGet(nullptr, &n, &names, &values) != 0) return out;
  for (PetscInt i = 0; i < n; ++i) {
    const std::string name = std::string("-") + names[i];
    if (std::find(ignore.begin(), ignore.end(), name) != ignore.end()) continue;
    if (name == "-no_signal_handler") continue;
    out.push_back(values[i] ? name + " " + values[i] : name);
  }
  PetscOptionsLeftRestore(nullptr, &n, &names, &values);
  return out;
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

}  // namespace

std::string configure_petsc_options(const io::SolverSpec& spec, const BorderedLayout& layout) {
  require_runtime();
  const std::string key = fmt::format("{}\n{}\n{} {} {}", spec.petsc_options, g_command_line_options, layout.border,
                                      layout.block_size, layout.blocks > 0);
  if (key == g_applied_key) return g_applied_summary;
  g_applied_key.clear();
  petsc_check(PetscOptionsClear(nullptr), "PetscOptionsClear");
  std::vector<std::string> defaults_set;

  // One stage per source, so that an error names where the bad option came from.
  auto stage = [&](const std::string& options, auto&& fail) {
    g_last_petsc_error.clear();
    if (!options.empty() && PetscOptionsInsertString(nullptr, options.c_str()) != 0)
      fail(fmt::format("cannot parse the PETSc options \"{}\": {}", options, g_last_petsc_error));
    for (const auto& [name, value] : kDefaultOptions) {
      PetscBool set = PETSC_FALSE;
      PetscOptionsHasName(nullptr, nullptr, name, &set);
      if (!set) {
        PetscOptionsSetValue(nullptr, name, value);
        defaults_set.emplace_back(name);
      }
    }
    const Trial t = trial_solve(layout);
    if (!t.ok)
      fail(fmt::format("PETSc options \"{}\" give no working bordered solver (trial setup and solve): {}", options,
                       t.error.empty() ? "unknown PETSc error" : t.error));
    const auto left = unused_options(defaults_set);
    if (!left.empty())
      fail(fmt::format("PETSc option(s) not used by the bordered solver (misspelt, or for a part it does not have): "
                       "{}; the solver built: {}",
                       join(left), t.description));
    return t;
  };
  Trial t = stage(spec.petsc_options, [&](const std::string& reason) {
    PetscOptionsClear(nullptr);
    throw io::SceneError(spec.petsc_options_file.empty() ? "<scene>" : spec.petsc_options_file,
                         spec.petsc_options_line, "solver.petsc_options", reason);
  });
  if (!g_command_line_options.empty())
    t = stage(g_command_line_options, [&](const std::string& reason) {
      PetscOptionsClear(nullptr);
      throw OptionsError("--petsc-options: " + reason);
    });
  g_applied_summary = fmt::format("{}; trial relative residual {:.1e}{}", t.description, t.residual,
                                  t.residual > 1e-10 ? " (an inexact solve: CVODE's Newton iteration will need more "
                                                       "iterations, or fail to converge)"
                                                     : "");
  g_applied_key = key;
  return g_applied_summary;
}

std::string prepare_linear_solver(const io::SolverSpec& spec, const BorderedLayout& layout) {
  const io::LinearSolverKind kind = resolve_linear_solver(spec.linear_solver, layout);
  std::string line = fmt::format("Newton linear solver: {}", linear_solver_name(kind));
  if (spec.linear_solver == io::LinearSolverKind::automatic)
    line += " (auto: the block elimination is 2.4-2.9x cheaper per Newton setup + solve than petsc-bordered at "
            "every size measured, 8 to 512 rolling elements, serial)";
  // PETSc options are validated whenever they are given, even if `auto` chose the other backend, so
  // that a typo shows at start-up and not in the first large run.
  const bool options_given = !spec.petsc_options.empty() || !g_command_line_options.empty();
  if (kind == io::LinearSolverKind::petsc_bordered) {
    line += "; " + configure_petsc_options(spec, layout);
  } else if (options_given && g_runtime) {
    configure_petsc_options(spec, layout);
    line += "; the PETSc options given are valid but unused by this backend";
  }
  return line;
}

}  // namespace raceway::solver
