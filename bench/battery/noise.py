"""The noise situations of the battery: what the true measurement errors are, against what the
user states to the tool (frequency 0.001, shape 0.02 relative standard deviations).

Independence: the battery's own generators (numpy's PCG64 streams), not jointid's noise code,
which was not read. The stated model is README's ("Diagnosis, exactly"): shape component j of
a mode with peak 1 has the standard deviation sigma_s sqrt(y_j^2 + (0.02 peak)^2), a frequency
the relative standard deviation sigma_f.

| situation     | shape error of component j                                  | frequency error       |
|---------------|--------------------------------------------------------------|-----------------------|
| as_stated     | sigma_s sqrt(y^2 + 0.02^2) N(0, 1)                           | sigma_f f N(0, 1)     |
| floor_x10     | sigma_s sqrt(y^2 + 0.2^2) N(0, 1) (additive floor 10x larger) | sigma_f f N(0, 1)     |
| twice_stated  | 2 sigma_s sqrt(y^2 + 0.02^2) N(0, 1)                         | 2 sigma_f f N(0, 1)   |
| half_stated   | sigma_s / 2 sqrt(y^2 + 0.02^2) N(0, 1)                       | sigma_f / 2 f N(0, 1) |
| heavy_tailed  | sigma_s sqrt(y^2 + 0.02^2) t_3 / sqrt(3) (Student t, 3 dof,  | sigma_f f N(0, 1)     |
|               | scaled to the stated standard deviation: same variance,     |                       |
|               | heavier tails)                                               |                       |

Shapes are scaled to a peak of 1 before the errors are added (y is the noise-free value) and
not rescaled after.
"""

from __future__ import annotations

import numpy as np

STATED_FREQUENCY = 0.001
STATED_SHAPE = 0.02

SITUATIONS = ["as_stated", "floor_x10", "twice_stated", "half_stated", "heavy_tailed"]

DESCRIPTION = {
    "as_stated": "the stated model: relative Gaussian shape noise with the 2% floor, relative Gaussian frequency noise",
    "floor_x10": "the stated model with an additive shape floor of 0.2 of the peak instead of 0.02",
    "twice_stated": "the stated model with both standard deviations doubled",
    "half_stated": "the stated model with both standard deviations halved",
    "heavy_tailed": "shape errors Student t with 3 degrees of freedom, scaled to the stated standard deviation; frequencies Gaussian as stated",
}


def apply(situation: str, freqs: np.ndarray, shapes: np.ndarray, rng: np.random.Generator,
          sf: float = STATED_FREQUENCY, ss: float = STATED_SHAPE) -> tuple[np.ndarray, np.ndarray]:
    """Noisy copies of frequencies (modes) and shapes (sensors x modes, each with peak 1)."""
    floor, factor = 0.02, 1.0
    if situation == "floor_x10":
        floor = 0.2
    elif situation == "twice_stated":
        factor = 2.0
    elif situation == "half_stated":
        factor = 0.5
    elif situation not in ("as_stated", "heavy_tailed"):
        raise ValueError(f"unknown noise situation {situation!r}; one of {SITUATIONS}")
    f = freqs * (1.0 + factor * sf * rng.standard_normal(freqs.shape))
    sigma = factor * ss * np.sqrt(shapes**2 + floor**2)
    if situation == "heavy_tailed":
        e = rng.standard_t(3, size=shapes.shape) / np.sqrt(3.0)
    else:
        e = rng.standard_normal(shapes.shape)
    return f, shapes + sigma * e
