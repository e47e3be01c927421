//! The [`Structure`] of a chain: DOFs, base K and M (beam elements, support springs, point
//! masses), the joint parameters of eq. (17) with dK/dp (eq. (8)), the sites of the effects.
//!
//! DOFs: `w` then `theta` of every node in node order, less those a support removes, then the
//! translation of every mass that hangs on a spring. Base matrices are summed in the order
//! elements, support springs, masses, sensor masses; the parameters' p_i dK/dp_i come after
//! (see [`Structure::assemble`]): k1, k2 of every joint, then the support stiffnesses and the
//! masses the model identifies (`identify`). A free-free chain of uniform beams therefore has
//! DOF index 2 node + (0 for w, 1 for theta) and bitwise the matrices of a dense assembly
//! element by element.

use super::Chain;
use super::beam::{element_mass, element_stiffness};
use super::joint::{JointStiffness, parameter_name};
use super::mesh::Mesh;
use super::support::{SPRING_NAMES, SPRING_UNITS, rigid_body_modes};
use crate::structure::{
    Direction, DofInfo, DofMap, ElementSite, EndSite, HeldCoupling, HeldMotions, JointSite,
    LineElement, Matrices, Parameter, Role, Sites, SparseSym, Structure, SupportSite, SymMatrix,
};

/// Abscissae closer than this fraction of the chain's length are one position.
const SAME_X: f64 = 1e-9;

