"""Checks of the 3D solid half-lap model (fe3d.py) against solutions that share nothing with it.

Independence: the references are (a) the exact free-free frequencies of a Timoshenko beam
(shear and rotary inertia, Cowper's shear factor kappa = 10 (1 + nu) / (12 + 11 nu) of a
rectangle), from the roots of its frequency determinant solved here (no beam elements), and of
an Euler-Bernoulli beam (cos(bL) cosh(bL) = 1), for the monolithic bar; (b) exact properties
of any free solid: six rigid-body fields in the null space of K, six zero eigenvalues, the
translational mass equal to rho b h L (plus a tip mass), and a patch test (a linear displacement
field reproduced exactly by a patch of distorted elements); (c) the glued lap on a second,
finer mesh. Nothing here imports or calls jointid.

Run: ``$(bash scripts/python-env.sh) bench/lap3d/check_fe3d.py``; exit 1 on any failure.
Takes 7 to 10 minutes on two cores (the fine mesh of (c), 285 000 DOFs, most of it).
"""

from __future__ import annotations

import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np
import scipy.optimize
import scipy.sparse
import scipy.sparse.linalg

sys.path.insert(0, str(Path(__file__).resolve().parent))
import fe3d  # noqa: E402

FAILURES: list[str] = []


def verdict(name: str, ok: bool) -> str:
    if not ok:
        FAILURES.append(name)
    return "ok" if ok else "FAIL"


# ------------------------------------------------------------------ beam references
def timoshenko_free_free(length, young, poisson, density, area, inertia, kappa, count):
    """The lowest `count` nonzero roots (Hz) of the free-free Timoshenko beam's frequency
    determinant. Harmonic motion w(x), psi(x) e^{i w t} of
        kappa G A (w'' - psi') + rho A w^2 w = 0,  E I psi'' + kappa G A (w' - psi) + rho I w^2 psi = 0
    has w = e^{s x} with E I s^4 + rho w^2 I (1 + E / (kappa G)) s^2
    + (rho w^2 / (kappa G)) (rho I w^2 - kappa G A) = 0: below the cut-off one root s^2 = a^2
    > 0, one s^2 = -b^2 < 0; w = C1 cosh ax + C2 sinh ax + C3 cos bx + C4 sin bx with
    psi' = w'' + r w, r = rho w^2 / (kappa G). Free ends: E I psi' = 0, kappa G A (w' - psi) = 0
    at x = 0 and L: a 4 x 4 determinant, scanned in 0.5 Hz steps and refined by Brent."""
    g = young / (2 * (1 + poisson))

    def det(f):
        om2 = (2 * np.pi * f) ** 2
        r = density * om2 / (kappa * g)
        qa = young * inertia
        qb = density * inertia * om2 + young * inertia * r
        qc = r * (density * inertia * om2 - kappa * g * area)
        disc = np.sqrt(qb * qb - 4 * qa * qc)
        al = np.sqrt((-qb + disc) / (2 * qa))
        be = np.sqrt((qb + disc) / (2 * qa))
        pa, pb = (al**2 + r) / al, (r - be**2) / be

        def rows(x):
            ch, sh, co, si = np.cosh(al * x), np.sinh(al * x), np.cos(be * x), np.sin(be * x)
            wd = np.array([al * sh, al * ch, -be * si, be * co])
            psi = np.array([pa * sh, pa * ch, pb * si, -pb * co])
            psid = np.array([pa * al * ch, pa * al * sh, pb * be * co, pb * be * si])
            return psid, wd - psi

        mat = np.array([*rows(0.0), *rows(length)])
        mat[:, :2] /= np.cosh(al * length)
        return np.linalg.det(mat)

    roots, f0, d0 = [], 1.0, det(1.0)
    while len(roots) < count:
        f1 = f0 + 0.5
        d1 = det(f1)
        if np.sign(d1) != np.sign(d0):
            roots.append(scipy.optimize.brentq(det, f0, f1, xtol=1e-10))
        f0, d0 = f1, d1
    return np.array(roots)


