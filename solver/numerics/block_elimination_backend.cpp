// The block-elimination backend: J and M as a BorderedMatrix (Eigen blocks), factored and solved by
// BorderedFactorization (solver/numerics/bordered_matrix.hpp).
#include <memory>

#include "solver/numerics/backend_factories.hpp"
#include "solver/numerics/sundials_custom.hpp"

namespace raceway::numerics::backend {

namespace {

class EigenBordered final : public MatrixContent {
 public:
  explicit EigenBordered(const BorderedLayout& l) : m(l.border, l.blocks, l.block_size) {}
  std::unique_ptr<MatrixContent> clone() const override { return std::make_unique<EigenBordered>(*this); }
  void zero() override { m.set_zero(); }
  void copy_to(MatrixContent& to) const override { static_cast<EigenBordered&>(to).m.copy_values(m); }
  void scale_add_identity(double c) override { m.scale_add_identity(c); }
  void multiply(const double* x, double* y) const override { m.multiply(x, y); }
  void load(const BorderedMatrix& j) override { m.copy_values(j); }
  BorderedMatrix m;
};

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

}  // namespace

NewtonObjects create_block_elimination(SUNContext ctx, N_Vector, const BorderedLayout& layout) {
  NewtonObjects o;
  o.matrix = make_custom_matrix(ctx, std::make_unique<EigenBordered>(layout));
  o.solver = make_custom_solver(ctx, std::make_unique<BlockEliminationSolver>());
  return o;
}

}  // namespace raceway::numerics::backend
