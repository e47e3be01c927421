"""The CSV texts of the library (the CLI's files, byte for byte) as tables: a pandas DataFrame
when pandas is importable, else a dict of numpy arrays; the text itself is kept
(``table.csv``, or ``df.attrs["csv"]``)."""

import csv
import io

import numpy as np


class Table(dict):
    """Columns by name (numpy arrays), in the CSV's order; ``csv`` is the CLI's text."""

    csv: str

    def __init__(self, columns, text):
        super().__init__(columns)
        self.csv = text


# Columns that count or number things: integers; every other number is a float.
_INTEGERS = {"cell", "mode", "n", "m", "nf", "trials", "failures", "level"}


def _column(name, values):
    if name in _INTEGERS and values and all(v.lstrip("-").isdigit() for v in values):
        return np.array([int(v) for v in values], dtype=np.int64)
    try:
        return np.array([float(v) if v != "" else np.nan for v in values], dtype=np.float64)
    except ValueError:
        return np.array(values, dtype=object)


def table(text):
    """The table of CSV ``text`` (numbers as float64, integers as int64, empty as NaN)."""
    rows = list(csv.reader(io.StringIO(text)))
    header, body = rows[0], rows[1:]
    columns = {name: _column(name, [r[j] for r in body]) for j, name in enumerate(header)}
    try:
        import pandas
    except ImportError:
        return Table(columns, text)
    frame = pandas.DataFrame(columns)
    frame.attrs["csv"] = text
    return frame