def euler_bernoulli_free_free(length, young, density, area, inertia, count):
    roots = [scipy.optimize.brentq(lambda x: np.cos(x) * np.cosh(x) - 1.0, a, a + 1.0)
             for a in (4.2, 7.4, 10.5, 13.6, 16.8, 19.9, 23.0, 26.2)[:count]]
    return np.array(roots) ** 2 / (2 * np.pi * length**2) * np.sqrt(young * inertia
                                                                     / (density * area))


# ------------------------------------------------------------------ (b) patch test
def patch_test() -> float:
    """A 2 x 2 x 2 block of H20 elements on [0, 1]^3 whose inner corner node is moved to
    (0.62, 0.41, 0.57) (straight edges, mid-edge nodes at the middles); the displacement
    u = c + A X imposed on the block's boundary nodes; the interior solved for. Returns the
    largest error of the interior nodes against the linear field (relative)."""
    corner = lambda i: np.array([0.62, 0.41, 0.57]) if tuple(i) == (1, 1, 1) else np.array(i) / 2
    nodes: dict = {}
    elems = []
    for ex in range(2):
        for ey in range(2):
            for ez in range(2):
                ids = []
                for a, b, c in fe3d.H20_LATTICE:
                    lat = (2 * ex + a, 2 * ey + b, 2 * ez + c)
                    if lat not in nodes:
                        # the node's position: the middle of its edge's corners
                        lo = [v // 2 for v in lat]
                        hi = [(v + 1) // 2 for v in lat]
                        nodes[lat] = (len(nodes), 0.5 * (corner(lo) + corner(hi)))
                    ids.append(nodes[lat][0])
                elems.append(ids)
    xyz = np.array([p for _, p in sorted(nodes.values(), key=lambda t: t[0])])
    n = len(xyz)
    k = np.zeros((3 * n, 3 * n))
    for ids in elems:
        ke, _ = fe3d.h20_matrices(xyz[ids], 2.0e11, 0.29, 7850.0)
        dofs = (3 * np.array(ids)[:, None] + np.arange(3)).ravel()
        k[np.ix_(dofs, dofs)] += ke
    a_mat = np.array([[1.0, 0.3, -0.2], [0.5, -0.7, 0.4], [0.1, 0.2, 0.6]]) * 1e-3
    u = (np.array([1e-4, -2e-4, 3e-4]) + xyz @ a_mat.T).ravel()
    boundary = np.array([np.any(np.isclose(p, 0) | np.isclose(p, 1)) for p in xyz])
    fixed = np.repeat(boundary, 3)
    free = ~fixed
    u_free = np.linalg.solve(k[np.ix_(free, free)], -k[np.ix_(free, fixed)] @ u[fixed])
    return float(np.max(np.abs(u_free - u[free])) / np.max(np.abs(u)))


def rigid_checks(name: str, spec: fe3d.Specimen) -> None:
    mesh = fe3d.Mesh(spec)
    r = mesh.rigid_modes()
    kr = mesh.K @ r
    scale = abs(mesh.K).max() * np.abs(r).max()
    res = float(np.abs(kr).max() / scale)
    mass = spec.density * spec.width * spec.height * spec.length + spec.tip_mass
    m_tr = [float(r[:, c] @ (mesh.M @ r[:, c])) for c in range(3)]
    m_err = max(abs(v / mass - 1) for v in m_tr)
    f, _ = fe3d.eigen(mesh, 8)
    n0 = int(np.sum(np.abs(f) < 1.0))
    ratio = float(np.max((f[:6] / f[6]) ** 2))
    ok = res < 1e-9 and m_err < 1e-10 and n0 == 6 and ratio < 1e-6
    print(f"  {name:24s} |K r|/(|K||r|) {res:.1e}  M(translation)/mass - 1 {m_err:.1e}  "
          f"|f| < 1 Hz: {n0}  max (f_rigid/f_7)^2 {ratio:.1e}  f_7 {f[6]:.2f} Hz  "
          f"{verdict('rigid ' + name, ok)}")


def main() -> int:
    t0 = time.time()
    base = fe3d.Specimen()
    b, h, L = base.width, base.height, base.length
    area, inertia = b * h, b * h**3 / 12
    kappa = 10 * (1 + base.poisson) / (12 + 11 * base.poisson)

    print("(a) monolithic bar, first 6 free-free bending modes in x-z against exact beams")
    print(f"    L = {L} m, b = {b} m, h = {h} m, E = {base.young:.3g}, nu = {base.poisson}, "
          f"rho = {base.density}, kappa (Cowper) = {kappa:.4f}")
    mono = fe3d.Mesh(replace(base, monolithic=True))
    f_fe, *_ = fe3d.bending_modes(mono, 6)
    f_ti = timoshenko_free_free(L, base.young, base.poisson, base.density, area, inertia, kappa, 6)
    f_eb = euler_bernoulli_free_free(L, base.young, base.density, area, inertia, 6)
    # the determinant solver against Euler-Bernoulli for a very slender bar (h = 0.1 mm)
    hs = 1e-4
    slender = timoshenko_free_free(L, base.young, base.poisson, base.density, b * hs,
                                   b * hs**3 / 12, kappa, 6)
    slender_err = float(np.max(np.abs(slender / euler_bernoulli_free_free(
        L, base.young, base.density, b * hs, b * hs**3 / 12, 6) - 1)))
    print(f"    (Timoshenko solver at h = 0.1 mm against Euler-Bernoulli: max {slender_err:.1e} "
          f"{verdict('timoshenko solver', slender_err < 1e-5)})")
    print("    mode   solid FE Hz   Timoshenko Hz   Euler-B. Hz   FE/Timo - 1   FE/EB - 1")
    for i in range(6):
        print(f"    {i + 1:4d} {f_fe[i]:13.3f} {f_ti[i]:15.3f} {f_eb[i]:13.3f} "
              f"{f_fe[i] / f_ti[i] - 1:+13.2e} {f_fe[i] / f_eb[i] - 1:+11.2e}")
    err = float(np.max(np.abs(f_fe / f_ti - 1)))
    print(f"    max |FE/Timoshenko - 1| = {err:.2e} (allowed 5e-3) "
          f"{verdict('Timoshenko', err <= 5e-3)}; max |FE/EB - 1| = "
          f"{float(np.max(np.abs(f_fe / f_eb - 1))):.2e} (shear and rotary inertia)")

    print("(b) rigid-body fields, mass, zero eigenvalues; patch test")
    for name, spec in (("monolithic", replace(base, monolithic=True)),
                       ("lap, uniform interface", base),
                       ("lap, bolts", replace(base, interface="bolts")),
                       ("lap, glued", replace(base, interface="glued")),
                       ("lap, uniform + 20 g tip", replace(base, tip_mass=0.02))):
        rigid_checks(name, spec)
    perr = patch_test()
    print(f"  patch test, 8 distorted H20: max interior error {perr:.1e} (allowed 1e-10) "
          f"{verdict('patch test', perr < 1e-10)}")

    print("(c) mesh convergence, glued lap: the generator's mesh against a finer one")
    fine = replace(base, interface="glued", dx=base.dx / 2, ny=2 * base.ny,
                   notch_grading=fe3d.graded(base.notch_grading[0] / 2, 4e-3),
                   z_layer=fe3d.graded(base.z_layer[0] / 2, 4e-3) + (5.2e-3,))
    glued = fe3d.Mesh(replace(base, interface="glued"))
    t1 = time.time()
    f1, *_ = fe3d.bending_modes(glued, 6)
    t_base = time.time() - t1
    fine_mesh = fe3d.Mesh(fine)
    t1 = time.time()
    f2, *_ = fe3d.bending_modes(fine_mesh, 6)
    t_fine = time.time() - t1
    print(f"    base: {glued.ndof} DOFs ({t_base:.0f} s); fine: dx/2, 2 ny, notch grading to "
          f"{fine.notch_grading[0] * 1e3:.4g} mm, {fine_mesh.ndof} DOFs ({t_fine:.0f} s)")
    print("    mode     base Hz     fine Hz   base/fine - 1")
    for i in range(6):
        print(f"    {i + 1:4d} {f1[i]:11.3f} {f2[i]:11.3f} {f1[i] / f2[i] - 1:+15.2e}")
    err = float(np.max(np.abs(f1 / f2 - 1)))
    print(f"    max {err:.2e} (allowed 2e-3) {verdict('convergence', err <= 2e-3)}")

    print(f"({time.time() - t0:.0f} s)")
    if FAILURES:
        print("FAILED:", ", ".join(FAILURES))
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
