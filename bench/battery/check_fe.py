"""Checks of the battery's finite elements (fe.py) against solutions that share nothing with them.

Independence: the references are (1) the analytic roots of cos(bL) cosh(bL) = 1 of a
free-free Euler-Bernoulli beam (Blevins, "Formulas for Natural Frequency and Mode Shape",
table 8-1: 4.730, 7.853, 10.996, ...), (2) the frequencies of paper case I printed in jointid's
README worked example (150.054, 655.524, 2411.608, 5356.350 Hz), and (3) an exact
continuous solution of the beam ODEs by transfer matrices (matrix exponential per segment,
point matrices for joints, masses and springs), solved as one multiple-shooting system: no
elements, no shape functions. The FE code was not written from jointid's sources.

Run: ``$(bash scripts/python-env.sh) bench/battery/check_fe.py``; exit 1 on any failure.
"""

from __future__ import annotations

import copy
import sys
from pathlib import Path

import numpy as np
import scipy.linalg
import scipy.optimize

sys.path.insert(0, str(Path(__file__).resolve().parent))
import fe  # noqa: E402

FAILURES: list[str] = []


def check(name: str, got: float, want: float, rtol: float) -> None:
    err = abs(got - want) / abs(want)
    ok = err <= rtol
    print(f"{'ok  ' if ok else 'FAIL'} {name}: {got:.9g} vs {want:.9g} (rel. err {err:.2e}, tol {rtol:.0e})")
    if not ok:
        FAILURES.append(name)


# ---------------------------------------------------------------- exact solution (transfer matrices)
# State z = (w, psi, M, V) with M = EI psi', V the shear force (Timoshenko: V = kappa G A (w' - psi)):
#   w' = psi + V / (kappa G A),  psi' = M / EI,  M' = -V - rho I w^2 psi,  V' = -rho A w^2 w.
# Euler-Bernoulli: 1 / (kappa G A) = 0 and rho I = 0. Across a joint (springs k1, k2, k12):
# [V, M] = C [dw, dpsi]; at a point mass m, J and grounded spring k: dV = (k - m w^2) w, dM = -J w^2 psi.


def segments_of(chain: fe.Chain):
    """The chain as exact segments (length, EI, rho A, 1/kGA, rho I) and point matrices between them,
    split at every element boundary (where masses and springs sit) and every piece boundary."""
    segs = []  # (length, ei, rho_a, shear_flex, rho_i)
    stations = []  # station s sits before segment s; one more after the last segment
    for bi, b in enumerate(chain.beams):
        node = chain.first_node(bi)
        l = b.length / b.elements
        ei = b.youngs_modulus * b.second_moment
        rho_a = b.density * b.area
        flex, rho_i = 0.0, 0.0
        if b.timoshenko:
            g = b.youngs_modulus / (2 * (1 + b.poisson))
            flex, rho_i = 1.0 / (b.kappa() * g * b.area), b.density * b.second_moment
        for e in range(b.elements):
            x0, x1 = e * l, (e + 1) * l
            inner = [p[i] for p in b.pieces for i in (0, 1) if x0 < p[i] < x1]
            cuts = sorted({x0, x1, *inner})
            for i, (a, c) in enumerate(zip(cuts[:-1], cuts[1:])):
                mid = 0.5 * (a + c)
                fe_, fm = 1.0, 1.0
                for s0, s1, pe, pm in b.pieces:
                    if s0 <= mid <= s1:
                        fe_, fm = pe, pm
                if i > 0:
                    stations.append(("none", None))
                elif e > 0 or bi == 0:
                    stations.append(("node", node + e))
                # else: the joint station before this beam is already there
                segs.append((c - a, fe_ * ei, fm * rho_a, flex / fe_ if flex else 0.0, rho_i * fm))
        last = chain.last_node(bi)
        stations.append(("joint", (last, bi)) if bi < len(chain.joints) else ("node", last))
    assert len(stations) == len(segs) + 1
    return segs, stations


def transfer(seg, om: float) -> np.ndarray:
    length, ei, rho_a, flex, rho_i = seg
    a = np.array(
        [
            [0.0, 1.0, 0.0, flex],
            [0.0, 0.0, 1.0 / ei, 0.0],
            [0.0, -rho_i * om * om, 0.0, -1.0],
            [-rho_a * om * om, 0.0, 0.0, 0.0],
        ]
    )
    return scipy.linalg.expm(a * length)


