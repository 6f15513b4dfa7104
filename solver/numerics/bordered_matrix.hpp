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
  /// this = from: the values copied straight into this matrix's storage where the two have one
  /// layout (CVODE copies the saved Jacobian at every linear setup), assigned otherwise.
  void copy_values(const BorderedMatrix& from);
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

/// The rolling elements' part of a block elimination, any block size: dense products with A_bk
/// and A_kb, the blocks' LU solves.
struct DenseBlocks {
  /// Factors every D_k and subtracts A_bk D_k^-1 A_kb from `schur`; false if a block is singular.
  bool factor(const BorderedMatrix& m, Eigen::MatrixXd& schur);
  /// y_k = D_k^-1 b_k and border -= A_bk y_k (b: the whole right-hand side).
  void forward(const BorderedMatrix& m, const double* b, Eigen::VectorXd& border);
  /// x_k = y_k - D_k^-1 A_kb x_b.
  void back(const BorderedMatrix& m, const Eigen::VectorXd& border_x, double* x);

  std::vector<Eigen::PartialPivLU<Eigen::MatrixXd>> lu;
  std::vector<Eigen::MatrixXd> inv_border;  ///< D_k^-1 A_kb
  std::vector<Eigen::VectorXd> y;           ///< D_k^-1 b_k of a solve
  Eigen::VectorXd product;                  ///< D_k^-1 A_kb x_b of a solve
};

/// The same for blocks of Bs x Bs known at compile time (the ball bearings' 9 x 9, the planar
/// rollers' 5 x 5), with fewer operations. A rolling element couples to a few border states only (a
/// ball: 5-8 of the 28 border rates depend on it, it depends on 10-16 border states): the exactly
/// zero rows of A_bk and columns of A_kb, found at each factorisation, are left out of the Schur
/// complement's update and of the solves. With `KeepInverse`, D_k^-1 is kept (from its LU, by
/// substitution), so that a block's solve is one fixed-size product, which the compiler unrolls
/// (the balls' blocks); without, each solve substitutes through the block's LU (the planar rollers':
/// a light roller on a stiff contact makes an ill-conditioned block, and with the explicit inverse
/// seed 002 without gravity took 4,904 steps over 0.15 s against 3,805 with the dense kernels, its
/// unloaded rollers no longer riding steadily on the outer race; substituting, 3,025 steps and the
/// steady ride). Round-off differs from DenseBlocks' (other sums in another order).
template <int Bs, bool KeepInverse>
struct SparseFixedBlocks {
  using Block = Eigen::Matrix<double, Bs, Bs>;
  using BlockVector = Eigen::Matrix<double, Bs, 1>;
  struct Element {
    Block inverse;                ///< D_k^-1 (KeepInverse)
    Eigen::PartialPivLU<Block> factors;  ///< D_k's LU (without KeepInverse)
    std::vector<int> rows, cols;  ///< the border rows of A_bk, columns of A_kb that are not zero
    Eigen::Matrix<double, Eigen::Dynamic, Bs> border_rows;  ///< A_bk(rows, :)
    Eigen::Matrix<double, Bs, Eigen::Dynamic> inv_border;   ///< D_k^-1 A_kb(:, cols)
    BlockVector y;                                          ///< D_k^-1 b_k of a solve
  };
  bool factor(const BorderedMatrix& m, Eigen::MatrixXd& schur);
  void forward(const BorderedMatrix& m, const double* b, Eigen::VectorXd& border);
  void back(const BorderedMatrix& m, const Eigen::VectorXd& border_x, double* x);

  std::vector<Element> elements;
  Eigen::PartialPivLU<Block> lu;       ///< of the block being factored
  BlockVector gathered, permuted;      ///< scratch
};

/// Block-elimination LU of a BorderedMatrix.
class BorderedFactorization {
 public:
  /// Factors M. Returns false if a block or the Schur complement is singular.
  bool factor(const BorderedMatrix& m);
  /// Solves M x = b (x and b may alias).
  void solve(const double* b, double* x) const;

 private:
  /// Calls f with the blocks' kernel for this matrix's block size: fixed-size where one is compiled
  /// (the ball's 9 states, the planar roller's 5), the dense one otherwise.
  template <class F>
  decltype(auto) with_blocks(F&& f) const {
    switch (m_->block_size()) {
      case 5: return f(fixed5_);
      case 9: return f(fixed9_);
      default: return f(dense_blocks_);
    }
  }
  const BorderedMatrix* m_ = nullptr;
  mutable DenseBlocks dense_blocks_;
  mutable SparseFixedBlocks<5, false> fixed5_;
  mutable SparseFixedBlocks<9, true> fixed9_;
  Eigen::PartialPivLU<Eigen::MatrixXd> schur_lu_;
  mutable Eigen::VectorXd work_b_, work_x_;
};

}  // namespace raceway::numerics
