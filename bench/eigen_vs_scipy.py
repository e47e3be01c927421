"""The scipy peer of `examples/eigen_bench.rs solve`: the lowest RIGID + COUNT pairs of the
exported K, M by scipy.sparse.linalg.eigsh in shift-invert mode at the shift jointid uses
(case.txt; 0 for a cantilever), with one of three factorisations of K - sigma M:

  superlu   eigsh's own (SuperLU, COLAMD column ordering)
  mmd       SuperLU with the symmetric minimum-degree ordering MMD_AT_PLUS_A
  banded    LAPACK's banded Cholesky (scipy.linalg.cholesky_banded), for a banded matrix

Prints the solve time (the factorisation included, the reading of the files not), the
frequencies and per elastic mode the relative residual ||K y - lambda M y|| / ||K y||
(plain double precision products).

With MODEL and OUT, the whole process that `jointid simulate --model MODEL/model.toml
--modes COUNT --out X.csv` is timed against: the external model's own files are read (K.mtx,
M.mtx and every dK/dp, dM/dp of model.toml, by scipy.io.mmread, its fast_matrix_market
reader on as many threads as OMP_NUM_THREADS), K(p) = K + sum p dK/dp and M(p) assembled,
solved as above (the shift of DIR/case.txt, a constant given beforehand), and the modes
written to OUT (np.savetxt: one line per DOF, a column per mode, the frequencies in the
header); the reading and writing times are printed beside the solve's.

python bench/eigen_vs_scipy.py DIR COUNT VARIANT [MODEL OUT]"""
import math
import os
import sys
import time
import tomllib

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


def read_model(model):
    """K(p) and M(p) of the external model in the folder `model`, as jointid assembles them."""
    with open(f"{model}/model.toml", "rb") as f:
        spec = tomllib.load(f)
    k = scipy.io.mmread(f"{model}/{spec['stiffness']}").tocsc()
    m = scipy.io.mmread(f"{model}/{spec['mass']}").tocsc()
    for p in spec["parameter"]:
        k = k + p["value"] * scipy.io.mmread(f"{model}/{p['dk']}").tocsc()
        if "dm" in p:
            m = m + p["value"] * scipy.io.mmread(f"{model}/{p['dm']}").tocsc()
    return k.tocsc(), m.tocsc()


def main():
    directory, count, variant = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    whole = sys.argv[4:6] if len(sys.argv) >= 6 else None
    threads = os.environ.get("OMP_NUM_THREADS")
    if threads:
        import scipy.io._fast_matrix_market as fmm
        fmm.PARALLELISM = int(threads)
    case = dict(line.split() for line in open(f"{directory}/case.txt"))
    rigid, shift = int(case["rigid"]), float(case["shift"]) if case["rigid"] != "0" else 0.0
    t = time.perf_counter()
    if whole:
        k, m = read_model(whole[0])
    else:
        k = scipy.io.mmread(f"{directory}/k.mtx").tocsc()
        m = scipy.io.mmread(f"{directory}/m.mtx").tocsc()
    print(f"read_s {time.perf_counter() - t:.4f}")
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
    if whole:
        t = time.perf_counter()
        hz = np.sqrt(np.maximum(values, 0.0)) / (2 * math.pi)
        np.savetxt(whole[1], vectors[:, rigid:], fmt="%.17g", delimiter=",",
                   header="frequencies_hz " + ",".join(f"{f!r}" for f in hz[rigid:]))
        print(f"write_s {time.perf_counter() - t:.4f}")
    for j in range(rigid, rigid + count):
        y = vectors[:, j]
        ky = k @ y
        r = np.linalg.norm(ky - values[j] * (m @ y)) / np.linalg.norm(ky)
        hz = math.sqrt(max(values[j], 0.0)) / (2 * math.pi)
        print(f"mode {j - rigid + 1} hz {hz:.9f} relative_residual {r:.2e}")


main()
