"""Physical effects that the nominal model of a jointed-beam chain leaves out, written from
their physics for the independent test battery.

Independence: written from README's one-line description of what each of jointid's candidates
is, physically, and from textbooks; jointid's effects code, simulate.rs and noise code were not
read. The parameterisations differ from jointid's on purpose where the physics allows (a joint
mass with its own rotary inertia, sensors with theirs, a shear coefficient after Cowper, a joint
whose stiffness follows a power of the frequency instead of the mode number).

Every effect has one size knob (a physical quantity) and parameters drawn once per case from
the case's random stream (a location, a sign, an inertia ratio). ``build`` returns the nominal
chain (what the model file says), the base truth (nominal geometry, the truth's joints) and the
effect truth (base plus the effect), plus a frequency exponent for the frequency-dependent joint.

Library effects (diagnose has a candidate of that name today):
- joint_coupling: k12 = s sqrt(k1 k2) at every joint, sign drawn (knob s, |s| < 1 keeps the
  joint positive definite).
- joint_mass: hardware of mass m at every joint, half on each joint node, each half with rotary
  inertia (m / 2) c I / A, c drawn log-uniform in [2, 9]: the radius of gyration of splice
  plates or a bolt-and-washer set is larger than the beam section's (c = 1 is jointid's
  fixed inertia). Splice plates of length 2h above and below the section: a^2 / 12 + e^2 with
  e = h/2 + t, about 8.7 I / A; a bolt through the height alone: about 2 I / A. Knob: m as a
  fraction of the beams' mass.
- sensor_mass: an accelerometer at every measured node: mass m_s, a cube of side
  a = (m_s / 3000 kg/m^3)^(1/3) glued on the top face, rotary inertia m_s (a^2 / 6 + (h/2 + a/2)^2)
  (its own inertia plus its offset from the neutral axis: the section's rotation moves it
  axially). Knob: the sensors' total mass as a fraction of the beams' mass.
- suspension: bungee cords at both free ends, a grounded transversal spring k_s each.
  Knob: the rigid bounce frequency sqrt(2 k_s / M) over the first elastic frequency.
- shear: every beam Timoshenko (shear flexibility with kappa = 10 (1 + nu) / (12 + 11 nu),
  Cowper's rectangle, G = E / (2 (1 + nu)), and rotary inertia rho I). Knob: the section's
  height h (the width kept); the nominal model carries the same section, Euler-Bernoulli.

Effects outside today's library:
- element_damage: one element (beam and element drawn, not at a free end or at the joint)
  loses a fraction d of its EI (a crack, a corroded or machined stretch). Knob d.
- lap_joint: the joint is a lap of length L_lap (drawn in 20-40 mm) centred on it, covered by
  bonded splice plates of thickness t on both faces: EI times (1 + 2t/h)^3, rho A times
  (1 + 2t/h) over the lap (t = h/2 is a double section). Knob t / h.
- frequency_joint: the joint stiffens or softens with frequency: mode r is the r-th mode of the
  chain whose k1, k2 (every joint) are times (f_r / f_1)^alpha, f_r its own frequency (a fixed
  point), f_1 the first elastic frequency of the base truth; sign of alpha drawn. Knob |alpha|.
- point_mass (this battery's choice of an effect no candidate can mimic well): a shaker's
  force transducer and stinger fixture, or a lifting eye, at one interior node that is not
  measured, not a joint node and not a free end: mass m_p with the rotary inertia of a steel
  cube glued on the top face. Its signature, frequency shifts proportional to w(x_p)^2 (and
  theta(x_p)^2) of each mode at one place, is not that of a joint mass (at the joint), of
  sensor masses (equal at every measured node) or of the other candidates. Knob: m_p as a
  fraction of the beams' mass.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass

import numpy as np

import fe
from geometries import Geometry, with_joints


@dataclass
class Built:
    nominal: fe.Chain
    base: fe.Chain
    effect: fe.Chain
    alpha: float | None = None  # frequency_joint: k(f) = k (f / f_1)^alpha
    description: dict | None = None  # the physical parameters, for truth.json


@dataclass
class Effect:
    name: str
    kind: str  # "library" or "outside"
    knob: str  # what the size is, with its unit
    guess: float  # a first size to try
    upper: float  # the largest physical size
    lower: float = 0.0


EFFECTS = {
    e.name: e
    for e in [
        Effect("joint_coupling", "library", "k12 / sqrt(k1 k2)", 0.1, 0.95),
        Effect("joint_mass", "library", "joint hardware mass / mass of all beams", 0.01, 1.0),
        Effect("sensor_mass", "library", "total sensor mass / mass of all beams", 0.01, 0.5),
        Effect("suspension", "library", "rigid bounce frequency / first elastic frequency", 0.1, 0.5),
        Effect("shear", "library", "section height h (m)", 0.0, 0.0),  # guess, upper: per geometry
        Effect("element_damage", "outside", "lost fraction of the element's EI", 0.1, 0.9),
        Effect("lap_joint", "outside", "splice plate thickness t / section height h", 0.05, 1.0),
        Effect("frequency_joint", "outside", "|alpha| in k(f) = k (f / f_1)^alpha", 0.02, 0.5),
        Effect("point_mass", "outside", "point mass / mass of all beams", 0.005, 0.3),
    ]
}

LIBRARY = [n for n, e in EFFECTS.items() if e.kind == "library"]
OUTSIDE = [n for n, e in EFFECTS.items() if e.kind == "outside"]


def height_of(beam: fe.Beam) -> float:
    return math.sqrt(12.0 * beam.second_moment / beam.area)


def draw_parameters(name: str, geom: Geometry, nominal: fe.Chain, sensors: list, rng: np.random.Generator) -> dict:
    """The effect's parameters other than its size, drawn once per case."""
    if name == "joint_coupling":
        return {"sign": float(rng.choice([-1.0, 1.0]))}
    if name == "joint_mass":
        return {"inertia_ratio": float(math.exp(rng.uniform(math.log(2.0), math.log(9.0))))}
    if name == "element_damage":
        # an element away from the free ends and the joints
        candidates = [(bi, e) for bi, b in enumerate(nominal.beams) for e in range(1, b.elements - 1)]
        bi, e = candidates[int(rng.integers(len(candidates)))]
        return {"beam": int(bi), "element": int(e)}
    if name == "lap_joint":
        return {"lap_length": float(rng.uniform(0.020, 0.040))}
    if name == "frequency_joint":
        return {"sign": float(rng.choice([-1.0, 1.0]))}
    if name == "point_mass":
        joint_nodes = set()
        for j in range(len(nominal.joints)):
            joint_nodes.update({nominal.last_node(j), nominal.first_node(j + 1)})
        ends = {0, nominal.nodes() - 1}
        free = [n for n in range(nominal.nodes()) if n not in joint_nodes | ends | set(sensors)]
        if not free:  # every node measured: any interior node off the joints
            free = [n for n in range(nominal.nodes()) if n not in joint_nodes | ends]
        return {"node": int(free[int(rng.integers(len(free)))])}
    return {}


