#include "solver/numerics/bordered_matrix.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
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

void BorderedMatrix::copy_values(const BorderedMatrix& from) {
  if (border_size_ != from.border_size_ || block_count_ != from.block_count_ || block_size_ != from.block_size_ ||
      border.size() != from.border.size()) {
    *this = from;
    return;
  }
  // memcpy's wide moves: a quarter of the instructions of the matrices' element-wise assignment.
  const auto copy = [](const Eigen::MatrixXd& a, Eigen::MatrixXd& b) {
    std::memcpy(b.data(), a.data(), static_cast<std::size_t>(a.size()) * sizeof(double));
  };
  copy(from.border, border);
  for (int k = 0; k < block_count_; ++k) {
    copy(from.border_to_block[k], border_to_block[k]);
    copy(from.block_to_border[k], block_to_border[k]);
    copy(from.block[k], block[k]);
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
template <class Lu>
bool usable(const Lu& lu) {
  const auto& u = lu.matrixLU();
  if (u.rows() == 0) return true;
  const double scale = u.cwiseAbs().maxCoeff();
  for (int i = 0; i < u.rows(); ++i)
    if (!(std::abs(u(i, i)) > 1e-14 * scale)) return false;
  return true;
}

// The indices of the rows (columns = false) or columns of `a` that hold a nonzero (a NaN counts:
// it is != 0), each line read up to its first nonzero (a row across the column-major storage).
void nonzero_lines(const Eigen::MatrixXd& a, bool columns, std::vector<int>& out) {
  out.clear();
  const Eigen::Index rows = a.rows(), cols = a.cols();
  const double* v = a.data();
  if (columns) {
    for (Eigen::Index c = 0; c < cols; ++c, v += rows)
      if (std::any_of(v, v + rows, [](double x) { return x != 0.0; })) out.push_back(static_cast<int>(c));
    return;
  }
  for (Eigen::Index r = 0; r < rows; ++r) {
    const double* x = v + r;
    for (Eigen::Index c = 0; c < cols; ++c, x += rows)
      if (*x != 0.0) {
        out.push_back(static_cast<int>(r));
        break;
      }
  }
}

// x = A^-1 b from A's partial-pivoting LU (P A = L U, L unit lower): x = U^-1 L^-1 P b by
// substitution, in loops of the compile-time size N; `scratch` holds P b.
template <int N, class Lu, class In, class Out, class Scratch>
void lu_substitute(const Lu& lu, const In& b, Out&& x, Scratch& scratch) {
  const auto& f = lu.matrixLU();
  const auto& p = lu.permutationP().indices();
  for (int i = 0; i < N; ++i) scratch(p(i)) = b(i);
  for (int i = 1; i < N; ++i) {
    double s = scratch(i);
    for (int j = 0; j < i; ++j) s -= f(i, j) * scratch(j);
    scratch(i) = s;
  }
  for (int i = N - 1; i >= 0; --i) {
    double s = scratch(i);
    for (int j = i + 1; j < N; ++j) s -= f(i, j) * scratch(j);
    scratch(i) = s / f(i, i);
  }
  x = scratch;
}
}  // namespace

bool DenseBlocks::factor(const BorderedMatrix& m, Eigen::MatrixXd& schur) {
  const auto n = static_cast<std::size_t>(m.block_count());
  lu.resize(n);
  inv_border.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const int kb = static_cast<int>(k);
    lu[k].compute(m.block[kb]);
    if (!usable(lu[k])) return false;
    // Without a border there is nothing to solve for; Eigen's triangular solve of a 0-column
    // right-hand side would still bind a reference to its element (0, 0) (undefined behaviour).
    if (m.border_size() == 0) {
      inv_border[k].resize(m.block[kb].rows(), 0);
      continue;
    }
    inv_border[k] = lu[k].solve(m.block_to_border[kb]);
    schur.noalias() -= m.border_to_block[kb] * inv_border[k];
  }
  return true;
}

void DenseBlocks::forward(const BorderedMatrix& m, const double* b, Eigen::VectorXd& border) {
  const int nb = m.border_size(), bs = m.block_size(), n = m.block_count();
  // Each product is evaluated into its own vector as Eigen evaluates it into a temporary.
  y.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    Eigen::VectorXd& yk = y[static_cast<std::size_t>(k)];
    yk = lu[static_cast<std::size_t>(k)].solve(Eigen::Map<const Eigen::VectorXd>(b + nb + k * bs, bs));
    border.noalias() -= m.border_to_block[k] * yk;
  }
}

void DenseBlocks::back(const BorderedMatrix& m, const Eigen::VectorXd& border_x, double* x) {
  const int nb = m.border_size(), bs = m.block_size(), n = m.block_count();
  for (int k = 0; k < n; ++k) {
    const auto i = static_cast<std::size_t>(k);
    product.noalias() = inv_border[i] * border_x;
    Eigen::Map<Eigen::VectorXd>(x + nb + k * bs, bs) = y[i] - product;
  }
}