def attachment(chain: fe.Chain, node: int, om: float) -> np.ndarray:
    p = np.eye(4)
    for n, m, j in chain.masses:
        if n == node:
            p[3, 0] -= m * om * om
            p[2, 1] -= j * om * om
    for n, kw, kt in chain.springs:
        if n == node:
            p[3, 0] += kw
            p[2, 1] += kt
    return p


def point_matrices(chain: fe.Chain, stations, om: float) -> list:
    mats = []
    for kind, data in stations:
        if kind == "node":
            mats.append(attachment(chain, data, om))
        elif kind == "none":
            mats.append(np.eye(4))
        else:
            node, bi = data
            j = chain.joints[bi]
            c = np.array([[j.k1, j.k12], [j.k12, j.k2]])
            ci = np.linalg.inv(c)  # [dw, dpsi] = C^-1 [V, M]
            jm = np.eye(4)
            jm[0, 3], jm[0, 2] = ci[0, 0], ci[0, 1]
            jm[1, 3], jm[1, 2] = ci[1, 0], ci[1, 1]
            p = attachment(chain, node + 1, om) @ jm @ attachment(chain, node, om)
            mats.append(p)
    return mats


def shooting_det(chain: fe.Chain, om: float, segs, stations, scale) -> float:
    """Sign-preserving n-th root of the determinant of the multiple-shooting system."""
    mats = point_matrices(chain, stations, om)
    d = np.diag(scale)
    di = np.diag(1.0 / scale)
    s = len(segs)
    n = 4 * (s + 1)
    a = np.zeros((n, n))
    # u_s: state just before station s; after station s it is P_s u_s; u_{s+1} = T_s P_s u_s.
    a[0:2, 0:4] = np.eye(4)[2:4]
    row = 2
    for i, seg in enumerate(segs):
        g = di @ transfer(seg, om) @ mats[i] @ d
        a[row : row + 4, 4 * i : 4 * i + 4] = g
        a[row : row + 4, 4 * (i + 1) : 4 * (i + 1) + 4] = -np.eye(4)
        row += 4
    a[row : row + 2, 4 * s : 4 * s + 4] = (di @ mats[s] @ d)[2:4]
    sign, logdet = np.linalg.slogdet(a)
    return sign * np.exp(logdet / n)


def exact_frequencies(chain: fe.Chain, near: np.ndarray) -> np.ndarray:
    """Roots of the exact characteristic function, each bracketed around an FE estimate."""
    segs, stations = segments_of(chain)
    l0 = chain.beams[0].length
    ei0 = chain.beams[0].youngs_modulus * chain.beams[0].second_moment
    scale = np.array([l0, 1.0, ei0 / l0, ei0 / l0**2])
    out = []
    for f in near:
        fn = lambda x: shooting_det(chain, 2 * np.pi * x, segs, stations, scale)  # noqa: E731
        for width in (1e-4, 1e-3, 1e-2, 5e-2):
            lo, hi = f * (1 - width), f * (1 + width)
            if fn(lo) * fn(hi) < 0:
                out.append(scipy.optimize.brentq(fn, lo, hi, xtol=1e-12 * f, rtol=1e-14))
                break
        else:
            out.append(np.nan)
    return np.array(out)


def count_roots(chain: fe.Chain, f_max: float, points: int = 1500) -> int:
    segs, stations = segments_of(chain)
    l0 = chain.beams[0].length
    ei0 = chain.beams[0].youngs_modulus * chain.beams[0].second_moment
    scale = np.array([l0, 1.0, ei0 / l0, ei0 / l0**2])
    grid = np.geomspace(f_max * 1e-4, f_max, points)
    vals = np.array([shooting_det(chain, 2 * np.pi * x, segs, stations, scale) for x in grid])
    return int(np.sum(np.sign(vals[1:]) != np.sign(vals[:-1])))


def precise(chain: fe.Chain, r: int, count: int) -> np.ndarray:
    """Elastic frequencies of the chain refined r times, by shift-invert (see fe.modes)."""
    f0, _ = fe.elastic_modes(chain, 1)
    fine, _ = fe.refine(chain, r)
    f, _ = fe.elastic_modes(fine, count, shift=(2 * np.pi * f0[0]) ** 2)
    return f


# ---------------------------------------------------------------- the checks


def paper_case_1() -> fe.Chain:
    steel = dict(youngs_modulus=2.1e11, density=7850.0, area=2.4e-3, second_moment=3.2e-7)
    return fe.Chain(
        beams=[fe.Beam(length=0.20, elements=7, **steel), fe.Beam(length=0.30, elements=10, **steel)],
        joints=[fe.Joint(k1=1.0e7, k2=1.0e4)],
    )


