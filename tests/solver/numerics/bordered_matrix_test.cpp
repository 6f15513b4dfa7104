// BorderedMatrix and BorderedFactorization against Eigen's dense LU of the same matrix: the
// block-elimination (Schur complement) solve, the product, M = c M + I, and the structure check;
// blocks of 5 (the dense elimination) and 9 (the fixed-size one that skips zero couplings), each
// block coupled to its own subset of the border.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "solver/numerics/bordered_matrix.hpp"

namespace raceway::numerics {
namespace {

constexpr int block_size = 5;

/// A random bordered matrix: entries in [-1, 1], diagonally dominant blocks and border so that the
/// blocks and the Schur complement are well conditioned (the Newton matrices I - gamma J are), filled
/// through add() one entry at a time. Block k's border rows r with (r + k) % 3 == 1 and border
/// columns c with (c + k) % 2 == 1 (but column 0) are left zero, as a rolling element touches only
/// some of the border's states.
BorderedMatrix random_bordered(int border, int blocks, int bs, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  BorderedMatrix m(border, blocks, bs);
  const int n = m.size();
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      const bool r_border = r < border, c_border = c < border;
      const int k = r_border ? (c - border) / bs : (r - border) / bs;
      const bool same_block = !r_border && !c_border && (r - border) / bs == (c - border) / bs;
      const bool coupled = r_border != c_border &&
                           (r_border ? (r + k) % 3 != 1 : (c == 0 || (c + k) % 2 != 1));
      if ((r_border && c_border) || coupled || same_block) m.add(r, c, u(rng));
    }
  }
  // Diagonal shift: enough to dominate a block row (bs + border entries of size <= 1) but
  // leaving the border coupling strong, so that a wrong Schur complement changes the solution.
  for (int r = 0; r < n; ++r) m.add(r, r, 2.0 + bs + 0.5 * border);
  return m;
}

class BorderedSolve : public ::testing::TestWithParam<std::tuple<int, int, int>> {};

TEST_P(BorderedSolve, MatchesDenseLU) {
  const auto [border, blocks, bs] = GetParam();
  std::mt19937 rng(1234u + static_cast<unsigned>(border * 100 + blocks));
  const BorderedMatrix m = random_bordered(border, blocks, bs, rng);
  const Eigen::MatrixXd dense = m.to_dense();
  const int n = m.size();
  ASSERT_EQ(dense.rows(), n);

  // to_dense() keeps what get() reports and is zero between different blocks.
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      ASSERT_EQ(dense(r, c), m.get(r, c)) << r << "," << c;
      if (r >= border && c >= border && (r - border) / bs != (c - border) / bs) {
        ASSERT_EQ(dense(r, c), 0.0);
      }
    }

  BorderedFactorization f;
  ASSERT_TRUE(f.factor(m));
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(dense);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int rep = 0; rep < 3; ++rep) {
    Eigen::VectorXd b(n);
    for (int i = 0; i < n; ++i) b[i] = u(rng);
    const Eigen::VectorXd expected = lu.solve(b);
    Eigen::VectorXd x(n);
    f.solve(b.data(), x.data());
    EXPECT_LE((x - expected).norm(), 1e-12 * expected.norm()) << "border " << border << ", blocks " << blocks;
    // In-place (x and b alias).
    Eigen::VectorXd y = b;
    f.solve(y.data(), y.data());
    EXPECT_LE((y - expected).norm(), 1e-12 * expected.norm()) << "aliased solve";
    // And it is a solution: residual of the original matrix.
    EXPECT_LE((dense * x - b).norm(), 1e-12 * b.norm());
  }

  // multiply() against the dense product.
  Eigen::VectorXd x(n), y(n);
  for (int i = 0; i < n; ++i) x[i] = u(rng);
  m.multiply(x.data(), y.data());
  const Eigen::VectorXd yd = dense * x;
  EXPECT_LE((y - yd).norm(), 1e-13 * yd.norm());

  // scale_add_identity: c M + I, entry by entry, and the factorisation of the result.
  BorderedMatrix s = m;
  const double c = -0.37;
  s.scale_add_identity(c);
  const Eigen::MatrixXd expected_s = c * dense + Eigen::MatrixXd::Identity(n, n);
  EXPECT_LE((s.to_dense() - expected_s).cwiseAbs().maxCoeff(), 1e-15 * dense.cwiseAbs().maxCoeff() + 1e-15);
  BorderedFactorization fs;
  if (fs.factor(s)) {
    Eigen::VectorXd b = Eigen::VectorXd::Ones(n);
    Eigen::VectorXd xs(n);
    fs.solve(b.data(), xs.data());
    const Eigen::VectorXd ref = expected_s.partialPivLu().solve(b);
    EXPECT_LE((xs - ref).norm(), 1e-10 * ref.norm());
  }
}

