"""Type stubs of the package's functions (see the docstrings in _api.py and docs/python.md)."""

import os
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from ._checks import ArgumentError as ArgumentError
from ._jointid import ComputationError as ComputationError
from ._jointid import InputError as InputError
from ._jointid import JointidError as JointidError
from ._jointid import SettingError as SettingError

PathLike = Union[str, os.PathLike]
ArrayLike = npt.ArrayLike
# a pandas.DataFrame when pandas is importable, else a dict of numpy arrays (jointid._tables.Table)
TableLike = Any

class Model:
    @classmethod
    def from_toml(cls, path: PathLike) -> "Model": ...
    @classmethod
    def from_matrices(
        cls,
        K: Any,
        M: Any,
        dK: Optional[Mapping[str, Any]] = ...,
        *,
        values: Optional[Mapping[str, float]] = ...,
        dM: Optional[Mapping[str, Any]] = ...,
        units: Optional[Mapping[str, str]] = ...,
        fixed: Sequence[str] = ...,
        dofs: Optional[Any] = ...,
        rigid_body_modes: Optional[int] = ...,
        sensor_tolerance: Optional[float] = ...,
    ) -> "Model": ...
    def modes(
        self, n: int, *, threads: Optional[int] = ...
    ) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...
    @property
    def dof_count(self) -> int: ...
    @property
    def rigid_body_modes(self) -> int: ...
    @property
    def labels(self) -> List[str]: ...
    @property
    def positions(self) -> npt.NDArray[np.float64]: ...
    @property
    def directions(self) -> List[str]: ...
    @property
    def parameters(self) -> List[Tuple[str, float, str, bool]]: ...

class Measured:
    model: Model
    @classmethod
    def from_csv(cls, path: PathLike, model: Model) -> "Measured": ...
    @classmethod
    def from_arrays(
        cls,
        model: Model,
        frequencies: ArrayLike,
        shapes: ArrayLike,
        *,
        labels: Optional[Sequence[str]] = ...,
        x: Optional[ArrayLike] = ...,
        xyz: Optional[ArrayLike] = ...,
        directions: Optional[Sequence[str]] = ...,
        modes: Optional[Sequence[int]] = ...,
        frequency_std: Optional[ArrayLike] = ...,
        shape_std: Optional[ArrayLike] = ...,
    ) -> "Measured": ...
    @classmethod
    def from_uff(
        cls,
        model: Model,
        datasets: Any,
        geometry: Mapping[str, Any],
        *,
        components: Mapping[int, str],
        space: bool = ...,
        modes: Optional[Sequence[int]] = ...,
    ) -> "Measured": ...
    @property
    def modes(self) -> List[int]: ...
    @property
    def frequencies(self) -> npt.NDArray[np.float64]: ...
    def to_csv(self) -> str: ...
    def __len__(self) -> int: ...

def identify(
    model: Model,
    measured: Measured,
    *,
    n: Optional[int] = ...,
    m: Optional[int] = ...,
    weighting: Optional[str] = ...,
    params: Optional[Sequence[str]] = ...,
    modes: Optional[Sequence[int]] = ...,
    frequency_noise: Optional[float] = ...,
    threads: Optional[int] = ...,
    as_csv: bool = ...,
) -> TableLike: ...
def diagnose(
    model: Model,
    measured: Measured,
    *,
    frequency_noise: float = ...,
    shape_noise: float = ...,
    stated_noise: bool = ...,
    n: Optional[int] = ...,
    m: Optional[int] = ...,
    weighting: str = ...,
    pairing_window: Optional[float] = ...,
    pair: Sequence[Tuple[int, int]] = ...,
    extended: bool = ...,
    causes: Sequence[str] = ...,
    threads: Optional[int] = ...,
    text: bool = ...,
    figures: bool = ...,
) -> Any: ...
def study(
    study: Union[PathLike, Dict[str, Any]],
    *,
    base_dir: Optional[PathLike] = ...,
    threads: Optional[int] = ...,
    progress: Optional[Callable[[int, int], None]] = ...,
    as_csv: bool = ...,
) -> TableLike: ...
def extract(
    frequencies: ArrayLike,
    frf: ArrayLike,
    *,
    coherence: Optional[ArrayLike] = ...,
    quantity: str = ...,
    band: Optional[Tuple[float, float]] = ...,
    modes: Optional[int] = ...,
    max_order: Optional[int] = ...,
    averages: Optional[int] = ...,
    mpc_min: Optional[float] = ...,
    threads: Optional[int] = ...,
) -> Dict[str, Any]: ...
def extract_uff(datasets: Any, **settings: Any) -> Dict[str, Any]: ...
def amplitude(
    levels: PathLike, *, joint: Optional[str] = ..., threads: Optional[int] = ...
) -> Dict[str, Any]: ...
def simulate(
    model: Model,
    modes: int,
    *,
    effects: Optional[Mapping[str, float]] = ...,
    shape_noise: float = ...,
    frequency_noise: float = ...,
    noise: str = ...,
    seed: int = ...,
    measure: str = ...,
) -> Measured: ...
