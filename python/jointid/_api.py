"""The commands as functions: thin wrappers that check array arguments (naming them), hand
them to the extension module once, and turn its texts into tables and dicts."""

import json
import logging
import os
from pathlib import Path

import numpy as np

from . import _jointid as _j
from ._checks import ArgumentError, array, non_negative
from ._measured import Measured
from ._model import Model
from ._tables import table

JointidError = _j.JointidError
InputError = _j.InputError
SettingError = _j.SettingError
ComputationError = _j.ComputationError

_log = logging.getLogger("jointid")

__all__ = [
    "ArgumentError",
    "ComputationError",
    "InputError",
    "JointidError",
    "Measured",
    "Model",
    "SettingError",
    "amplitude",
    "diagnose",
    "extract",
    "extract_uff",
    "identify",
    "simulate",
    "study",
]


def identify(
    model,
    measured,
    *,
    n=None,
    m=None,
    weighting=None,
    params=None,
    modes=None,
    frequency_noise=None,
    threads=None,
    as_csv=False,
):
    """The paper's per-mode corrections (``jointid identify``): n, m and weighting
    (``"equal"``, ``"inverse"``, ``"inverse-sqrt"``) together, or none of them to identify
    each mode's parameter from its frequency alone; ``params`` names (or ``["auto"]``),
    ``modes`` the measured modes to identify. Returns the table of the CLI's CSV (columns
    mode, param, initial, correction, corrected, relative_correction, ...); its text with
    ``as_csv``. Warnings (modes left unsolved) and notes go to the ``jointid`` logger."""
    non_negative("frequency_noise", frequency_noise)
    csv, warnings, notes = _j.identify(
        model._inner,
        measured._inner,
        n=n,
        m=m,
        weighting=weighting,
        params=None if params is None else [str(p) for p in params],
        modes=None if modes is None else [int(r) for r in modes],
        frequency_noise=frequency_noise,
        threads=threads,
    )
    for w in warnings:
        _log.warning(w)
    for line in notes.splitlines():
        _log.info(line)
    return csv if as_csv else table(csv)


def diagnose(
    model,
    measured,
    *,
    frequency_noise=0.001,
    shape_noise=0.02,
    stated_noise=False,
    n=None,
    m=None,
    weighting="inverse",
    pairing_window=None,
    pair=(),
    extended=False,
    causes=(),
    threads=None,
    text=False,
    figures=False,
):
    """The diagnosis (``jointid diagnose``): the model calibrated on every mode, what it
    still misses traced to a candidate effect. Returns the report as the CLI's ``--json``
    (a dict); with ``text``, a pair (report, the CLI's terminal text); with ``figures``, the
    report has also ``"figures"``: the CLI's ``--plots`` SVGs as a dict file name ->
    (caption, SVG text)."""
    non_negative("frequency_noise", frequency_noise)
    non_negative("shape_noise", shape_noise)
    kw = {} if pairing_window is None else {"pairing_window": float(pairing_window)}
    report, words, drawn = _j.diagnose(
        model._inner,
        measured._inner,
        frequency_noise=float(frequency_noise),
        shape_noise=float(shape_noise),
        stated_noise=bool(stated_noise),
        n=n,
        m=m,
        weighting=weighting,
        pair=[(int(a), int(b)) for a, b in pair],
        extended=bool(extended),
        causes=[str(c) for c in causes],
        figures=bool(figures),
        threads=threads,
        **kw,
    )
    report = json.loads(report)
    if figures:
        report["figures"] = {name: (caption, svg) for name, caption, svg in drawn}
    return (report, words) if text else report


def study(study, *, base_dir=None, threads=None, progress=None, as_csv=False):
    """Runs a Monte-Carlo study (``jointid study``): ``study`` a study file's path, or its
    content as a dict (its ``model`` relative to ``base_dir``, default the working
    directory). Returns the result table, the CLI's CSV (its text with ``as_csv``).
    ``progress(done, total)`` is called with the trials done as they advance (at most every
    50 ms, on the calling thread); an exception it raises stops the study."""
    if isinstance(study, dict):
        text = _j.json_to_toml(json.dumps(study))
        file = Path(base_dir or os.getcwd()) / "study.toml"
    else:
        file = Path(study)
        try:
            text = file.read_text()
        except OSError as e:
            raise InputError(f"{file}: cannot read the file: {e}") from None
    csv = _j.study(text, os.fspath(file), threads=threads, progress=progress)
    return csv if as_csv else table(csv)


