#include "solver/numerics/bordered_matrix.hpp"

#include <cmath>
#include <stdexcept>

namespace raceway::numerics {

BorderedMatrix::BorderedMatrix(int border_size, int block_count, int block_size)
    : border(Eigen::MatrixXd::Zero(border_size, border_size)),
      border_to_block(block_count, Eigen::MatrixXd::Zero(border_size, block_size)),
      block_to_border(block_count, Eigen::MatrixXd::Zero(block_size, border_size)),
      block(block_count, Eigen::MatrixXd::Zero(block_size, block_size)),
      border_size_(border_size),
      block_count_(block_count),
      block_size_(block_size) {}

void BorderedMatrix::set_zero() {
  border.setZero();
  for (int k = 0; k < block_count_; ++k) {
    border_to_block[k].setZero();
    block_to_border[k].setZero();
    block[k].setZero();
  }
}

void BorderedMatrix::add(int row, int col, double v) {
  const int nb = border_size_, m = block_size_;
  if (row < nb && col < nb) {
    border(row, col) += v;
  } else if (row < nb) {
    border_to_block[(col - nb) / m](row, (col - nb) % m) += v;
  } else if (col < nb) {
    block_to_border[(row - nb) / m]((row - nb) % m, col) += v;
  } else {
    const int k = (row - nb) / m;
    if ((col - nb) / m != k) throw std::logic_error("BorderedMatrix: entry couples two blocks");
    block[k]((row - nb) % m, (col - nb) % m) += v;
  }
}

double BorderedMatrix::get(int row, int col) const {
  const int nb = border_size_, m = block_size_;
  if (row < nb && col < nb) return border(row, col);
  if (row < nb) return border_to_block[(col - nb) / m](row, (col - nb) % m);
  if (col < nb) return block_to_border[(row - nb) / m]((row - nb) % m, col);
  const int k = (row - nb) / m;
  return (col - nb) / m == k ? block[k]((row - nb) % m, (col - nb) % m) : 0.0;
}

void BorderedMatrix::scale_add_identity(double c) {
  border *= c;
  border.diagonal().array() += 1.0;
  for (int k = 0; k < block_count_; ++k) {
    border_to_block[k] *= c;
    block_to_border[k] *= c;
    block[k] *= c;
    block[k].diagonal().array() += 1.0;
  }
}

void BorderedMatrix::multiply(const double* x, double* y) const {
  const int nb = border_size_, m = block_size_;
  Eigen::Map<const Eigen::VectorXd> xb(x, nb);
  Eigen::Map<Eigen::VectorXd> yb(y, nb);
  yb = border * xb;
  for (int k = 0; k < block_count_; ++k) {
    Eigen::Map<const Eigen::VectorXd> xk(x + nb + k * m, m);
    Eigen::Map<Eigen::VectorXd> yk(y + nb + k * m, m);
    yb += border_to_block[k] * xk;
    yk = block_to_border[k] * xb + block[k] * xk;
  }
}

Eigen::MatrixXd BorderedMatrix::to_dense() const {
  const int nb = border_size_, m = block_size_;
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(size(), size());
  d.topLeftCorner(nb, nb) = border;
  for (int k = 0; k < block_count_; ++k) {
    d.block(0, nb + k * m, nb, m) = border_to_block[k];
    d.block(nb + k * m, 0, m, nb) = block_to_border[k];
    d.block(nb + k * m, nb + k * m, m, m) = block[k];
  }
  return d;
}

namespace {
bool usable(const Eigen::PartialPivLU<Eigen::MatrixXd>& lu) {
  const auto& u = lu.matrixLU();
  if (u.rows() == 0) return true;
  const double scale = u.cwiseAbs().maxCoeff();
  for (int i = 0; i < u.rows(); ++i)
    if (!(std::abs(u(i, i)) > 1e-14 * scale)) return false;
  return true;
}
}  // namespace

bool BorderedFactorization::factor(const BorderedMatrix& m) {
  m_ = &m;
  const int n = m.block_count();
  block_lu_.resize(n);
  block_inv_border_.resize(n);
  Eigen::MatrixXd schur = m.border;
  for (int k = 0; k < n; ++k) {
    block_lu_[k].compute(m.block[k]);
    if (!usable(block_lu_[k])) return false;
    // Without a border there is nothing to solve for; Eigen's triangular solve of a 0-column
    // right-hand side would still bind a reference to its element (0, 0) (undefined behaviour).
    if (m.border_size() == 0) {
      block_inv_border_[k].resize(m.block[k].rows(), 0);
      continue;
    }
    block_inv_border_[k] = block_lu_[k].solve(m.block_to_border[k]);
    schur.noalias() -= m.border_to_block[k] * block_inv_border_[k];
  }
  schur_lu_.compute(schur);
  work_b_.resize(m.border_size());
  return usable(schur_lu_);
}

void BorderedFactorization::solve(const double* b, double* x) const {
  const BorderedMatrix& m = *m_;
  const int nb = m.border_size(), bs = m.block_size(), n = m.block_count();
  // Forward: y_k = D_k^-1 b_k; border right-hand side b_b - sum A_bk y_k.
  // The work vectors keep their sizes between calls (no allocation per solve); each product is
  // evaluated into its own vector as Eigen evaluates it into a temporary: the same bits.
  work_b_ = Eigen::Map<const Eigen::VectorXd>(b, nb);
  work_y_.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    Eigen::VectorXd& y = work_y_[static_cast<std::size_t>(k)];
    y = block_lu_[k].solve(Eigen::Map<const Eigen::VectorXd>(b + nb + k * bs, bs));
    work_b_.noalias() -= m.border_to_block[k] * y;
  }
  work_x_ = schur_lu_.solve(work_b_);
  Eigen::Map<Eigen::VectorXd>(x, nb) = work_x_;
  // Back: x_k = y_k - D_k^-1 A_kb x_b.
  for (int k = 0; k < n; ++k) {
    work_product_.noalias() = block_inv_border_[k] * work_x_;
    Eigen::Map<Eigen::VectorXd>(x + nb + k * bs, bs) = work_y_[static_cast<std::size_t>(k)] - work_product_;
  }
}

}  // namespace raceway::numerics
