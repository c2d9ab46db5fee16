"""Factor the symmetric positive-definite matrices of a Laplace fit: solve and log det."""

import numpy as np
from scipy import linalg, sparse
from scipy.sparse import linalg as sparse_linalg

# Above this many random-effect columns the q × q matrices are factored sparse (SuperLU
# with a fill-reducing order): a dense Cholesky grows as q³ (q = 5,000: seconds a step).
DENSE_UP_TO = 1500


class Factor:
    """Solve with, and take the log-determinant of, a symmetric positive-definite matrix."""

    def __init__(self, matrix):
        if sparse.issparse(matrix):
            self.lu = sparse_linalg.splu(
                matrix.tocsc(),
                permc_spec="MMD_AT_PLUS_A",
                diag_pivot_thresh=0.0,
                options={"SymmetricMode": True},
            )
            self.logdet = float(np.log(np.abs(self.lu.U.diagonal())).sum())
            self.solve = self.lu.solve
        else:
            factor = linalg.cho_factor(matrix, lower=True, check_finite=False)
            self.logdet = float(2 * np.log(np.diag(factor[0])).sum())
            self.solve = lambda rhs: linalg.cho_solve(factor, rhs, check_finite=False)
