// A matrix that is block diagonal with borders (seed 000 fig. 2):
//
//        [ A_bb   A_b1  A_b2 ... ]      border: rings and cage (n_b states)
//   M =  [ A_1b   D_1            ]      D_k: rolling element k's block (m x m)
//        [ A_2b         D_2      ]      rolling elements touch only the border
//        [ ...              ...  ]
//
// and its factorisation by block elimination: the Schur complement
// S = A_bb - sum_k A_bk D_k^-1 A_kb is formed and factored exactly, so factorisation and solve cost
// O(N) in the number of rolling elements (instead of O(N^3) and O(N^2) dense).
//
// This is the Jacobian every Newton linear-solver backend is loaded from
// (solver/numerics/newton_backends.hpp), and BorderedFactorization is the block-elimination backend;
// the petsc-bordered backend does the same elimination with PETSc's PCFIELDSPLIT. Which to use is
// measured in README "Newton linear solvers".
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace raceway::numerics {

/// Sizes of a bordered system: border states (rings, cage), rolling elements, states per element.
struct BorderedLayout {
  int border = 0, blocks = 0, block_size = 0;
  int size() const { return border + blocks * block_size; }
};

class BorderedMatrix {
 public:
  BorderedMatrix() = default;
  BorderedMatrix(int border_size, int block_count, int block_size);

  int size() const { return border_size_ + block_count_ * block_size_; }
  int border_size() const { return border_size_; }
  int block_count() const { return block_count_; }
  int block_size() const { return block_size_; }

  void set_zero();
  /// Adds v at global (row, col). Throws std::logic_error for an entry coupling two different
  /// blocks (the structure forbids it).
  void add(int row, int col, double v);
  double get(int row, int col) const;
  /// this = c * this + I
  void scale_add_identity(double c);
  /// y = this * x
  void multiply(const double* x, double* y) const;
  Eigen::MatrixXd to_dense() const;

  Eigen::MatrixXd border;                      ///< A_bb
  std::vector<Eigen::MatrixXd> border_to_block;  ///< A_bk: n_b x m (border rows, block columns)
  std::vector<Eigen::MatrixXd> block_to_border;  ///< A_kb: m x n_b
  std::vector<Eigen::MatrixXd> block;            ///< D_k: m x m

 private:
  int border_size_ = 0, block_count_ = 0, block_size_ = 0;
};

/// Block-elimination LU of a BorderedMatrix.
class BorderedFactorization {
 public:
  /// Factors M. Returns false if a block or the Schur complement is singular.
  bool factor(const BorderedMatrix& m);
  /// Solves M x = b (x and b may alias).
  void solve(const double* b, double* x) const;

 private:
  const BorderedMatrix* m_ = nullptr;
  std::vector<Eigen::PartialPivLU<Eigen::MatrixXd>> block_lu_;
  std::vector<Eigen::MatrixXd> block_inv_border_;  ///< D_k^-1 A_kb
  Eigen::PartialPivLU<Eigen::MatrixXd> schur_lu_;
  mutable Eigen::VectorXd work_b_, work_x_, work_product_;
  mutable std::vector<Eigen::VectorXd> work_y_;  ///< D_k^-1 b_k of a solve
};

}  // namespace raceway::numerics
