"""The package gives the CLI's results on the same inputs: identify, study and diagnose bit
for bit (the same CSV bytes, the same JSON), extract to the bit on the real UNESP-BERT FRFs
read by pyuff (a reader independent of jointid's own).

Independence: the measured modes are written by the CLI's `simulate` with noise (or by the
CLI's `extract` from the real FRFs), files the package then reads like any user's; every
expected value is what the release CLI writes, run here as a separate process."""

import json
import math

import numpy as np
import pytest

import jointid

STUDY = """name = "py-compare"
model = "{model}"

[truth]
delta = {{ k1 = 2.0e6, k2 = 2.0e3 }}

[[grid]]
modes = [1, 2, 3]
n = [10]
m = [5, 7]
nf = [0, 5]
weighting = ["equal", "inverse"]
shape_noise = [0.04]
frequency_noise = [0.001]

[monte_carlo]
trials = 3000
seed = 7
noise = "uniform"

[output]
csv = "{csv}"
"""


@pytest.fixture(scope="module")
def paper(root, cli, tmp_path_factory):
    """The paper's model and noisy measured modes of it written by the CLI."""
    tmp = tmp_path_factory.mktemp("paper")
    model = root / "models" / "paper-case-1.toml"
    truth = root / "models" / "paper-case-1-truth.toml"
    measured = tmp / "measured.csv"
    cli("simulate", "--model", truth, "--modes", "4", "--shape-noise", "0.01",
        "--frequency-noise", "0.001", "--seed", "3", "--measure", "w", "--out", measured)
    return model, measured, tmp


def test_identify_equals_cli(paper, cli):
    model_path, measured_path, tmp = paper
    out = tmp / "identify.csv"
    cli("identify", "--model", model_path, "--measured", measured_path, "--n", "10",
        "--m", "5", "--weighting", "inverse", "--out", out)
    model = jointid.Model.from_toml(model_path)
    measured = jointid.Measured.from_csv(measured_path, model)
    text = jointid.identify(model, measured, n=10, m=5, weighting="inverse", as_csv=True)
    assert text == out.read_text()
    table = jointid.identify(model, measured, n=10, m=5, weighting="inverse")
    cli_rows = out.read_text().splitlines()[1:]
    assert len(table["mode"]) == len(cli_rows) == 8
    assert float(cli_rows[0].split(",")[3]) == table["correction"][0]


def test_identify_from_frequency_equals_cli(paper, cli):
    model_path, measured_path, tmp = paper
    out = tmp / "identify-f.csv"
    cli("identify", "--model", model_path, "--measured", measured_path, "--from-frequency",
        "--params", "k1", "--out", out)
    model = jointid.Model.from_toml(model_path)
    measured = jointid.Measured.from_csv(measured_path, model)
    assert jointid.identify(model, measured, params=["k1"], as_csv=True) == out.read_text()


def test_study_equals_cli(root, cli, tmp_path):
    model = root / "models" / "paper-case-1.toml"
    csv = tmp_path / "cli.csv"
    file = tmp_path / "study.toml"
    file.write_text(STUDY.format(model=model, csv=csv))
    cli("study", file, "--quiet")
    expected = csv.read_text()
    assert jointid.study(file, as_csv=True) == expected
    # the same study as a dict, its model relative to base_dir, on one thread
    as_dict = {
        "name": "py-compare",
        "model": "paper-case-1.toml",
        "truth": {"delta": {"k1": 2.0e6, "k2": 2.0e3}},
        "grid": [{"modes": [1, 2, 3], "n": [10], "m": [5, 7], "nf": [0, 5],
                  "weighting": ["equal", "inverse"], "shape_noise": [0.04],
                  "frequency_noise": [0.001]}],
        "monte_carlo": {"trials": 3000, "seed": 7, "noise": "uniform"},
        "output": {"csv": "unused.csv"},
    }
    assert jointid.study(as_dict, base_dir=model.parent, threads=1, as_csv=True) == expected


def test_diagnose_equals_cli(paper, cli):
    model_path, measured_path, tmp = paper
    out = tmp / "diagnose.json"
    plots = tmp / "plots"
    done = cli("diagnose", "--model", model_path, "--measured", measured_path,
               "--json", out, "--plots", plots, "--quiet")
    model = jointid.Model.from_toml(model_path)
    measured = jointid.Measured.from_csv(measured_path, model)
    report, text = jointid.diagnose(model, measured, text=True, figures=True)
    figures = report.pop("figures")
    assert report == json.loads(out.read_text())
    assert text == done.stdout
    assert figures and all((plots / name).read_text() == svg for name, (_, svg) in figures.items())


