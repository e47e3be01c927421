"""``Measured``: measured modes from arrays, the CSV or universal files (pyuff), checked
against a model."""

import os

import numpy as np

from . import _jointid as _j
from ._checks import ArgumentError, array

InputError = _j.InputError


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