impl Chain {
    /// The structure of this chain.
    pub fn build(&self) -> Structure {
        let mesh = Mesh::of(self);
        let tol = SAME_X * self.length();
        let same = |a: f64, b: f64| (a - b).abs() <= tol;
        // DOF numbering.
        let mut infos = Vec::new();
        let mut constrained = Vec::new();
        let mut node_dofs: Vec<[Option<usize>; 2]> = Vec::with_capacity(mesh.nodes.len());
        for (n, node) in mesh.nodes.iter().enumerate() {
            let mut pair = [None, None];
            for (k, direction) in [Direction::W, Direction::Theta].into_iter().enumerate() {
                let label = DofMap::node_label(n, direction);
                if let Some((i, s)) = self
                    .supports
                    .iter()
                    .enumerate()
                    .find(|(_, s)| same(s.x, node.x) && s.kind.removes(direction))
                {
                    constrained.push((
                        label,
                        format!("support[{i}] ({} at x = {} m)", s.kind.name(), s.x),
                    ));
                    continue;
                }
                pair[k] = Some(infos.len());
                infos.push(DofInfo {
                    label,
                    position: [node.x, 0.0, 0.0],
                    direction,
                    node: Some(n),
                });
            }
            node_dofs.push(pair);
        }
        let hanging: Vec<usize> = (0..self.masses.len())
            .filter(|&i| self.masses[i].spring.is_some())
            .map(|i| {
                infos.push(DofInfo {
                    label: format!("mass{i}:w"),
                    position: [self.masses[i].x, 0.0, 0.0],
                    direction: Direction::W,
                    node: None,
                });
                infos.len() - 1
            })
            .collect();
        let n = infos.len();
        let node_at = |x: f64| {
            mesh.nodes
                .iter()
                .position(|node| same(node.x, x))
                .expect("the mesh has a node at every feature")
        };
        let lines: Vec<LineElement> = mesh
            .elements
            .iter()
            .map(|e| {
                let [a, b] = e.nodes;
                LineElement {
                    x: [mesh.nodes[a].x, mesh.nodes[b].x],
                    dofs: [
                        node_dofs[a][0],
                        node_dofs[a][1],
                        node_dofs[b][0],
                        node_dofs[b][1],
                    ],
                }
            })
            .collect();
        // The motions the rigid supports hold, where one node is held (not at a joint).
        let mut supports = Vec::new();
        let mut node_held: Vec<[Option<usize>; 2]> = vec![[None, None]; mesh.nodes.len()];
        let mut held_count = 0;
        for s in &self.supports {
            let mut at = mesh
                .nodes
                .iter()
                .enumerate()
                .filter(|(_, n)| same(n.x, s.x));
            let (Some((node, _)), None) = (at.next(), at.next()) else {
                continue;
            };
            let held: Vec<Direction> = [Direction::W, Direction::Theta]
                .into_iter()
                .filter(|&d| s.kind.removes(d))
                .collect();
            if held.is_empty() {
                continue;
            }
            for &d in &held {
                node_held[node][usize::from(d == Direction::Theta)] = Some(held_count);
                held_count += 1;
            }
            let section = mesh
                .elements
                .iter()
                .find(|e| e.nodes.contains(&node))
                .expect("every node is on an element")
                .section;
            supports.push(SupportSite {
                x: mesh.nodes[node].x,
                section,
                held,
            });
        }
        let mut held = HeldRecorder::new(held_count);
        // Base matrices.
        let (mut k, mut m) = (Vec::new(), Vec::new());
        for (e, line) in mesh.elements.iter().zip(&lines) {
            let ke = element_stiffness(&e.section, e.length);
            let me = element_mass(&e.section, e.length);
            let local_held: [Option<usize>; 4] =
                std::array::from_fn(|i| node_held[e.nodes[i / 2]][i % 2]);
            for i in 0..4 {
                for j in 0..4 {
                    if let (Some(di), Some(dj)) = (line.dofs[i], line.dofs[j]) {
                        k.push((di, dj, ke[i][j]));
                        m.push((di, dj, me[i][j]));
                    }
                    if let Some(h) = local_held[i] {
                        held.record(h, line.dofs[j], local_held[j], ke[i][j], me[i][j]);
                    }
                }
            }
        }
        // Grounded springs of the supports: in the base, or parameters after the joints'.
        let mut extra: Vec<Parameter> = Vec::new();
        for (i, s) in self.supports.iter().enumerate() {
            let values = s.kind.springs();
            for (slot, name) in SPRING_NAMES.into_iter().enumerate() {
                if values[slot] <= 0.0 {
                    continue;
                }
                let dofs: Vec<usize> = mesh
                    .nodes
                    .iter()
                    .zip(&node_dofs)
                    .filter(|(node, _)| same(node.x, s.x))
                    .filter_map(|(_, d)| d[slot])
                    .collect();
                if s.identify[slot] {
                    let mut pattern = SparseSym::zero();
                    for &d in &dofs {
                        pattern.push(d, d, 1.0);
                    }
                    extra.push(Parameter {
                        name: format!("support{i}.{name}"),
                        unit: SPRING_UNITS[slot],
                        value: values[slot],
                        stiffness: pattern,
                        mass: SparseSym::zero(),
                        role: Role::Identified,
                    });
                } else {
                    k.extend(dofs.iter().map(|&d| (d, d, values[slot])));
                }
            }
        }
        let mut hanging_dof = hanging.iter();
        for (i, p) in self.masses.iter().enumerate() {
            let [w, theta] = node_dofs[node_at(p.x)];
            // (DOF, mass on it): translation m, rotation J of a rigidly attached mass.
            let carried: Vec<(usize, f64)> = match p.spring {
                None => w
                    .map(|w| (w, p.mass))
                    .into_iter()
                    .chain(
                        theta
                            .filter(|_| p.rotary_inertia > 0.0)
                            .map(|t| (t, p.rotary_inertia)),
                    )
                    .collect(),
                Some(spring) => {
                    let own = *hanging_dof.next().expect("a DOF per hanging mass");
                    spring_entries(&mut k, w, Some(own), spring);
                    vec![(own, p.mass)]
                }
            };
            if p.identify {
                // dM/dm: the rotary inertia scales with the mass.
                let mut dm = SparseSym::zero();
                for &(d, value) in &carried {
                    dm.push(d, d, value / p.mass);
                }
                extra.push(Parameter {
                    name: format!("mass{i}.m"),
                    unit: "kg",
                    value: p.mass,
                    stiffness: SparseSym::zero(),
                    mass: dm,
                    role: Role::Identified,
                });
            } else {
                m.extend(carried.iter().map(|&(d, value)| (d, d, value)));
            }
        }
        for s in self.sensors.iter().filter(|s| s.mass > 0.0) {
            if let Some(w) = node_dofs[node_at(s.x)][0] {
                m.push((w, w, s.mass));
            }
        }
        // Joint parameters.
        let mut parameters = Vec::new();
        let mut joints = Vec::new();
        for (j, joint) in self.joints.iter().enumerate() {
            let (a, b) = (mesh.beam_ends[j].1, mesh.beam_ends[j + 1].0);
            let first = parameters.len();
            for (kind, role) in JointStiffness::ALL.into_iter().zip(joint.roles) {
                let slot = match kind {
                    JointStiffness::Transversal => 0,
                    JointStiffness::Rotational => 1,
                };
                let mut stiffness = Vec::new();
                spring_entries(&mut stiffness, node_dofs[a][slot], node_dofs[b][slot], 1.0);
                let mut pattern = SparseSym::zero();
                for (i, j, v) in stiffness {
                    pattern.push(i, j, v);
                }
                parameters.push(Parameter {
                    name: parameter_name(j, self.joints.len(), kind),
                    unit: kind.unit(),
                    value: kind.of(joint),
                    stiffness: pattern,
                    mass: SparseSym::zero(),
                    role,
                });
            }
            let beam_a = &self.beams[j];
            joints.push(JointSite {
                x: mesh.nodes[a].x,
                w: [node_dofs[a][0], node_dofs[b][0]],
                theta: [node_dofs[a][1], node_dofs[b][1]],
                sections: [
                    beam_a.section_at(beam_a.length),
                    self.beams[j + 1].section_at(0.0),
                ],
                parameters: [first, first + 1],
            });
        }
        parameters.extend(extra);
        let elements = mesh
            .elements
            .iter()
            .zip(&lines)
            .map(|(e, line)| ElementSite {
                beam: e.beam,
                line: line.clone(),
                section: e.section,
            })
            .collect();
        let last = mesh.nodes.len() - 1;
        let free_ends = [0, last]
            .into_iter()
            .filter(|&node| !self.supports.iter().any(|s| same(s.x, mesh.nodes[node].x)))
            .filter_map(|node| match node_dofs[node] {
                [Some(w), Some(theta)] => Some(EndSite {
                    x: mesh.nodes[node].x,
                    w,
                    theta,
                }),
                _ => None,
            })
            .collect();
        let dofs = DofMap::new(infos, lines, constrained);
        let sensors = self
            .sensors
            .iter()
            .map(|s| {
                let mut o = dofs
                    .at_x(s.x, s.direction)
                    .expect("declared sensors are validated on the chain");
                if let Some(label) = &s.label {
                    o.label = label.clone();
                }
                o
            })
            .collect();
        Structure {
            base: Matrices {
                k: SymMatrix::from_entries(n, &k),
                m: SymMatrix::from_entries(n, &m),
            },
            parameters,
            dofs,
            sensors,
            rigid: rigid_body_modes(&self.supports),
            sites: Sites {
                beam_mass: self.beam_mass(),
                beams: self.beams.len(),
                joints,
                elements,
                free_ends,
                supports,
                held: held.finish(),
            },
        }
    }
}

