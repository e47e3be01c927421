"""Checks of array arguments before they cross into the library, each error naming the
argument, the index, the value and what is allowed (vectorised: no per-element Python work
on the arrays)."""

import numpy as np

from ._jointid import JointidError


class ArgumentError(JointidError):
    """An array or list argument of the wrong shape, with a value that is not finite or out of
    range, or naming a label the model does not have."""


def array(name, value, ndim, shape=None, dtype=np.float64):
    """``value`` as a C-contiguous array of ``ndim`` dimensions (``shape``: the sizes required,
    None for any), every entry finite."""
    try:
        a = np.asarray(value, dtype=dtype)
    except (TypeError, ValueError) as e:
        raise ArgumentError(f"{name} is invalid: it must be an array of numbers ({e})") from None
    if a.ndim != ndim:
        raise ArgumentError(
            f"{name} has shape {a.shape}: it must have {ndim} dimension(s)"
            + (f", shape {_shape(shape)}" if shape else "")
        )
    if shape is not None:
        for axis, (got, want) in enumerate(zip(a.shape, shape)):
            if want is not None and got != want:
                raise ArgumentError(
                    f"{name} has shape {a.shape}: it must have shape {_shape(shape)} "
                    f"(axis {axis} has {got}, not {want})"
                )
    finite = np.isfinite(a)
    if not finite.all():
        index = tuple(int(i) for i in np.argwhere(~finite)[0])
        raise ArgumentError(
            f"{name}[{', '.join(map(str, index))}] = {a[index]} is invalid: every value must be finite"
        )
    return np.ascontiguousarray(a)


def _shape(shape):
    return "(" + ", ".join("any" if s is None else str(s) for s in shape) + ")"


def non_negative(name, value):
    """A number >= 0."""
    if value is None:
        return value
    v = float(value)
    if not (v >= 0.0 and np.isfinite(v)):
        raise ArgumentError(f"{name} = {value} is invalid: it must be a finite number >= 0")
    return v


def coordinates(name, matrix, size=None):
    """A square matrix (scipy.sparse of any format, or dense) as 0-based coordinates
    (rows, columns, values), both triangles as given."""
    if hasattr(matrix, "tocoo"):
        coo = matrix.tocoo()
        shape = coo.shape
        rows, cols, vals = coo.row, coo.col, np.asarray(coo.data, dtype=np.float64)
        bad = ~np.isfinite(vals)
        if bad.any():
            k = int(np.argmax(bad))
            raise ArgumentError(
                f"{name}[{int(rows[k])}, {int(cols[k])}] = {vals[k]} is invalid: every value must be finite"
            )
    else:
        dense = array(name, matrix, 2)
        shape = dense.shape
        rows, cols = np.nonzero(dense)
        vals = dense[rows, cols]
    if len(shape) != 2 or shape[0] != shape[1]:
        raise ArgumentError(f"{name} has shape {tuple(shape)}: it must be square")
    if size is not None and shape[0] != size:
        raise ArgumentError(
            f"{name} has shape {tuple(shape)}: it must be ({size}, {size}), the shape of K"
        )
    return (
        np.ascontiguousarray(rows, dtype=np.int64),
        np.ascontiguousarray(cols, dtype=np.int64),
        np.ascontiguousarray(vals, dtype=np.float64),
    )
