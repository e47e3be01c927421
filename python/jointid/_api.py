"""The package's functions: thin wrappers that check array arguments (naming them), hand
them to the extension module once, and turn its texts into tables and dicts."""

import json
import logging
import os
from pathlib import Path

import numpy as np

from . import _jointid as _j
from ._checks import ArgumentError, array, coordinates, non_negative
from ._tables import table

JointidError = _j.JointidError
InputError = _j.InputError
SettingError = _j.SettingError
ComputationError = _j.ComputationError

_log = logging.getLogger("jointid")

_DOF_COLUMNS = ("label", "x", "y", "z", "direction")


class Model:
    """A model: stiffness and mass with the derivatives of the identified parameters (a beam
    chain, a solid, or external matrices), its DOF table and its rigid-body modes."""

    def __init__(self, inner):
        self._inner = inner

    @classmethod
    def from_toml(cls, path):
        """Reads and validates a model file (TOML: ``kind`` chain, matrices or solid), as
        ``jointid identify --model PATH`` does. Raises InputError naming the file and field."""
        return cls(_j.Model.from_toml(os.fspath(path)))

    @classmethod
    def from_matrices(
        cls,
        K,
        M,
        dK=None,
        *,
        values=None,
        dM=None,
        units=None,
        fixed=(),
        dofs=None,
        rigid_body_modes=None,
        sensor_tolerance=None,
    ):
        """A model from matrices: ``K`` and ``M`` without the parameters' terms (scipy.sparse
        of any format, or dense; symmetric), ``dK`` a dict name -> dK/dp (same forms),
        ``values`` a dict name -> nominal value p (required for each), optional ``dM`` (name
        -> dM/dp), ``units`` (name -> unit, default N/m), ``fixed`` (names held fixed),
        ``dofs`` a DOF table (dict of arrays or DataFrame with columns label, x, y, z,
        direction; default labels "1".."N" at the origin, direction x), ``rigid_body_modes``
        (counted when None). The model is K + sum p dK/dp, M + sum p dM/dp, with every check
        of an external model's files (symmetry, positive definite M, rigid-body count)."""
        k = coordinates("K", K)
        size = int(max(k[0].max(initial=-1), k[1].max(initial=-1)) + 1)
        size = K.shape[0] if hasattr(K, "shape") else size
        m = coordinates("M", M, size)
        dK = dict(dK or {})
        dM = dict(dM or {})
        values = dict(values or {})
        units = dict(units or {})
        for name in list(dM) + list(values) + list(units) + list(fixed):
            if name not in dK:
                raise ArgumentError(
                    f"{name!r} is named in values, dM, units or fixed but not in dK: "
                    f"the parameters are {sorted(dK)}"
                )
        parameters = []
        for name, derivative in dK.items():
            if name not in values:
                raise ArgumentError(f"values[{name!r}] is missing: every parameter of dK needs its nominal value")
            value = float(values[name])
            if not np.isfinite(value):
                raise ArgumentError(f"values[{name!r}] = {value} is invalid: it must be finite")
            parameters.append(
                (
                    str(name),
                    value,
                    str(units.get(name, "N/m")),
                    name not in fixed,
                    coordinates(f"dK[{name!r}]", derivative, size),
                    coordinates(f"dM[{name!r}]", dM[name], size) if name in dM else None,
                )
            )
        labels, positions, directions = _dof_table(dofs, size)
        return cls(
            _j.Model._from_coordinates(
                size,
                k,
                m,
                parameters,
                labels,
                positions,
                directions,
                rigid_body_modes=rigid_body_modes,
                sensor_tolerance=sensor_tolerance,
            )
        )

    def modes(self, n, *, threads=None):
        """The ``n`` lowest elastic modes (after the rigid-body ones): frequencies (Hz,
        ascending, shape (n,)) and M-normalised shapes (shape (DOFs, n))."""
        return self._inner.modes(int(n), threads=threads)

    @property
    def dof_count(self):
        """Number of DOFs."""
        return self._inner.dof_count

    @property
    def rigid_body_modes(self):
        """Number of rigid-body modes."""
        return self._inner.rigid_body_modes

    @property
    def labels(self):
        """The DOF labels, in index order."""
        return self._inner.labels

    @property
    def positions(self):
        """The DOFs' positions, m (shape (DOFs, 3)), in index order."""
        return self._inner.positions

    @property
    def directions(self):
        """The DOFs' directions (w, theta, x, y, z, rx, ry, rz), in index order."""
        return self._inner.directions

    @property
    def parameters(self):
        """The parameters: a list of (name, value, unit, identified)."""
        return self._inner.parameters

    def __repr__(self):
        return repr(self._inner)