def extract(
    frequencies,
    frf,
    *,
    coherence=None,
    quantity="acceleration",
    band=None,
    modes=None,
    max_order=None,
    averages=None,
    mpc_min=None,
    threads=None,
):
    """Modal parameters from FRFs (``jointid extract``): ``frequencies`` (Hz, evenly
    spaced, (lines,)), ``frf`` complex (responses, lines), optional ``coherence`` (responses,
    lines) and ``averages`` (the H1 estimates' averages: standard errors from the
    coherence). Returns a dict of arrays: frequency_hz, damping_ratio, frequency_std,
    damping_std, mpc, mpd_deg (modes,), shapes, shape_std (responses, modes; real, largest
    component +1), complex_shapes, and band_hz."""
    f = array("frequencies", frequencies, 1)
    h = array("frf", frf, 2, (None, f.shape[0]), dtype=np.complex128)
    c = None if coherence is None else array("coherence", coherence, 2, h.shape)
    return _j.extract(
        f,
        h,
        coherence=c,
        quantity=quantity,
        band=None if band is None else (float(band[0]), float(band[1])),
        modes=modes,
        max_order=max_order,
        averages=averages,
        mpc_min=mpc_min,
        threads=threads,
    )


_QUANTITIES = {8: "displacement", 11: "velocity", 12: "acceleration"}


def extract_uff(datasets, **settings):
    """:func:`extract` on the FRFs (dataset 58, function type 4) of a pyuff dataset list
    (``pyuff.UFF(path).read_sets()``), with their coherences (function type 6) when every
    response has one; the quantity from the FRFs' ordinate; the frequency lines those of the
    first FRF's abscissa read as the CLI reads a file's (an even axis stored with 6 digits
    becomes start + i step). The result has also ``nodes``
    and ``directions``, the response of each row of the shapes."""
    sets = [datasets] if isinstance(datasets, dict) else list(datasets)
    frfs = [d for d in sets if d.get("type") == 58 and d.get("func_type") == 4]
    if not frfs:
        raise ArgumentError("datasets holds no FRF (dataset 58 of function type 4)")
    coherences = {
        (d.get("rsp_node"), d.get("rsp_dir")): d
        for d in sets
        if d.get("type") == 58 and d.get("func_type") == 6
    }
    keys = [(d.get("rsp_node"), d.get("rsp_dir")) for d in frfs]
    if "quantity" not in settings:
        code = frfs[0].get("ordinate_spec_data_type")
        settings["quantity"] = _QUANTITIES.get(code, "acceleration")
    if "coherence" not in settings and all(k in coherences for k in keys):
        settings["coherence"] = np.vstack([np.real(coherences[k]["data"]) for k in keys])
    x = array("datasets[0]['x']", frfs[0]["x"], 1)
    lines = _j.even_lines(x)
    if lines is None:
        raise ArgumentError("datasets[0]['x'] is invalid: the FRFs' frequencies must be evenly spaced")
    # a response in a negative direction is the opposite of the positive one, as the CLI reads it
    signs = np.array([-1.0 if (d.get("rsp_dir") or 0) < 0 else 1.0 for d in frfs])
    frf = np.vstack([d["data"] for d in frfs]) * signs[:, None]
    result = extract(lines, frf, **settings)
    result["nodes"] = np.array([k[0] for k in keys])
    result["directions"] = np.array([k[1] for k in keys])
    return result


def amplitude(levels, *, joint=None, threads=None):
    """The amplitude dependence across the levels of a levels file (``jointid
    amplitude``): a dict of the CLI's tables by file name (amplitude_levels.csv, ...; with
    ``joint``, the joint's too) and ``"summary"``, the CLI's text."""
    tables, summary = _j.amplitude(os.fspath(levels), joint=joint, threads=threads)
    out = {name: table(text) for name, text in tables.items()}
    out["summary"] = summary
    return out


def simulate(
    model,
    modes,
    *,
    effects=None,
    shape_noise=0.0,
    frequency_noise=0.0,
    noise="gaussian",
    seed=0,
    measure="all",
):
    """Measured modes of ``model`` (``jointid simulate``): its first ``modes`` elastic modes
    with ``effects`` (a dict name -> size) added, measured at ``measure`` (``"all"``,
    ``"w"``, ``"theta"``, ``"sensors"``) with relative errors ``shape_noise`` and
    ``frequency_noise`` (``noise``: ``"gaussian"`` or ``"uniform"``, seeded)."""
    non_negative("shape_noise", shape_noise)
    non_negative("frequency_noise", frequency_noise)
    inner = _j.simulate(
        model._inner,
        int(modes),
        effects=[(str(k), float(v)) for k, v in dict(effects or {}).items()],
        shape_noise=float(shape_noise),
        frequency_noise=float(frequency_noise),
        noise=str(noise),
        seed=int(seed),
        measure=str(measure),
    )
    return Measured(inner, model)