INSTANTIATE_TEST_SUITE_P(BordersAndBlocks, BorderedSolve,
                         ::testing::Combine(::testing::Values(0, 1, 6, 10), ::testing::Values(1, 5, 13, 64),
                                            ::testing::Values(5, 9)),
                         [](const ::testing::TestParamInfo<std::tuple<int, int, int>>& p) {
                           return "border" + std::to_string(std::get<0>(p.param)) + "_blocks" +
                                  std::to_string(std::get<1>(p.param)) + "_size" + std::to_string(std::get<2>(p.param));
                         });

TEST(BorderedMatrix, AddRejectsEntryCouplingTwoBlocks) {
  BorderedMatrix m(6, 13, block_size);
  const int b0 = 6, b1 = 6 + block_size, last = 6 + 12 * block_size;
  EXPECT_THROW(m.add(b0, b1, 1.0), std::logic_error);
  EXPECT_THROW(m.add(b1 + 4, b0 + 4, 1.0), std::logic_error);
  EXPECT_THROW(m.add(last, b0, 1.0), std::logic_error);
  // Within a block, and block-border couplings, are accepted and land where get() says.
  EXPECT_NO_THROW(m.add(b1, b1 + 4, 2.0));
  EXPECT_NO_THROW(m.add(b1, 5, 3.0));
  EXPECT_NO_THROW(m.add(0, last + 4, 4.0));
  EXPECT_EQ(m.get(b1, b1 + 4), 2.0);
  EXPECT_EQ(m.get(b1, 5), 3.0);
  EXPECT_EQ(m.get(0, last + 4), 4.0);
  EXPECT_EQ(m.get(b0, b1), 0.0);
  // A rejected entry left the matrix unchanged.
  const Eigen::MatrixXd d = m.to_dense();
  EXPECT_EQ(d.cwiseAbs().sum(), 9.0);
}

TEST(BorderedMatrix, FactorReportsSingularBlock) {
  // A zero roller block (singular) must be reported, not solved into NaNs (both eliminations).
  for (const int size : {block_size, 9}) {
    BorderedMatrix m(2, 3, size);
    for (int r = 0; r < m.size(); ++r)
      if (r < 2 || r >= 2 + size) m.add(r, r, 1.0);
    BorderedFactorization f;
    EXPECT_FALSE(f.factor(m)) << size;
  }
}

// copy_values: every value of the source, in a matrix of the same layout (copied in place, its
// storage kept) and in one of another layout or a default one (assigned).
TEST(BorderedMatrix, CopyValuesCopiesEveryValue) {
  std::mt19937 rng(99u);
  const BorderedMatrix from = random_bordered(6, 5, 9, rng);
  BorderedMatrix same = random_bordered(6, 5, 9, rng), other(2, 3, 5), empty;
  const double* storage = same.block[4].data();
  for (BorderedMatrix* to : {&same, &other, &empty}) {
    to->copy_values(from);
    ASSERT_EQ(to->size(), from.size());
    EXPECT_EQ(to->border_size(), 6);
    EXPECT_EQ(to->block_count(), 5);
    EXPECT_EQ(to->to_dense(), from.to_dense());
  }
  EXPECT_EQ(same.block[4].data(), storage);
}

}  // namespace
}  // namespace raceway::numerics
