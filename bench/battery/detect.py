"""How detectable an effect is at the stated noise, and the effect size that makes it weak or strong.

Independence: the battery's own weighted least squares (scipy.optimize.least_squares on the
battery's FE); jointid's code was not read. The weighting is the stated noise model of README
("Diagnosis, exactly"), since that is the yardstick the user gives the tool.

Detectability: the noncentrality lambda = min over the joints' k1, k2 of the weighted residual
sum of squares of the nominal model against the NOISE-FREE measured modes of the effect truth:

    sum_r ((f_r(k) - f_r) / (sigma_f f_r))^2 + sum_r sum_j ((c_r y_rj(k) - y_rj) / sigma_j)^2,
    sigma_j = sigma_s sqrt(y_rj^2 + (0.02 peak_r)^2), c_r fitted per mode (closed form).

It is what the effect adds to the chi^2 of a joint-only fit, in units of the stated noise: a
candidate that captured the effect exactly would have a likelihood-ratio statistic distributed
as a noncentral chi^2 with this noncentrality. With the Bonferroni level of today's diagnose
(0.01 / 5 candidates, 1 parameter: critical value 9.55), lambda = 16 is detected with about
80% probability ("weak": just detectable) and lambda = 400 (20 sigma) always ("strong").
Sizes are found by a safeguarded secant iteration in log(size) - log(lambda) (lambda grows
about as size^2 for small sizes); an effect whose largest physical size stays below the target
is "capped" and the generator moves to another geometry.
"""

from __future__ import annotations

import copy
import math

import numpy as np
import scipy.linalg
import scipy.optimize

import effects
import fe

WEAK = 16.0
STRONG = 400.0
FLOOR = 0.02  # README: the floor of the shape noise, a fraction of the mode's peak


def log_stiffnesses(joints: list) -> np.ndarray:
    """log k1, log k2 of every joint: the fits' joint parameters."""
    return np.log([v for j in joints for v in (j.k1, j.k2)])


class JointFit:
    """The nominal model with every joint's k1, k2 free (log parameters), against fixed data."""

    def __init__(self, nominal: fe.Chain, sensors: list, count: int, frequency_noise: float, shape_noise: float):
        free = copy.deepcopy(nominal)
        for j in free.joints:
            j.k1, j.k2, j.k12 = 0.0, 0.0, 0.0
        self.k0, self.m = fe.assemble(free)
        self.units = []  # dK / dk for k1, k2 of every joint
        for ji in range(len(nominal.joints)):
            for which in ("k1", "k2"):
                c = copy.deepcopy(free)
                setattr(c.joints[ji], which, 1.0)
                self.units.append(fe.assemble(c)[0] - self.k0)
        self.start = log_stiffnesses(nominal.joints)
        self.dofs = 2 * np.asarray(sensors)
        self.count = count
        self.sf = frequency_noise
        self.ss = shape_noise

    def model(self, x: np.ndarray):
        k = self.k0 + sum(math.exp(v) * u for v, u in zip(x, self.units))
        lam, y = scipy.linalg.eigh(k, self.m, subset_by_index=[0, fe.RIGID_BODY_MODES + self.count - 1])
        f = np.sqrt(np.maximum(lam[fe.RIGID_BODY_MODES :], 0.0)) / (2 * math.pi)
        return f, y[self.dofs, fe.RIGID_BODY_MODES :]

    def residuals(self, x: np.ndarray, freqs: np.ndarray, shapes: np.ndarray) -> np.ndarray:
        f, y = self.model(x)
        return weighted_residuals(f, y, freqs, shapes, self.sf, self.ss)

    def noncentrality(self, freqs: np.ndarray, shapes: np.ndarray, start: np.ndarray | None = None) -> tuple[float, np.ndarray]:
        """min chi^2 over the joints and the fitted log-stiffnesses."""
        best = None
        for x0 in [self.start] if start is None else [start, self.start]:
            sol = scipy.optimize.least_squares(self.residuals, x0, args=(freqs, shapes), method="lm", x_scale=1.0, xtol=1e-12, ftol=1e-12)
            chi2 = float(np.sum(sol.fun**2))
            if best is None or chi2 < best[0]:
                best = (chi2, sol.x)
        return best


def weighted_residuals(f, y, freqs, shapes, sf: float, ss: float) -> np.ndarray:
    """Residuals of model modes (f, y at the sensors) against data in units of the stated noise
    (module docs), each model shape scaled onto the data in closed form."""
    out = [(f - freqs) / (sf * freqs)]
    for r in range(len(freqs)):
        ym = shapes[:, r]
        sigma = ss * np.sqrt(ym**2 + (FLOOR * np.max(np.abs(ym))) ** 2)
        yv = y[:, r] / sigma
        t = ym / sigma
        c = float(yv @ t / (yv @ yv))
        out.append(c * yv - t)
    return np.concatenate(out)