/// Collects the beam's stiffness and mass on the held motions, element entry by entry.
struct HeldRecorder {
    stiffness_own: Vec<Vec<f64>>,
    mass_own: Vec<Vec<f64>>,
    // (held motion, DOF) -> (stiffness, mass)
    free: std::collections::BTreeMap<(usize, usize), (f64, f64)>,
}

impl HeldRecorder {
    fn new(count: usize) -> Self {
        Self {
            stiffness_own: vec![vec![0.0; count]; count],
            mass_own: vec![vec![0.0; count]; count],
            free: std::collections::BTreeMap::new(),
        }
    }

    /// The element entry (k, m) between held motion `h` and a DOF or another held motion.
    fn record(&mut self, h: usize, dof: Option<usize>, other: Option<usize>, k: f64, m: f64) {
        match (dof, other) {
            (Some(d), _) => {
                let e = self.free.entry((h, d)).or_insert((0.0, 0.0));
                e.0 += k;
                e.1 += m;
            }
            (None, Some(g)) => {
                self.stiffness_own[h][g] += k;
                self.mass_own[h][g] += m;
            }
            // A DOF removed by a support that stays rigid: ground.
            (None, None) => {}
        }
    }

    fn finish(self) -> HeldMotions {
        let count = self.stiffness_own.len();
        let (mut kf, mut mf) = (vec![Vec::new(); count], vec![Vec::new(); count]);
        for ((h, d), (k, m)) in self.free {
            kf[h].push((d, k));
            mf[h].push((d, m));
        }
        HeldMotions {
            stiffness: HeldCoupling {
                own: self.stiffness_own,
                free: kf,
            },
            mass: HeldCoupling {
                own: self.mass_own,
                free: mf,
            },
        }
    }
}

/// The entries of a spring of stiffness `value` between DOFs `a` and `b`, in the order of
/// [`SparseSym::spring`]; a removed end (`None`) is the ground.
fn spring_entries(
    out: &mut Vec<(usize, usize, f64)>,
    a: Option<usize>,
    b: Option<usize>,
    value: f64,
) {
    if let Some(a) = a {
        out.push((a, a, value));
    }
    if let Some(b) = b {
        out.push((b, b, value));
    }
    if let (Some(a), Some(b)) = (a, b) {
        out.push((a, b, -value));
        out.push((b, a, -value));
    }
}