def _dof_table(dofs, size):
    if dofs is None:
        return [str(i + 1) for i in range(size)], np.zeros((size, 3)), ["x"] * size
    missing = [c for c in _DOF_COLUMNS if c not in dofs]
    if missing:
        raise ArgumentError(
            f"dofs has no column {missing[0]!r}: it must have the columns {', '.join(_DOF_COLUMNS)}"
        )
    labels = [str(v) for v in np.asarray(dofs["label"]).tolist()]
    directions = [str(v) for v in np.asarray(dofs["direction"]).tolist()]
    if len(labels) != size or len(directions) != size:
        raise ArgumentError(
            f"dofs has {len(labels)} rows: it must have one per DOF, {size} (the size of K)"
        )
    xyz = np.column_stack([array(f"dofs[{c!r}]", dofs[c], 1, (size,)) for c in ("x", "y", "z")])
    return labels, np.ascontiguousarray(xyz), directions


class Measured:
    """Measured modes (frequencies and partial shapes), checked against a model."""

    def __init__(self, inner, model):
        self._inner = inner
        self.model = model

    @classmethod
    def from_csv(cls, path, model):
        """Reads a measured-modes CSV (the CLI's ``--measured`` file) against ``model``."""
        return cls(_j.Measured.from_csv(os.fspath(path), model._inner), model)

    @classmethod
    def from_arrays(
        cls,
        model,
        frequencies,
        shapes,
        *,
        labels=None,
        x=None,
        xyz=None,
        directions=None,
        modes=None,
        frequency_std=None,
        shape_std=None,
    ):
        """Measured modes from arrays: ``frequencies`` (Hz, shape (modes,)), ``shapes``
        (shape (points, modes)), the points as DOF or sensor ``labels`` (points,), or as
        positions along a chain ``x`` (points,) or in space ``xyz`` (points, 3) with
        ``directions`` (points,; w/theta, or x/y/z); ``modes`` the mode numbers (default 1, 2,
        ...); optional standard errors ``frequency_std`` (Hz, (modes,)) and ``shape_std``
        ((points, modes))."""
        f = array("frequencies", frequencies, 1)
        count = f.shape[0]
        v = array("shapes", shapes, 2, (None, count))
        points = v.shape[0]
        given = [k for k, a in (("labels", labels), ("x", x), ("xyz", xyz)) if a is not None]
        if len(given) != 1:
            raise ArgumentError(
                f"points: give exactly one of labels, x or xyz (given: {', '.join(given) or 'none'})"
            )
        kw = {}
        if labels is not None:
            kw["labels"] = [str(s) for s in labels]
            if len(kw["labels"]) != points:
                raise ArgumentError(
                    f"labels has {len(kw['labels'])} entries: it must have one per row of shapes, {points}"
                )
            known = set(model.labels)
            unknown = [i for i, s in enumerate(kw["labels"]) if s not in known]
        else:
            unknown = []
            if x is not None:
                kw["x"] = array("x", x, 1, (points,))
            else:
                kw["xyz"] = array("xyz", xyz, 2, (points, 3))
            if directions is None or len(directions) != points:
                raise ArgumentError(
                    f"directions is invalid: it must give one direction per point, {points}"
                )
            kw["directions"] = [str(d) for d in directions]
        numbers = list(range(1, count + 1)) if modes is None else [int(r) for r in modes]
        if len(numbers) != count:
            raise ArgumentError(f"modes has {len(numbers)} entries: it must have one per frequency, {count}")
        if frequency_std is not None:
            kw["frequency_std"] = array("frequency_std", frequency_std, 1, (count,))
        if shape_std is not None:
            kw["shape_std"] = array("shape_std", shape_std, 2, v.shape)
        try:
            inner = _j.Measured._from_columns(model._inner, numbers, f, v, **kw)
        except InputError as e:
            if unknown:
                i = unknown[0]
                raise ArgumentError(
                    f"labels[{i}] = {kw['labels'][i]!r} is invalid: it is not a DOF label of the model "
                    f"(nor a sensor it declares): {e}"
                ) from None
            raise
        return cls(inner, model)

    @classmethod
    def from_uff(cls, model, datasets, geometry, *, components, space=False, modes=None):
        """Measured modes from universal files read by pyuff: the real normal modes of
        ``datasets`` (dataset 55, analysis type 2: ``freq``, ``node_nums``, ``r1``..``r6``),
        located by ``geometry`` (a dataset 15 or 2411: ``node_nums``, ``x``, ``y``, ``z``).
        ``components`` maps a component of the dataset (1-6) to the model's direction it
        measures (on a chain ``"w"`` or ``"theta"``, e.g. ``{2: "w"}``; in space with ``space``
        ``"x"``..``"rz"``); a chain's points are at the nodes' ``x``, space's at their
        ``x, y, z``. ``modes`` the mode numbers (default the datasets' ``mode_n``)."""
        sets = [datasets] if isinstance(datasets, dict) else list(datasets)
        shapes = [d for d in sets if d.get("type") == 55 and d.get("analysis_type") == 2]
        if not shapes:
            raise ArgumentError("datasets holds no real normal mode (dataset 55, analysis type 2)")
        nodes = [int(n) for n in shapes[0]["node_nums"]]
        for k, d in enumerate(shapes):
            if [int(n) for n in d["node_nums"]] != nodes:
                raise ArgumentError(
                    f"datasets: mode shape {k} has other nodes than the first: every shape must list the same nodes"
                )
        where = {int(n): i for i, n in enumerate(geometry["node_nums"])}
        missing = [n for n in nodes if n not in where]
        if missing:
            raise ArgumentError(f"geometry has no node {missing[0]}: the shapes' nodes must all be in it")
        comps = sorted((int(c), str(d)) for c, d in dict(components).items())
        if not comps or any(c not in range(1, 7) for c, _ in comps):
            raise ArgumentError(f"components = {components!r} is invalid: it maps components 1 to 6 to directions")
        rows = [where[n] for n in nodes for _ in comps]
        xyz = np.column_stack([np.asarray(geometry[a], dtype=float)[rows] for a in ("x", "y", "z")])
        values = np.column_stack(
            [np.concatenate([[np.real(d[f"r{c}"][i]) for c, _ in comps] for i in range(len(nodes))])
             for d in shapes]
        )
        directions = [name for _ in nodes for _, name in comps]
        numbers = [int(d["mode_n"]) for d in shapes] if modes is None else modes
        where_points = {"xyz": xyz} if space else {"x": xyz[:, 0]}
        return cls.from_arrays(model, [float(d["freq"]) for d in shapes], values,
                               directions=directions, modes=numbers, **where_points)

    @property
    def modes(self):
        """The mode numbers (1 = the first elastic mode)."""
        return self._inner.modes

    @property
    def frequencies(self):
        """The measured frequencies, Hz."""
        return self._inner.frequencies

    def to_csv(self):
        """The measured-modes CSV text."""
        return self._inner.to_csv()

    def __len__(self):
        return len(self._inner)

    def __repr__(self):
        return repr(self._inner)


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
