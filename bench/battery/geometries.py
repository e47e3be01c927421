"""The geometries of the battery: free-free chains of 2 and 3 beams, steel and aluminium.

Independence: chosen for this battery, not taken from jointid except paper case I's geometry
(models/paper-case-1.toml, the README's worked example). Every beam is a solid rectangle of
width b and height h (bending about the width axis): A = b h, I = b h^3 / 12, h = sqrt(12 I / A).

The joints' stiffnesses are set against the beams' own, so that the joint matters in the low
modes (k2 L / EI between about 0.1 and 10, k1 L^3 / (12 EI) between about 0.2 and 20): a joint
that is nearly rigid or nearly free would leave nothing to calibrate.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass

import fe

STEEL = dict(youngs_modulus=2.1e11, density=7850.0, poisson=0.29)
ALUMINIUM = dict(youngs_modulus=7.0e10, density=2700.0, poisson=0.33)


@dataclass
class Geometry:
    id: str
    material: str
    width: float  # m
    height: float  # m
    beams: list  # (length m, elements)
    joints: list  # (k1 N/m, k2 N m/rad), nominal

    def chain(self, height: float | None = None) -> fe.Chain:
        """The nominal chain (Euler-Bernoulli, the nominal joints); ``height`` overrides h."""
        h = self.height if height is None else height
        mat = STEEL if self.material == "steel" else ALUMINIUM
        beams = [
            fe.Beam(length=l, elements=n, area=self.width * h, second_moment=self.width * h**3 / 12.0, **mat)
            for l, n in self.beams
        ]
        return fe.Chain(beams=beams, joints=[fe.Joint(k1=k1, k2=k2) for k1, k2 in self.joints])


GEOMETRIES = [
    # paper case I: steel 60 x 40 mm, 0.20 m in 7 + 0.30 m in 10 elements, the paper's joint
    Geometry("steel2-paper", "steel", 0.060, 0.040, [(0.20, 7), (0.30, 10)], [(1.0e7, 1.0e4)]),
    # aluminium flat bar 40 x 12 mm, long beams, fine meshes
    Geometry("alu2-flat", "aluminium", 0.040, 0.012, [(0.45, 12), (0.35, 9)], [(1.0e6, 1.5e3)]),
    # steel 30 x 20 mm, three beams, two different joints
    Geometry("steel3-bar", "steel", 0.030, 0.020, [(0.30, 8), (0.25, 6), (0.40, 11)], [(5.0e6, 8.0e3), (3.0e6, 5.0e3)]),
    # aluminium 25 x 25 mm, three beams, coarse meshes
    Geometry("alu3-square", "aluminium", 0.025, 0.025, [(0.25, 6), (0.20, 5), (0.35, 9)], [(5.0e6, 2.0e3), (2.0e6, 5.0e3)]),
    # steel 50 x 60 mm, short thick beams (h / L 0.2 - 0.24: shear matters)
    Geometry("steel2-thick", "steel", 0.050, 0.060, [(0.25, 8), (0.30, 10)], [(5.0e7, 5.0e4)]),
    # aluminium 40 x 50 mm, short thick beams (h / L 0.23 - 0.25)
    Geometry("alu2-thick", "aluminium", 0.040, 0.050, [(0.20, 7), (0.22, 8)], [(2.0e7, 2.0e4)]),
    # steel flat 20 x 8 mm, long slender beams, 15 + 10 elements
    Geometry("steel2-slender", "steel", 0.020, 0.008, [(0.60, 15), (0.40, 10)], [(2.0e5, 3.0e2)]),
]

BY_ID = {g.id: g for g in GEOMETRIES}


def with_joints(chain: fe.Chain, joints: list) -> fe.Chain:
    c = copy.deepcopy(chain)
    c.joints = [fe.Joint(k1=j.k1, k2=j.k2, k12=j.k12) for j in joints]
    return c
