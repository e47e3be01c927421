"""``Model``: a structure from a model file or from matrices in memory, and its modes."""

import os

import numpy as np

from . import _jointid as _j
from ._checks import ArgumentError, array, coordinates

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