def check_free_free_beam() -> None:
    print("free-free Euler-Bernoulli beam against cos(bL) cosh(bL) = 1")
    roots = [scipy.optimize.brentq(lambda x: np.cos(x) * np.cosh(x) - 1.0, a, a + 1.0) for a in (4.2, 7.4, 10.5, 13.6, 16.8, 19.9)]
    for got, want in zip(roots, [4.730, 7.853, 10.996, 14.137, 17.279, 20.420]):
        check("  root bL", got, want, 1e-4)
    length, ei, rho_a = 0.7, 2.1e11 * 3.2e-7, 7850.0 * 2.4e-3
    beam = dict(length=length, youngs_modulus=2.1e11, density=7850.0, area=2.4e-3, second_moment=3.2e-7)
    prev = None
    for n in (10, 20, 40, 160):
        chain = fe.Chain(beams=[fe.Beam(elements=n, **beam)], joints=[])
        f = precise(chain, 1, 6)
        exact = np.array(roots) ** 2 / (2 * np.pi * length**2) * np.sqrt(ei / rho_a)
        err = np.abs(f / exact - 1)
        print(f"  {n} elements: max rel. error of 6 modes {err.max():.2e}")
        if prev is not None and n == 40:
            # Hermite cubics: eigenvalue error O(h^4), so halving h divides the error by ~16
            check(f"  convergence rate mode 6, {n} elements (error ratio)", prev[5] / err[5], 16.0, 0.1)
        prev = err
    check("  160 elements, mode 1", f[0], exact[0], 3e-9)
    check("  160 elements, mode 6", f[5], exact[5], 3e-7)


def check_quadrature_element() -> None:
    print("quadrature Hermite element against the closed form (uniform), Timoshenko stiffness against Przemieniecki's")
    ei, rho_a, l = 6.72e4, 18.84, 0.0286
    k0, m0 = fe.eb_uniform(ei, rho_a, l)
    k1, m1 = fe.eb_piecewise(ei, rho_a, l, [(0.3 * l, 0.6 * l, 1.0, 1.0)])
    check("  K (max entry difference / max entry)", 1 + np.abs(k1 - k0).max() / np.abs(k0).max(), 1.0, 1e-14)
    check("  M (max entry difference / max entry)", 1 + np.abs(m1 - m0).max() / np.abs(m0).max(), 1.0, 1e-14)
    kga = 1e6
    phi = 12 * ei / (kga * l * l)
    kt, mt = fe.timoshenko(ei, kga, rho_a, 0.0, l)
    closed = ei / ((1 + phi) * l**3) * np.array(
        [
            [12, 6 * l, -12, 6 * l],
            [6 * l, (4 + phi) * l * l, -6 * l, (2 - phi) * l * l],
            [-12, -6 * l, 12, -6 * l],
            [6 * l, (2 - phi) * l * l, -6 * l, (4 + phi) * l * l],
        ]
    )
    check(f"  Timoshenko K, phi = {phi:.2f}", 1 + np.abs(kt - closed).max() / np.abs(closed).max(), 1.0, 1e-13)
    # phi = 1e-9: the matrices differ from Euler-Bernoulli's by O(phi)
    k_thin, m_thin = fe.timoshenko(ei, 12 * ei / (l * l * 1e-9), rho_a, 0.0, l)
    check("  Timoshenko -> Euler-Bernoulli as phi -> 0 (K)", 1 + np.abs(k_thin - k0).max() / np.abs(k0).max(), 1.0, 1e-8)
    check("  Timoshenko -> Euler-Bernoulli as phi -> 0 (M)", 1 + np.abs(m_thin - m0).max() / np.abs(m0).max(), 1.0, 1e-8)
    whole = fe.eb_piecewise(ei, rho_a, l, [(0.0, l, 0.3, 2.5)])
    check("  a piece over the whole element scales K", 1 + np.abs(whole[0] - 0.3 * k0).max() / np.abs(k0).max(), 1.0, 1e-14)
    check("  a piece over the whole element scales M", 1 + np.abs(whole[1] - 2.5 * m0).max() / np.abs(m0).max(), 1.0, 1e-14)