def find_size(noncentrality, target: float, guess: float, lower: float, upper: float, rtol: float = 0.08):
    """Size s in (lower, upper] with noncentrality(s) within rtol of target.
    Returns (size, lambda, capped, evaluations)."""
    hist = []
    s = min(max(guess, lower * 1.01 if lower > 0 else guess), upper)
    for _ in range(25):
        lam = noncentrality(s)
        hist.append((s, lam))
        if abs(lam / target - 1.0) <= rtol:
            return s, lam, False, hist
        below = [(a, b) for a, b in hist if b < target]
        above = [(a, b) for a, b in hist if b > target]
        if below and above:
            (s0, l0) = max(below, key=lambda t: t[0]) if all(b > 0 for _, b in below) else below[-1]
            (s1, l1) = min(above, key=lambda t: t[0])
            if s0 > s1:  # not monotone: bisect the latest pair
                (s0, l0), (s1, l1) = sorted([hist[-1], hist[-2]], key=lambda t: t[0])
            lo, hi = math.log(s0), math.log(s1)
            t = (math.log(target) - math.log(max(l0, 1e-300))) / (math.log(l1) - math.log(max(l0, 1e-300)))
            t = min(max(t, 0.1), 0.9)
            s_new = math.exp(lo + t * (hi - lo))
        else:
            slope = 2.0
            if len(hist) >= 2 and hist[-1][1] > 0 and hist[-2][1] > 0 and hist[-1][0] != hist[-2][0]:
                slope = (math.log(hist[-1][1]) - math.log(hist[-2][1])) / (math.log(hist[-1][0]) - math.log(hist[-2][0]))
                slope = min(max(slope, 0.5), 8.0)
            s_new = s * (target / max(lam, 1e-300)) ** (1.0 / slope)
            s_new = min(s_new, upper)
            if lower > 0:
                s_new = max(s_new, lower)
            if s_new == upper and s == upper:
                return s, lam, True, hist
        s = s_new
    best = min(hist, key=lambda t: abs(math.log(t[1] / target)) if t[1] > 0 else 1e9)
    return best[0], best[1], abs(best[1] / target - 1.0) > 0.3, hist


# Mimicry: how well a library effect reproduces another effect's noise-free data.
#
# An effect outside the library (or another library effect) can leave data that a library
# effect reproduces to within the noise: a lap whose splice plates stiffen the beam behind a
# soft rotational joint spring shows only its added mass, which is a joint mass; no method can
# then tell them apart, and naming the library effect states what the data show. The mimicry
# of library effect e is the noncentrality left when e explains the data at its best:
#
#     lambda_e = min over the joints' k1, k2 and e's knobs of the weighted residual sum of
#                squares of (nominal + e) against the noise-free data,
#
# the same yardstick as the detectability above. Knobs (the battery's own effects, with the
# knobs a fit would free): joint_coupling s in [-0.95, 0.95] and joint_mass its mass and its
# rotary inertia ratio c in [1, 48], one of each per joint as jointid's candidates free them
# (c = 1 is the coupled inertia m I/A; c = 48 a radius of gyration of two section heights,
# jointid's plausible bound); sensor_mass its mass and its radius of gyration g in [0, 2] section
# heights (jointid's plausible range of the sensor's free rotary inertia); suspension its bounce
# ratio; shear a factor t in [0, 3] on the Timoshenko shear flexibility and rotary inertia of
# the physical section (t = 1 the true Timoshenko beam).
MIMICS = ["joint_coupling", "joint_mass", "sensor_mass", "suspension", "shear"]
# effects whose knobs jointid's candidate frees at every joint separately (one k12; one mass
# and rotary inertia per joint): their mimics free every knob per joint too
PER_JOINT = ["joint_coupling", "joint_mass"]

# knob bounds and starting points per library effect
# (the first start is the nominal model: the effect absent)
_KNOBS = {
    "joint_coupling": ([-0.95], [0.95], [[0.0], [0.05], [-0.05]]),
    "joint_mass": ([0.0, 1.0], [1.0, 48.0], [[0.0, 1.0], [0.01, 1.0], [0.01, 5.0], [0.01, 20.0]]),
    "sensor_mass": ([0.0, 0.0], [0.5, 2.0], [[0.0, 0.6], [0.005, 0.6], [0.05, 0.6], [0.005, 1.5]]),
    "suspension": ([0.0], [0.5], [[0.0], [0.02], [0.2]]),
    "shear": ([0.0], [3.0], [[0.0], [0.5], [1.5]]),
}


