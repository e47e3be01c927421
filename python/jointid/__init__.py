"""jointid for Python: the stiffness of mechanical joints identified from measured vibration
modes, mode by mode (Abdel-Mohsen & Bassiouni), Monte-Carlo robustness studies of it, modal
extraction from FRFs and a diagnosis of what a calibrated model still misses.

Bindings of the Rust library ``jointid``, the only implementation: every function here runs
the library with the GIL released and returns what the command-line tool writes (the same
numbers, the same CSV and JSON), as numpy arrays, dicts or pandas DataFrames. Ctrl-C
interrupts a call within a fraction of a second. Nothing is printed: warnings and notes go to
the ``jointid`` logger.

Functions: :class:`Model` (``from_toml``, ``from_matrices``, ``modes``), :class:`Measured`
(``from_arrays``, ``from_csv``, ``from_uff``), :func:`identify`, :func:`diagnose`,
:func:`study`, :func:`extract`, :func:`extract_uff`, :func:`amplitude`, :func:`simulate`.
Errors: :class:`JointidError` (a ``ValueError``) and its kinds :class:`InputError`,
:class:`SettingError`, :class:`ArgumentError`, :class:`ComputationError`.
"""

from ._api import (
    ArgumentError,
    ComputationError,
    InputError,
    JointidError,
    Measured,
    Model,
    SettingError,
    amplitude,
    diagnose,
    extract,
    extract_uff,
    identify,
    simulate,
    study,
)
from ._jointid import __version__

__all__ = [
    "ArgumentError",
    "ComputationError",
    "InputError",
    "JointidError",
    "Measured",
    "Model",
    "SettingError",
    "__version__",
    "amplitude",
    "diagnose",
    "extract",
    "extract_uff",
    "identify",
    "simulate",
    "study",
]