def _cli_modes(path):
    """The CLI's measured-modes CSV: per mode its frequency and its values in row order."""
    lines = path.read_text().splitlines()
    head = lines[0].split(",")
    modes = {}
    for line in lines[1:]:
        row = dict(zip(head, line.split(",")))
        mode = modes.setdefault(int(row["mode"]), {"f": float(row["frequency_hz"]), "v": [],
                                                   "zeta": float(row["damping_ratio"])})
        mode["v"].append(float(row["value"]))
    return modes


def test_extract_on_pyuff_equals_cli(unesp, cli, tmp_path):
    pyuff = pytest.importorskip("pyuff")
    frf = unesp / "frf_0p10V.uff"
    out = tmp_path / "modes.csv"
    cli("extract", "--frf", frf, "--geometry", unesp / "geometry.uff", "--band", "10:110",
        "--modes", "2", "--max-order", "30", "--averages", "54", "--out", out, "--quiet")
    expected = _cli_modes(out)
    datasets = pyuff.UFF(str(frf)).read_sets()
    got = jointid.extract_uff(datasets, band=(10, 110), modes=2, max_order=30, averages=54)
    assert len(expected) == len(got["frequency_hz"]) == 2
    for r, mode in expected.items():
        assert got["frequency_hz"][r - 1] == mode["f"]
        assert got["damping_ratio"][r - 1] == mode["zeta"]
        np.testing.assert_array_equal(got["shapes"][:, r - 1], mode["v"])
    assert all(math.isfinite(s) and s > 0 for s in got["frequency_std"])


def test_uff_55_written_by_pyuff_reads_as_the_csv(paper, tmp_path):
    """The CLI's measured modes written by pyuff as dataset 55 (and the nodes as dataset 15),
    read back by pyuff and given to Measured.from_uff: the modes of the CSV to pyuff's six
    digits, and the identification of the CLI on those rounded values."""
    pyuff = pytest.importorskip("pyuff")
    model_path, measured_path, _ = paper
    model = jointid.Model.from_toml(model_path)
    rows = [line.split(",") for line in measured_path.read_text().splitlines()]
    head, body = rows[0], rows[1:]
    assert head[:5] == ["mode", "frequency_hz", "node", "dof", "value"]
    # each node's abscissa from the model's DOF table (label `node:w`)
    labels, positions = model.labels, model.positions
    at = {n: float(positions[labels.index(f"{n}:w"), 0]) for n in sorted({int(r[2]) for r in body})}
    # a position names one point: the joint's second node (at its first's x) is left out
    nodes = [n for n in at if list(at.values()).index(at[n]) == list(at).index(n)]
    xs = [at[n] for n in nodes]
    body = [r for r in body if int(r[2]) in nodes]
    frequency = {int(r[0]): float(r[1]) for r in body}
    value = {(int(r[0]), int(r[2])): float(r[4]) for r in body}
    numbers = [n + 1 for n in nodes]  # universal files number nodes from 1
    path = tmp_path / "modes.uff"
    uff = pyuff.UFF(str(path))
    uff.write_sets(pyuff.prepare_15(node_nums=numbers, def_cs=[0] * len(nodes),
                                    disp_cs=[0] * len(nodes), color=[1] * len(nodes), x=xs,
                                    y=[0.0] * len(xs), z=[0.0] * len(xs)), mode="overwrite")
    for mode, f in frequency.items():
        w = np.array([value[(mode, n)] for n in nodes])
        zero = np.zeros_like(w)
        uff.write_sets(pyuff.prepare_55(
            id1=f"mode {mode}", id2="NONE", id3="NONE", id4="NONE", id5="NONE", model_type=1,
            analysis_type=2, data_ch=2, spec_data_type=8, data_type=2, load_case=1, mode_n=mode,
            freq=f, modal_m=1.0, modal_damp_vis=0.0, modal_damp_his=0.0, node_nums=numbers,
            r1=zero, r2=w, r3=zero), mode="add")
    sets = pyuff.UFF(str(path)).read_sets()
    geometry = next(d for d in sets if d["type"] == 15)
    measured = jointid.Measured.from_uff(model, sets, geometry, components={2: "w"})
    assert measured.modes == sorted(frequency)
    np.testing.assert_allclose(measured.frequencies, [frequency[r] for r in sorted(frequency)],
                               rtol=1e-5)
    lines = measured.to_csv().splitlines()
    column = lines[0].split(",").index("value")
    peak = max(abs(v) for v in value.values())
    for mode in frequency:
        got = sorted(float(r.split(",")[column]) for r in lines[1:] if r.startswith(f"{mode},"))
        want = sorted(v for (m, _), v in value.items() if m == mode)
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-5 * peak)
