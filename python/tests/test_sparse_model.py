"""A model built here with scipy.sparse goes through modes, identify and diagnose.

The structure: a rectangular lattice of 8 x 5 point masses moving out of plane (one DOF
each, 40 DOFs like the paper's beam model), neighbours tied by springs; the springs that cross
the line between columns 3 and 4 are the joint (parameter ``kj``), the springs along the bottom
row an edge stiffener (``ke``). Free: one rigid-body mode (the translation).

Independence: the reference frequencies and the "measured" modes come from scipy alone
(``scipy.sparse.linalg.eigsh`` in shift-invert, ``scipy.linalg.eigh`` on the modified model),
never from jointid; the expected identification is the modification introduced here."""

import numpy as np
import pytest
import scipy.linalg
import scipy.sparse as sp
import scipy.sparse.linalg

import jointid

NX, NY = 8, 5
K_SPRING = 4.0e4  # N/m
MASS = 0.05  # kg
KJ, KE = 1.0e4, 2.0e4  # N/m, nominal


def _index(i, j):
    return j * NX + i


def lattice():
    """K without the parameters, dK/dkj, dK/dke (each scipy.sparse, unit stiffness), M, the
    DOF table."""
    n = NX * NY
    parts = {"k": [], "kj": [], "ke": []}
    for j in range(NY):
        for i in range(NX):
            for di, dj in ((1, 0), (0, 1)):
                a, b = (i, j), (i + di, j + dj)
                if b[0] >= NX or b[1] >= NY:
                    continue
                which = "kj" if (di == 1 and i == 3) else "ke" if (dj == 0 and j == 0) else "k"
                parts[which].append((_index(*a), _index(*b)))

    def springs(pairs, k):
        rows, cols, vals = [], [], []
        for a, b in pairs:
            rows += [a, b, a, b]
            cols += [a, b, b, a]
            vals += [k, k, -k, -k]
        return sp.coo_array((vals, (rows, cols)), shape=(n, n)).tocsr()

    K = springs(parts["k"], K_SPRING)
    dK = {"kj": springs(parts["kj"], 1.0), "ke": springs(parts["ke"], 1.0)}
    M = sp.diags_array(np.full(n, MASS)).tocsc()
    dofs = {
        "label": [f"p{i}_{j}" for j in range(NY) for i in range(NX)],
        "x": [0.05 * i for j in range(NY) for i in range(NX)],
        "y": [0.05 * j for j in range(NY) for i in range(NX)],
        "z": [0.0] * n,
        "direction": ["z"] * n,
    }
    return K, dK, M, dofs


@pytest.fixture(scope="module")
def built():
    K, dK, M, dofs = lattice()
    model = jointid.Model.from_matrices(
        K, M, dK=dK, values={"kj": KJ, "ke": KE}, dofs=dofs
    )
    return model, (K, dK, M, dofs)


def test_modes_match_eigsh(built):
    model, (K, dK, M, _) = built
    assert model.dof_count == NX * NY
    assert model.rigid_body_modes == 1
    total = K + KJ * dK["kj"] + KE * dK["ke"]
    lam = scipy.sparse.linalg.eigsh(total.tocsc(), k=7, M=M, sigma=-1.0, which="LM")[0]
    expected = np.sqrt(np.sort(lam)[1:]) / (2 * np.pi)
    frequencies, shapes = model.modes(6)
    np.testing.assert_allclose(frequencies, expected, rtol=1e-9)
    # M-normalised shapes: Y^T M Y = I
    np.testing.assert_allclose(shapes.T @ (M @ shapes), np.eye(6), atol=1e-9)


def _measured(model, K, dK, M, kj, labels, count):
    """The lowest `count` elastic modes of the lattice with joint stiffness kj, read at
    `labels` (scipy's dense solver)."""
    total = (K + kj * dK["kj"] + KE * dK["ke"]).toarray()
    lam, y = scipy.linalg.eigh(total, M.toarray())
    rows = [model.labels.index(s) for s in labels]
    f = np.sqrt(lam[1 : count + 1]) / (2 * np.pi)
    return jointid.Measured.from_arrays(model, f, y[rows, 1 : count + 1], labels=labels)


def test_identify_and_diagnose_a_softer_joint(built):
    model, (K, dK, M, dofs) = built
    truth = 0.7 * KJ
    measured = _measured(model, K, dK, M, truth, dofs["label"], 4)
    # one parameter per mode from its frequency: the truth, to the solver's precision, on
    # the modes the joint moves (modes 2 and 4 have their nodal line on it)
    table = jointid.identify(model, measured, params=["kj"], modes=[1, 3])
    kj = np.asarray(table["corrected"])[np.asarray(table["param"]) == "kj"]
    np.testing.assert_allclose(kj, truth, rtol=1e-6)
    # the paper's system on the shapes: every mode moves kj down, towards the truth
    table = jointid.identify(
        model, measured, n=12, m=8, weighting="inverse", params=["kj"], modes=[1, 3]
    )
    corrected = np.asarray(table["corrected"])
    assert np.all(corrected < KJ) and np.all(np.abs(corrected - truth) < 0.1 * KJ)
    # the diagnosis calibrates the joint on every mode and finds nothing missing
    report = jointid.diagnose(model, measured)
    assert report["verdict"] == "none"
    calibrated = {p["name"]: p["value"] for p in report["before"]["parameters"]}
    assert abs(calibrated["kj"] - truth) < 1e-6 * truth
    assert abs(calibrated["ke"] - KE) < 1e-6 * KE
    assert report["initial"]["frequency_rms_pct"] > 1.0
