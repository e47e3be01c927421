"""Noise-free measured modes of a battery case: the first elastic modes of the truth, translations
at the sensors, each shape scaled to a peak of +1 over the measured components.

Independence: the battery's own code (fe.py, effects.py); jointid's simulate.rs was not read.

How the effect enters, and why a finer mesh: the model file's mesh (5-15 elements per beam) is
too coarse for some effects (a lap whose ends fall inside elements, a Timoshenko beam whose
elements are shorter than they are high), and a battery whose effects were discretised on the
model's own mesh would test the tool against one discretisation of each effect. So the effect
is computed as an increment on a mesh r = 4 times finer (with nodes at every piece boundary)
and added to the model-mesh prediction of the base truth (nominal geometry, truth joints):

    f_r = f_r(base, model mesh) * f_r(effect, fine) / f_r(base, fine)
    y_r = y_r(base, model mesh) + [a y_r(effect, fine) - b y_r(base, fine)]   at the model's nodes

(a, b: least-squares scales onto y_r(base, model mesh); shape information is scale-free). A
clean case is therefore exactly the model-mesh prediction of the truth, and every effect is
its converged physical increment (the discretisation error of the increment is ~ r^-4 smaller
than the model mesh's own). Modes of the effect truth are paired with base modes by MAC (an
effect may reorder close modes).
"""

from __future__ import annotations

import copy

import numpy as np

import fe
from effects import Built

REFINE = 4
EXTRA = 3  # base modes beyond the measured ones, for the MAC pairing


def peak_normalised(v: np.ndarray) -> np.ndarray:
    return v / v[int(np.argmax(np.abs(v)))]


def _ls_scale(v: np.ndarray, onto: np.ndarray) -> float:
    return float(v @ onto / (v @ v))


def _frequency_dependent(chain: fe.Chain, count: int, alpha: float, f1: float, shift: float):
    """Mode r of the chain whose joints are scaled by (f_r / f1)^alpha: the root of
    g(s) = (f_r(s) / f1)^alpha - s per mode, by the secant method from s = 1 and the first
    substitution (the plain substitution converges linearly, the secant superlinearly)."""
    freqs, shapes = [], []
    for r in range(count):

        def g(scale):
            f, y = fe.elastic_modes(chain, r + 1, joint_scale=scale, shift=shift)
            return (f[r] / f1) ** alpha - scale, f[r], y[:, r]

        s0 = 1.0
        g0, f, y = g(s0)
        s1 = s0 + g0
        for _ in range(60):
            g1, f, y = g(s1)
            if abs(g1) <= 1e-11 * s1:
                break
            step = g1 * (s1 - s0) / (g1 - g0) if g1 != g0 else g1
            s0, g0, s1 = s1, g1, s1 - step
        else:
            raise RuntimeError(f"frequency-dependent joint: no fixed point for mode {r + 1} (alpha {alpha})")
        freqs.append(f)
        shapes.append(y)
    return np.array(freqs), np.array(shapes).T


def truth_modes(built: Built, count: int = 6) -> tuple[np.ndarray, np.ndarray, dict]:
    """Frequencies (Hz) and w shapes at every node of the model (nodes x modes) of the effect
    truth, by the increment rule above; and diagnostics (pairing, MACs)."""
    nodes = built.base.nodes()
    f_cb, y_cb = fe.elastic_modes(built.base, count + EXTRA)
    w_cb = y_cb[0 : 2 * nodes : 2, :]
    shift = (2.0 * np.pi * f_cb[0]) ** 2
    base = copy.deepcopy(built.base)
    for bb, eb in zip(base.beams, built.effect.beams):
        bb.pieces = [(p[0], p[1], 1.0, 1.0) for p in eb.pieces]  # the same fine mesh
    fine_base, node_map = fe.refine(base, REFINE)
    fine_eff, node_map_eff = fe.refine(built.effect, REFINE)
    assert np.array_equal(node_map, node_map_eff)
    f_fb, y_fb = fe.elastic_modes(fine_base, count + EXTRA, shift=shift)
    if built.alpha is None:
        f_fe, y_fe = fe.elastic_modes(fine_eff, count, shift=shift)
    else:
        f_fe, y_fe = _frequency_dependent(fine_eff, count, built.alpha, f_fb[0], shift)
    w_fb = y_fb[2 * node_map, :]
    w_fe = y_fe[2 * node_map, :]
    mac = (w_fe.T @ w_fb) ** 2 / np.outer(np.sum(w_fe**2, 0), np.sum(w_fb**2, 0))
    pairing = [int(np.argmax(mac[i])) for i in range(count)]
    if len(set(pairing)) != count:
        raise RuntimeError(f"effect modes pair with base modes {pairing}: not one to one")
    freqs = np.empty(count)
    shapes = np.empty((nodes, count))
    for i, j in enumerate(pairing):
        freqs[i] = f_cb[j] * f_fe[i] / f_fb[j]
        yb = w_cb[:, j]
        shapes[:, i] = yb + _ls_scale(w_fe[:, i], yb) * w_fe[:, i] - _ls_scale(w_fb[:, j], yb) * w_fb[:, j]
    info = {"pairing_with_base_modes": [j + 1 for j in pairing], "mac_with_paired_base_mode": [float(mac[i, j]) for i, j in enumerate(pairing)]}
    return freqs, shapes, info


def at_sensors(shapes: np.ndarray, sensors: list) -> np.ndarray:
    """Shapes at the sensors (sensors x modes), each mode scaled to a peak of +1."""
    y = shapes[np.asarray(sensors), :]
    return np.column_stack([peak_normalised(y[:, r]) for r in range(y.shape[1])])