class Mimic:
    """Library effect ``name`` on the case's nominal chain, the joints' k1, k2 and the effect's
    knobs free, against fixed data."""

    def __init__(self, name: str, geom, nominal: fe.Chain, sensors: list, count: int, frequency_noise: float, shape_noise: float):
        self.name, self.geom, self.nominal = name, geom, nominal
        self.sensors, self.count = sensors, count
        self.dofs = 2 * np.asarray(sensors)
        self.sf, self.ss = frequency_noise, shape_noise
        self.joints = len(nominal.joints)

    def chain(self, x: np.ndarray) -> fe.Chain:
        joints = [fe.Joint(k1=math.exp(x[2 * j]), k2=math.exp(x[2 * j + 1])) for j in range(self.joints)]
        knobs = x[2 * self.joints :]
        if self.name == "shear":
            c = copy.deepcopy(self.nominal)
            c.joints = joints
            for b in c.beams:
                b.timoshenko, b.shear_scale = True, float(knobs[0])
            return c
        if self.name in PER_JOINT:
            # one size per joint (the first knobs), as jointid's candidate frees them
            sizes = [float(v) for v in knobs[: self.joints]]
            params = {"sign": 1.0, "per_joint": sizes}
            if self.name == "joint_mass":
                params["inertia_ratio"] = [float(v) for v in knobs[self.joints :]]
            return effects.build(self.name, 1.0, self.geom, joints, self.sensors, params, nominal=self.nominal).effect
        params = {"gyration_heights": float(knobs[1])} if self.name == "sensor_mass" else {}
        return effects.build(self.name, float(knobs[0]), self.geom, joints, self.sensors, params, nominal=self.nominal).effect

    def knobs(self) -> tuple[list, list, list]:
        """Bounds and starts of the knobs: ``_KNOBS``, the size repeated per joint for the
        per-joint effects."""
        lower, upper, starts = _KNOBS[self.name]
        if self.name not in PER_JOINT:
            return lower, upper, starts
        # every knob per joint: the size, and the joint mass's inertia ratio
        n = self.joints
        return ([v for v in lower for _ in range(n)], [v for v in upper for _ in range(n)],
                [[v for v in s for _ in range(n)] for s in starts])

    def residuals(self, x: np.ndarray, freqs: np.ndarray, shapes: np.ndarray) -> np.ndarray:
        f, y = fe.elastic_modes(self.chain(x), self.count)
        return weighted_residuals(f, y[self.dofs, :], freqs, shapes, self.sf, self.ss)

    def noncentrality(self, freqs: np.ndarray, shapes: np.ndarray, joints_start: np.ndarray) -> tuple[float, list]:
        """min chi^2 over the joints and the knobs, from ``joints_start`` and each of the
        effect's knob starts; and the knobs at the minimum."""
        lower, upper, starts = self.knobs()
        # the joints' log-stiffnesses within a factor 1e6 of the start (a fit that runs
        # beyond has left every physical joint, and exp() would overflow)
        span = math.log(1e6)
        lo = np.concatenate([np.asarray(joints_start) - span, lower])
        hi = np.concatenate([np.asarray(joints_start) + span, upper])
        best = None
        for knobs in starts:
            x0 = np.concatenate([joints_start, knobs])
            sol = scipy.optimize.least_squares(self.residuals, x0, args=(freqs, shapes), bounds=(lo, hi), method="trf", x_scale="jac", xtol=1e-10, ftol=1e-10, max_nfev=400)
            chi2 = float(np.sum(sol.fun**2))
            if best is None or chi2 < best[0]:
                best = (chi2, [float(v) for v in sol.x[2 * self.joints :]])
        return best


def mimicry(geom, nominal: fe.Chain, sensors: list, freqs: np.ndarray, shapes: np.ndarray, joints_start: np.ndarray,
            frequency_noise: float, shape_noise: float, skip: str | None = None) -> dict:
    """lambda_e and e's knobs at its best, for every library effect e but ``skip`` (the truth's
    own name). The fits start from the joint-only optimum (so lambda_e never exceeds the
    truth's own noncentrality) and from the truth joints."""
    _, best_joints = JointFit(nominal, sensors, len(freqs), frequency_noise, shape_noise).noncentrality(freqs, shapes, joints_start)
    out = {}
    for name in MIMICS:
        if name == skip:
            continue
        mimic = Mimic(name, geom, nominal, sensors, len(freqs), frequency_noise, shape_noise)
        lam, knobs = min(mimic.noncentrality(freqs, shapes, start) for start in (best_joints, joints_start))
        out[name] = {"noncentrality": lam, "knobs": knobs}
    return out
