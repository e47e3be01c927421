"""Bad input raises the documented exception (a ``jointid.JointidError``, itself a
``ValueError``) whose message names the argument, the index or field, and what is allowed.

Independence: the inputs are written here by hand; nothing expected comes from jointid."""

import numpy as np
import pytest
import scipy.sparse as sp

import jointid


def two_dof():
    K = np.array([[2.0e4, -1.0e4], [-1.0e4, 1.0e4]])
    M = np.diag([1.0, 1.0])
    dK = {"k": np.array([[1.0, -1.0], [-1.0, 1.0]])}
    dofs = {"label": ["a", "b"], "x": [0.0, 1.0], "y": [0.0, 0.0], "z": [0.0, 0.0],
            "direction": ["x", "x"]}
    return K, M, dK, dofs


@pytest.fixture(scope="module")
def model():
    K, M, dK, dofs = two_dof()
    return jointid.Model.from_matrices(K, M, dK=dK, values={"k": 1.0e3}, dofs=dofs)


def test_hierarchy():
    for kind in (jointid.InputError, jointid.SettingError, jointid.ArgumentError,
                 jointid.ComputationError):
        assert issubclass(kind, jointid.JointidError)
    assert issubclass(jointid.JointidError, ValueError)


def test_non_symmetric_k_names_k():
    K, M, dK, dofs = two_dof()
    K[0, 1] = -2.0e4
    with pytest.raises(jointid.InputError, match=r"^K is not symmetric: K\[0, 1\] = -2e4 but K\[1, 0\] = -1e4"):
        jointid.Model.from_matrices(sp.csr_array(K), M, dK=dK, values={"k": 1.0}, dofs=dofs)


def test_wrong_shapes_name_the_argument():
    K, M, dK, dofs = two_dof()
    with pytest.raises(jointid.ArgumentError, match=r"^M has shape \(3, 3\): it must be \(2, 2\)"):
        jointid.Model.from_matrices(K, np.eye(3), dK=dK, values={"k": 1.0}, dofs=dofs)
    with pytest.raises(jointid.ArgumentError, match=r"^K has shape \(2, 3\): it must be square"):
        jointid.Model.from_matrices(np.ones((2, 3)), M, dK=dK, values={"k": 1.0}, dofs=dofs)


def test_nan_names_the_entry(model):
    K, M, dK, dofs = two_dof()
    M[1, 1] = np.nan
    with pytest.raises(jointid.ArgumentError, match=r"^M\[1, 1\] = nan is invalid"):
        jointid.Model.from_matrices(K, M, dK=dK, values={"k": 1.0}, dofs=dofs)
    with pytest.raises(jointid.ArgumentError, match=r"^shapes\[0, 0\] = nan is invalid"):
        jointid.Measured.from_arrays(model, [20.0], [[np.nan], [1.0]], labels=["a", "b"])


def test_measured_shapes_must_match_frequencies(model):
    with pytest.raises(jointid.ArgumentError, match=r"^shapes has shape \(2, 3\): .*axis 1 has 3, not 1"):
        jointid.Measured.from_arrays(model, [20.0], np.ones((2, 3)), labels=["a", "b"])


def test_missing_dof_label_names_it(model):
    with pytest.raises(jointid.ArgumentError, match=r"^labels\[1\] = 'c' is invalid: it is not a DOF label"):
        jointid.Measured.from_arrays(model, [20.0], [[1.0], [0.5]], labels=["a", "c"])


def test_missing_parameter_value():
    K, M, dK, dofs = two_dof()
    with pytest.raises(jointid.ArgumentError, match=r"^values\['k'\] is missing"):
        jointid.Model.from_matrices(K, M, dK=dK, dofs=dofs)


def test_negative_noise_names_it(model):
    with pytest.raises(jointid.ArgumentError, match=r"^shape_noise = -0.1 is invalid: it must be a finite number >= 0"):
        jointid.simulate(model, 1, shape_noise=-0.1)
    measured = jointid.simulate(model, 1)
    with pytest.raises(jointid.ArgumentError, match=r"^frequency_noise = -1 is invalid"):
        jointid.diagnose(model, measured, frequency_noise=-1)


def test_settings_carry_the_library_message(model, root):
    paper = jointid.Model.from_toml(root / "models" / "paper-case-1.toml")
    measured = jointid.simulate(paper, 3)
    with pytest.raises(jointid.SettingError, match=r"^n = 39 is invalid"):
        jointid.identify(paper, measured, n=39, m=5, weighting="inverse")
    with pytest.raises(jointid.SettingError, match=r"^params = k2,k2 is invalid: it lists k2 twice"):
        jointid.identify(paper, measured, params=["k2", "k2"])
    with pytest.raises(jointid.SettingError, match=r"^modes = 7 is invalid: it asks for mode 7"):
        jointid.identify(paper, measured, modes=[7])
    with pytest.raises(jointid.SettingError, match=r"^threads = 0 is invalid: it must be from 1"):
        paper.modes(3, threads=0)


def test_files_name_file_and_field(tmp_path):
    bad = tmp_path / "model.toml"
    bad.write_text("kind = \"matrices\"\nstiffness = \"\"\n")
    with pytest.raises(jointid.InputError, match=str(bad)):
        jointid.Model.from_toml(bad)
    with pytest.raises(jointid.InputError, match="cannot read the file"):
        jointid.study(tmp_path / "absent.toml")