template <int Bs, bool KeepInverse>
bool SparseFixedBlocks<Bs, KeepInverse>::factor(const BorderedMatrix& m, Eigen::MatrixXd& schur) {
  elements.resize(static_cast<std::size_t>(m.block_count()));
  for (int k = 0; k < m.block_count(); ++k) {
    Element& e = elements[static_cast<std::size_t>(k)];
    lu.compute(Eigen::Map<const Block>(m.block[k].data()));
    if (!usable(lu)) return false;
    if constexpr (KeepInverse) {
      for (int j = 0; j < Bs; ++j) lu_substitute<Bs>(lu, Block::Identity().col(j), e.inverse.col(j), permuted);
    } else {
      e.factors = lu;
    }
    nonzero_lines(m.border_to_block[k], false, e.rows);
    nonzero_lines(m.block_to_border[k], true, e.cols);
    const auto r = static_cast<Eigen::Index>(e.rows.size()), c = static_cast<Eigen::Index>(e.cols.size());
    e.border_rows.resize(r, Bs);
    for (Eigen::Index i = 0; i < r; ++i) e.border_rows.row(i) = m.border_to_block[k].row(e.rows[static_cast<std::size_t>(i)]);
    e.inv_border.resize(Bs, c);
    for (Eigen::Index j = 0; j < c; ++j) {
      gathered = m.block_to_border[k].col(e.cols[static_cast<std::size_t>(j)]);
      if constexpr (KeepInverse) {
        e.inv_border.col(j).noalias() = e.inverse.lazyProduct(gathered);
      } else {
        lu_substitute<Bs>(e.factors, gathered, e.inv_border.col(j), permuted);
      }
      for (Eigen::Index i = 0; i < r; ++i)
        schur(e.rows[static_cast<std::size_t>(i)], e.cols[static_cast<std::size_t>(j)]) -=
            e.border_rows.row(i).dot(e.inv_border.col(j));
    }
  }
  return true;
}

template <int Bs, bool KeepInverse>
void SparseFixedBlocks<Bs, KeepInverse>::forward(const BorderedMatrix& m, const double* b, Eigen::VectorXd& border) {
  const int nb = m.border_size();
  for (int k = 0; k < m.block_count(); ++k) {
    Element& e = elements[static_cast<std::size_t>(k)];
    const Eigen::Map<const BlockVector> b_k(b + nb + k * Bs);
    if constexpr (KeepInverse) {
      e.y.noalias() = e.inverse.lazyProduct(b_k);
    } else {
      lu_substitute<Bs>(e.factors, b_k, e.y, permuted);
    }
    for (std::size_t i = 0; i < e.rows.size(); ++i)
      border(e.rows[i]) -= e.border_rows.row(static_cast<Eigen::Index>(i)).dot(e.y);
  }
}

template <int Bs, bool KeepInverse>
void SparseFixedBlocks<Bs, KeepInverse>::back(const BorderedMatrix& m, const Eigen::VectorXd& border_x, double* x) {
  const int nb = m.border_size();
  for (int k = 0; k < m.block_count(); ++k) {
    const Element& e = elements[static_cast<std::size_t>(k)];
    BlockVector product = BlockVector::Zero();
    for (std::size_t j = 0; j < e.cols.size(); ++j)
      product += e.inv_border.col(static_cast<Eigen::Index>(j)) * border_x(e.cols[j]);
    Eigen::Map<BlockVector>(x + nb + k * Bs) = e.y - product;
  }
}

template struct SparseFixedBlocks<5, false>;
template struct SparseFixedBlocks<9, true>;

bool BorderedFactorization::factor(const BorderedMatrix& m) {
  m_ = &m;
  Eigen::MatrixXd schur = m.border;
  const bool blocks_usable = with_blocks([&](auto& blocks) { return blocks.factor(m, schur); });
  if (!blocks_usable) return false;
  schur_lu_.compute(schur);
  work_b_.resize(m.border_size());
  return usable(schur_lu_);
}

void BorderedFactorization::solve(const double* b, double* x) const {
  const BorderedMatrix& m = *m_;
  const int nb = m.border_size();
  // Forward: y_k = D_k^-1 b_k; border right-hand side b_b - sum A_bk y_k. The work vectors keep
  // their sizes between calls (no allocation per solve).
  work_b_ = Eigen::Map<const Eigen::VectorXd>(b, nb);
  with_blocks([&](auto& blocks) { blocks.forward(m, b, work_b_); });
  work_x_ = schur_lu_.solve(work_b_);
  Eigen::Map<Eigen::VectorXd>(x, nb) = work_x_;
  // Back: x_k = y_k - D_k^-1 A_kb x_b.
  with_blocks([&](auto& blocks) { blocks.back(m, work_x_, x); });
}

}  // namespace raceway::numerics
