// The sundials-dense backend, the baseline: SUNDIALS' dense matrix and dense LU of the whole Newton
// matrix, O(N^3) per factorisation.
#include <sundials/sundials_linearsolver.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "solver/numerics/backend_factories.hpp"

namespace raceway::numerics::backend {

NewtonObjects create_sundials_dense(SUNContext ctx, N_Vector y, const BorderedLayout& layout) {
  const auto n = static_cast<sunindextype>(layout.size());
  NewtonObjects o;
  o.matrix = SUNDenseMatrix(n, n, ctx);
  o.solver = SUNLinSol_Dense(y, o.matrix, ctx);
  return o;
}

void load_dense(const BorderedMatrix& j, SUNMatrix a) {
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
}

}  // namespace raceway::numerics::backend