def check_paper_case() -> None:
    print("paper case I (2 beams, 17 elements) against README's worked example")
    f, _ = fe.elastic_modes(paper_case_1(), 4)
    for got, want in zip(f, [150.054, 655.524, 2411.608, 5356.350]):
        check("  frequency (Hz)", round(got, 3), want, 1e-12)


def compare_exact(name: str, chain: fe.Chain, r: int, count: int, rtol: float, order: float) -> None:
    """FE refined r/2 and r times against the exact roots: the error at r within ``rtol`` and the
    observed order of convergence log2(err(r/2) / err(r)) at least ``order`` on the modes whose
    error is well above the round-off floor (1e-9)."""
    coarse = precise(chain, r // 2, count)
    f = precise(chain, r, count)
    exact = exact_frequencies(chain, f)
    n_exact = count_roots(chain, 1.02 * f[-1])
    want = count if not chain.springs else count + 2
    ok = n_exact == want
    print(f"{'ok  ' if ok else 'FAIL'}   {name}: {n_exact} roots of the exact characteristic function up to mode {count} (want {want})")
    if not ok:
        FAILURES.append(f"{name} root count")
    for i, (a, c, b) in enumerate(zip(coarse, f, exact)):
        e1, e2 = abs(a / b - 1), abs(c / b - 1)
        if e1 > 1e-7:
            p = np.log2(e1 / max(e2, 1e-16))
            ok = p >= order
            print(f"{'ok  ' if ok else 'FAIL'}   {name}, mode {i + 1}: observed order {p:.2f} (want >= {order})")
            if not ok:
                FAILURES.append(f"{name} mode {i + 1} order")
        check(f"  {name}, mode {i + 1}, FE x{r} vs exact", c, b, rtol)


def check_against_exact() -> None:
    print("refined FE against the exact transfer-matrix solution")
    base = paper_case_1()
    compare_exact("paper case I", base, 16, 6, 2e-7, 3.5)
    c = copy.deepcopy(base)
    c.joints[0].k12 = 0.6 * np.sqrt(c.joints[0].k1 * c.joints[0].k2)
    compare_exact("joint coupling 0.6", c, 16, 6, 2e-7, 3.5)
    c = copy.deepcopy(base)
    c.masses = [(7, 0.1, 2e-4), (8, 0.1, 2e-4), (3, 0.02, 1e-5)]
    c.springs = [(0, 2e4, 0.0), (18, 2e4, 0.0)]
    compare_exact("masses with inertia, end springs", c, 16, 6, 2e-7, 3.5)
    c = copy.deepcopy(base)
    c.beams[1].pieces = [(0.0, 0.017, 8.0, 2.0), (0.134, 0.146, 0.5, 1.0)]
    c.beams[0].pieces = [(0.187, 0.2, 8.0, 2.0)]
    compare_exact("lap pieces and a damaged piece (nodes at their ends)", c, 16, 6, 2e-7, 3.5)
    alu = dict(youngs_modulus=7.0e10, density=2700.0, area=6.25e-4, second_moment=3.255e-8)
    three = fe.Chain(
        beams=[fe.Beam(length=0.25, elements=6, **alu), fe.Beam(length=0.20, elements=5, **alu), fe.Beam(length=0.35, elements=9, **alu)],
        joints=[fe.Joint(k1=5e6, k2=2e3), fe.Joint(k1=2e6, k2=5e3)],
    )
    compare_exact("3-beam aluminium chain", three, 16, 6, 2e-7, 3.5)
    thick = copy.deepcopy(three)
    for b in thick.beams:
        b.timoshenko = True
        b.area, b.second_moment = 0.04 * 0.06, 0.04 * 0.06**3 / 12
        b.poisson = 0.33
    # shear-dominated fine elements (length << height): w is nearly linear in them, order 2
    compare_exact("3-beam thick Timoshenko chain", thick, 32, 6, 1e-5, 1.9)
    tim = fe.Chain(
        beams=[fe.Beam(length=0.3, elements=10, youngs_modulus=2.1e11, density=7850.0, area=0.05 * 0.08, second_moment=0.05 * 0.08**3 / 12, poisson=0.29, timoshenko=True)],
        joints=[],
    )
    compare_exact("free-free Timoshenko beam h/L = 0.27", tim, 32, 6, 1e-4, 1.9)


def main() -> int:
    check_free_free_beam()
    check_quadrature_element()
    check_paper_case()
    check_against_exact()
    print(f"\n{len(FAILURES)} failure(s)" + (": " + ", ".join(FAILURES) if FAILURES else ""))
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
