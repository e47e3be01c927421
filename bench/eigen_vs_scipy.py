"""The scipy peer of `examples/eigen_bench.rs solve`: the lowest RIGID + COUNT pairs of the
exported K, M by scipy.sparse.linalg.eigsh in shift-invert mode at the shift jointid uses
(case.txt; 0 for a cantilever), with one of three factorisations of K - sigma M:

  superlu   eigsh's own (SuperLU, COLAMD column ordering)
  mmd       SuperLU with the symmetric minimum-degree ordering MMD_AT_PLUS_A
  banded    LAPACK's banded Cholesky (scipy.linalg.cholesky_banded), for a banded matrix

Prints the solve time (the factorisation included, the reading of the files not), the
frequencies and per elastic mode the relative residual ||K y - lambda M y|| / ||K y||
(plain double precision products).

python bench/eigen_vs_scipy.py DIR COUNT VARIANT"""
import math
import sys
import time

import numpy as np
import scipy.io
import scipy.linalg
import scipy.sparse
import scipy.sparse.linalg as sla

# A banded factor above this many bytes is not tried (the machine has some GB to share).
BANDED_LIMIT = 4e9


def operator(a, variant):
    """(K - sigma M)^-1 as a LinearOperator, or None for eigsh's own."""
    n = a.shape[0]
    if variant == "superlu":
        return None
    if variant == "mmd":
        lu = sla.splu(a.tocsc(), permc_spec="MMD_AT_PLUS_A",
                      options={"SymmetricMode": True}, diag_pivot_thresh=0.0)
        return sla.LinearOperator((n, n), matvec=lu.solve, dtype=float)
    if variant == "banded":
        coo = a.tocoo()
        width = int(np.max(np.abs(coo.row - coo.col)))
        if 8.0 * (width + 1) * n > BANDED_LIMIT:
            raise MemoryError(f"band {width} too wide")
        band = np.zeros((width + 1, n))
        lower = coo.row >= coo.col
        band[(coo.row - coo.col)[lower], coo.col[lower]] = coo.data[lower]
        factor = scipy.linalg.cholesky_banded(band, lower=True, check_finite=False)
        return sla.LinearOperator(
            (n, n), matvec=lambda x: scipy.linalg.cho_solve_banded(
                (factor, True), x, check_finite=False), dtype=float)
    raise ValueError(variant)


def main():
    directory, count, variant = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    case = dict(line.split() for line in open(f"{directory}/case.txt"))
    rigid, shift = int(case["rigid"]), float(case["shift"]) if case["rigid"] != "0" else 0.0
    k = scipy.io.mmread(f"{directory}/k.mtx").tocsc()
    m = scipy.io.mmread(f"{directory}/m.mtx").tocsc()
    t = time.perf_counter()
    try:
        op = operator((k - shift * m).tocsc(), variant)
    except MemoryError as e:
        print(f"skipped {e}")
        return
    values, vectors = sla.eigsh(k, k=rigid + count, M=m, sigma=shift, which="LM", OPinv=op)
    seconds = time.perf_counter() - t
    order = np.argsort(values)
    values, vectors = values[order], vectors[:, order]
    print(f"time_s {seconds:.4f}")
    for j in range(rigid, rigid + count):
        y = vectors[:, j]
        ky = k @ y
        r = np.linalg.norm(ky - values[j] * (m @ y)) / np.linalg.norm(ky)
        hz = math.sqrt(max(values[j], 0.0)) / (2 * math.pi)
        print(f"mode {j - rigid + 1} hz {hz:.9f} relative_residual {r:.2e}")


main()