def per_joint(params: dict, joints: int) -> list:
    """Factors on the size at each joint: ``params["per_joint"]`` when given (the mimicry fits,
    which free one size per joint as a fit of jointid's per-joint candidates would), else 1 at
    every joint (the truths: the same hardware at every joint)."""
    return list(params.get("per_joint", [1.0] * joints))


def build(name: str | None, size: float, geom: Geometry, truth_joints: list, sensors: list, params: dict,
          nominal: fe.Chain | None = None) -> Built:
    """Nominal, base truth and effect truth chains of one case (see module docs). ``nominal``:
    put the effect on this chain instead of the geometry's (the mimicry fits of detect.py,
    which put a library effect on another case's nominal model; not for shear, whose size is
    the section)."""
    if name == "shear":
        nominal = geom.chain(height=size)
    elif nominal is None:
        nominal = geom.chain()
    base = with_joints(nominal, truth_joints)
    eff = copy.deepcopy(base)
    mass = base.total_mass()
    desc: dict = {}
    if name is None:
        pass
    elif name == "joint_coupling":
        s = params["sign"] * size
        for j, per in zip(eff.joints, per_joint(params, len(eff.joints))):
            j.k12 = s * per * math.sqrt(j.k1 * j.k2)
        desc = {"k12_over_sqrt_k1k2": s, "k12": [j.k12 for j in eff.joints]}
    elif name == "joint_mass":
        # one ratio for every joint (the truths), or one per joint (the mimicry fits)
        ratios = params["inertia_ratio"]
        if not isinstance(ratios, list):
            ratios = [ratios] * len(eff.joints)
        for ji, per in enumerate(per_joint(params, len(eff.joints))):
            m = size * per * mass
            for node, beam in ((eff.last_node(ji), eff.beams[ji]), (eff.first_node(ji + 1), eff.beams[ji + 1])):
                inertia = 0.5 * m * ratios[ji] * beam.second_moment / beam.area
                eff.masses.append((node, 0.5 * m, inertia))
        m = size * mass
        desc = {
            "mass_per_joint_kg": m,
            "fraction_of_beam_mass": size,
            "rotary_inertia_per_node_kg_m2": [x[2] for x in eff.masses],
            "inertia_over_jointid_fixed_inertia": params["inertia_ratio"],
        }
    elif name == "sensor_mass":
        ms = size * mass / len(sensors)
        side = (ms / 3000.0) ** (1.0 / 3.0)
        for node in sensors:
            beam = eff.beams[beam_of(eff, node)]
            e = 0.5 * height_of(beam) + 0.5 * side
            if "gyration_heights" in params:  # the mimicry fits: rotary inertia free
                inertia = ms * (params["gyration_heights"] * height_of(beam)) ** 2
            else:  # a cube of side `side` on the face, its centre e off the axis
                inertia = ms * (side**2 / 6.0 + e**2)
            eff.masses.append((node, ms, inertia))
        desc = {"mass_per_sensor_kg": ms, "total_fraction_of_beam_mass": size, "cube_side_m": side, "rotary_inertia_kg_m2": eff.masses[0][2]}
    elif name == "suspension":
        f0, _ = fe.elastic_modes(base, 1)
        ks = 0.5 * (2.0 * math.pi * size * f0[0]) ** 2 * mass
        eff.springs = [(0, ks, 0.0), (eff.nodes() - 1, ks, 0.0)]
        desc = {"spring_per_end_N_per_m": ks, "bounce_over_first_elastic": size}
    elif name == "shear":
        for b in eff.beams:
            b.timoshenko = True
        b0 = eff.beams[0]
        g = b0.youngs_modulus / (2.0 * (1.0 + b0.poisson))
        desc = {
            "height_m": size,
            "width_m": geom.width,
            "height_over_shortest_beam": size / min(b.length for b in eff.beams),
            "shear_coefficient": b0.kappa(),
            "poisson": b0.poisson,
            "shear_modulus_Pa": g,
            "phi_per_beam": [12 * b.youngs_modulus * b.second_moment / (b.kappa() * g * b.area * (b.length / b.elements) ** 2) for b in eff.beams],
        }
    elif name == "element_damage":
        b = eff.beams[params["beam"]]
        l = b.length / b.elements
        e = params["element"]
        b.pieces = [(e * l, (e + 1) * l, 1.0 - size, 1.0)]
        desc = {"beam": params["beam"], "element": e, "lost_fraction_of_EI": size}
    elif name == "lap_joint":
        lap = params["lap_length"]
        for ji in range(len(eff.joints)):
            left, right = eff.beams[ji], eff.beams[ji + 1]
            for beam, x0, x1 in ((left, left.length - lap / 2, left.length), (right, 0.0, lap / 2)):
                r = 1.0 + 2.0 * size
                beam.pieces.append((x0, x1, r**3, r))
        desc = {"lap_length_m": lap, "plate_thickness_over_h": size, "EI_factor": (1 + 2 * size) ** 3, "mass_factor": 1 + 2 * size}
    elif name == "frequency_joint":
        desc = {"alpha": params["sign"] * size}
        return Built(nominal, base, eff, params["sign"] * size, desc)
    elif name == "point_mass":
        m = size * mass
        side = (m / 7850.0) ** (1.0 / 3.0)
        node = params["node"]
        beam = eff.beams[beam_of(eff, node)]
        e = 0.5 * height_of(beam) + 0.5 * side
        eff.masses.append((node, m, m * (side**2 / 6.0 + e**2)))
        desc = {"node": node, "mass_kg": m, "fraction_of_beam_mass": size, "rotary_inertia_kg_m2": eff.masses[0][2]}
    else:
        raise ValueError(name)
    return Built(nominal, base, eff, None, desc)


def beam_of(chain: fe.Chain, node: int) -> int:
    for bi in range(len(chain.beams)):
        if chain.first_node(bi) <= node <= chain.last_node(bi):
            return bi
    raise ValueError(node)


def shear_bounds(geom: Geometry) -> tuple[float, float, float]:
    """Guess, lower and upper section height for the shear effect: from 1/50 of the geometry's
    height up to half its shortest beam."""
    shortest = min(l for l, _ in geom.beams)
    return geom.height, 0.02 * geom.height, 0.5 * shortest
