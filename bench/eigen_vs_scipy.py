"""The scipy peer of examples/eigen_bench.rs: the lowest COUNT modes of the exported K, M by
scipy.sparse.linalg.eigsh in shift-invert mode (sigma = 0), REPEAT runs, median time, peak
resident memory, and both solvers' frequencies against the analytic cantilever ones.

python bench/eigen_vs_scipy.py DIR COUNT REPEAT OURS_FREQUENCIES..."""
import math
import resource
import sys
import time

import numpy as np
import scipy.io
import scipy.optimize
import scipy.sparse.linalg

E, RHO, AREA, I2, LENGTH = 2.1e11, 7850.0, 2.4e-3, 3.2e-7, 1.0


def analytic(count):
    """Roots of cos(bL) cosh(bL) = -1, as frequencies of the 1 m cantilever."""
    out = []
    for n in range(1, count + 1):
        guess = (n - 0.5) * math.pi
        bl = scipy.optimize.brentq(lambda x: math.cos(x) * math.cosh(x) + 1.0,
                                   guess - 0.5, guess + 0.5) if n < 8 else guess
        b = bl / LENGTH
        out.append(math.sqrt(b**4 * E * I2 / (RHO * AREA)) / (2 * math.pi))
    return np.array(out)


def main():
    directory, count, repeat = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    ours = np.array([float(v) for v in sys.argv[4:]])
    k = scipy.io.mmread(f"{directory}/k.mtx").tocsc()
    m = scipy.io.mmread(f"{directory}/m.mtx").tocsc()
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        values, _ = scipy.sparse.linalg.eigsh(k, k=count, M=m, sigma=0.0, which="LM")
        times.append(time.perf_counter() - t)
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    theirs = np.sqrt(np.maximum(np.sort(values), 0.0)) / (2 * math.pi)
    exact = analytic(count)
    print(f"scipy {scipy.__version__}: median {np.median(times):.3f} s of {repeat}, "
          f"peak RSS {peak:.0f} MB ({before:.0f} MB before the solves)")
    print("mode  analytic_hz  jointid_rel_err  scipy_rel_err")
    for i in range(min(count, 8)):
        print(f"{i + 1:4d} {exact[i]:12.6f} {abs(ours[i] - exact[i]) / exact[i]:16.2e}"
              f" {abs(theirs[i] - exact[i]) / exact[i]:14.2e}")
    print("largest |jointid - scipy| / scipy over all modes:",
          f"{np.max(np.abs(ours - theirs) / theirs):.2e}")


main()
