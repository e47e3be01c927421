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

use super::beam::{element_mass, element_stiffness};
use super::joint::{JointStiffness, parameter_name};
use super::lap::{LAP_UNIT, ROOT_UNIT};
use super::layered::{self, Laps};
use super::mesh::{Mesh, SAME_X};
use super::support::{SPRING_NAMES, SPRING_UNITS, rigid_body_modes};
use super::{Chain, PointMass};
use crate::structure::{
    Alternative, Direction, DofInfo, DofMap, ElementSite, EndSite, HeldCoupling, HeldMotions,
    JointSite, LineElement, Matrices, Parameter, Role, Sites, SparseSym, Structure, SupportSite,
    SymMatrix, terms_at,
};

impl Chain {
    /// The structure of this chain.
    pub fn build(&self) -> Structure {
        let mesh = Mesh::of(self);
        let tol = SAME_X * self.length();
        let (mut infos, constrained, node_dofs) = number_nodes(self, &mesh, tol);
        let layout = Layout {
            chain: self,
            mesh,
            tol,
            node_dofs,
        };
        let hanging = layout.hanging_dofs(&mut infos);
        let laps = Laps::number(self, &layout.mesh, &layout.node_dofs, tol, &mut infos);
        let n = infos.len();
        let mut lines = layout.lines();
        laps.hinge(&mut lines);
        let (supports, node_held, held_count) = layout.held_supports();
        // Base matrices: elements, support springs, masses, sensor masses; the parameters
        // after the joints': identified support springs and masses.
        let (mut k, mut m) = (Vec::new(), Vec::new());
        let held = layout.elements(&lines, &node_held, held_count, &mut k, &mut m);
        let mut extra = layout.support_springs(&lines, &mut k);
        extra.extend(layout.masses(&lines, &hanging, &mut k, &mut m));
        layout.sensor_masses(&lines, &mut m);
        let (mut lap_k, mut lap_m) = (SparseSym::zero(), SparseSym::zero());
        laps.base(&mut lap_k, &mut lap_m);
        k.extend_from_slice(lap_k.entries());
        m.extend_from_slice(lap_m.entries());
        let (mut parameters, joints) = layout.joints(&laps);
        parameters.extend(extra);
        let elements = layout
            .mesh
            .elements
            .iter()
            .zip(&lines)
            .map(|(e, line)| ElementSite {
                beam: e.beam,
                line: line.clone(),
                section: e.section,
            })
            .collect();
        let free_ends = layout.free_ends();
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
            }
            .into(),
            parameters,
            dofs: dofs.into(),
            sensors,
            rigid: rigid_body_modes(&self.supports) + laps.rigid(),
            sites: Sites {
                beam_mass: self.beam_mass(),
                beams: self.beams.len(),
                joints,
                elements,
                free_ends,
                supports,
                held: held.finish(),
            },
            alternatives: self.alternatives(),
            open_faces: 0,
            reduced: None,
        }
    }

    /// The layered lap in place of every point joint whose overlap the model gives.
    fn alternatives(&self) -> Vec<Alternative> {
        if self.joints.iter().any(|j| j.lap.is_some_and(|l| !l.active)) {
            vec![Alternative {
                name: LAYERED_LAP,
                structure: std::sync::Arc::new(self.with_laps().build()),
            }]
        } else {
            Vec::new()
        }
    }
}

/// The name of the alternative in which the point joints with an overlap are layered laps.
pub const LAYERED_LAP: &str = "layered_lap";

/// Matrix entries (row, column, value), summed in their order.
type Entries = Vec<(usize, usize, f64)>;

/// The entries of value c c^T, c the observation `terms` ((DOF, coefficient)).
fn outer(terms: &[(usize, f64)], value: f64) -> impl Iterator<Item = (usize, usize, f64)> + '_ {
    terms
        .iter()
        .flat_map(move |&(a, ca)| terms.iter().map(move |&(b, cb)| (a, b, value * ca * cb)))
}

/// Per node, its (w, theta) DOF or held motion (`None` where it has none).
type PerNode = Vec<[Option<usize>; 2]>;

/// The DOFs of the nodes: w then theta of every node in node order, less those a support
/// removes (each recorded with the support that removed it). Returns the DOFs' descriptions,
/// the removed labels and every node's (w, theta) DOF.
fn number_nodes(
    chain: &Chain,
    mesh: &Mesh,
    tol: f64,
) -> (Vec<DofInfo>, Vec<(String, String)>, PerNode) {
    let mut infos = Vec::new();
    let mut constrained = Vec::new();
    let mut node_dofs: PerNode = Vec::with_capacity(mesh.nodes.len());
    for (n, node) in mesh.nodes.iter().enumerate() {
        let mut pair = [None, None];
        for (k, direction) in [Direction::W, Direction::Theta].into_iter().enumerate() {
            let label = DofMap::node_label(n, direction);
            if let Some((i, s)) = chain
                .supports
                .iter()
                .enumerate()
                .find(|(_, s)| (s.x - node.x).abs() <= tol && s.kind.removes(direction))
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
    (infos, constrained, node_dofs)
}

/// What the steps of a build share: the chain, its mesh and every node's (w, theta) DOF.
struct Layout<'a> {
    chain: &'a Chain,
    mesh: Mesh,
    /// Abscissae closer than this are one position, m.
    tol: f64,
    node_dofs: PerNode,
}

impl Layout<'_> {
    fn same(&self, a: f64, b: f64) -> bool {
        (a - b).abs() <= self.tol
    }

    fn node_at(&self, x: f64) -> usize {
        self.node_near(x)
            .expect("the mesh has a node at every feature")
    }

    /// The first node at abscissa `x`, if the mesh has one there (module `mesh`).
    fn node_near(&self, x: f64) -> Option<usize> {
        self.mesh.nodes.iter().position(|node| self.same(node.x, x))
    }

    /// A DOF (its translation) for every mass that hangs on a spring, after the nodes'.
    fn hanging_dofs(&self, infos: &mut Vec<DofInfo>) -> Vec<usize> {
        let masses = &self.chain.masses;
        (0..masses.len())
            .filter(|&i| masses[i].spring.is_some())
            .map(|i| {
                infos.push(DofInfo {
                    label: format!("mass{i}:w"),
                    position: [masses[i].x, 0.0, 0.0],
                    direction: Direction::W,
                    node: None,
                });
                infos.len() - 1
            })
            .collect()
    }

    /// Every element's ends and DOFs.
    fn lines(&self) -> Vec<LineElement> {
        let (nodes, dofs) = (&self.mesh.nodes, &self.node_dofs);
        self.mesh
            .elements
            .iter()
            .map(|e| {
                let [a, b] = e.nodes;
                LineElement {
                    x: [nodes[a].x, nodes[b].x],
                    dofs: [dofs[a][0], dofs[a][1], dofs[b][0], dofs[b][1]],
                }
            })
            .collect()
    }

    /// The motions the rigid supports hold, where one node is held (not at a joint): the
    /// supports' sites, every node's held motions (index among all held ones) and their count.
    fn held_supports(&self) -> (Vec<SupportSite>, PerNode, usize) {
        let mesh = &self.mesh;
        let mut supports = Vec::new();
        let mut node_held: PerNode = vec![[None, None]; mesh.nodes.len()];
        let mut held_count = 0;
        for s in &self.chain.supports {
            let mut at = mesh
                .nodes
                .iter()
                .enumerate()
                .filter(|(_, n)| self.same(n.x, s.x));
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
        (supports, node_held, held_count)
    }

    /// The beam elements' stiffness and mass entries into `k`, `m`; their entries on the held
    /// motions recorded.
    fn elements(
        &self,
        lines: &[LineElement],
        node_held: &PerNode,
        held_count: usize,
        k: &mut Entries,
        m: &mut Entries,
    ) -> HeldRecorder {
        let mut held = HeldRecorder::new(held_count);
        for (e, line) in self.mesh.elements.iter().zip(lines) {
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
        held
    }

    /// The supports' grounded springs: into `k`, or as identified parameters (returned). On
    /// every node at the support's abscissa, or, between nodes (module `mesh`), k c c^T of the
    /// interpolation c of the motion along `lines`.
    fn support_springs(&self, lines: &[LineElement], k: &mut Entries) -> Vec<Parameter> {
        let mut extra = Vec::new();
        for (i, s) in self.chain.supports.iter().enumerate() {
            let values = s.kind.springs();
            for (slot, name) in SPRING_NAMES.into_iter().enumerate() {
                if values[slot] <= 0.0 {
                    continue;
                }
                let unit: Entries = if self.node_near(s.x).is_some() {
                    // Every node there: at a joint's abscissa, both beams' ends.
                    self.mesh
                        .nodes
                        .iter()
                        .zip(&self.node_dofs)
                        .filter(|(node, _)| self.same(node.x, s.x))
                        .filter_map(|(_, d)| d[slot])
                        .map(|d| (d, d, 1.0))
                        .collect()
                } else {
                    let direction = [Direction::W, Direction::Theta][slot];
                    let terms = terms_at(lines, s.x, direction).unwrap_or_default();
                    outer(&terms, 1.0).collect()
                };
                if s.identify[slot] {
                    let mut pattern = SparseSym::zero();
                    for &(a, b, v) in &unit {
                        pattern.push(a, b, v);
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
                    k.extend(unit.iter().map(|&(a, b, v)| (a, b, values[slot] * v)));
                }
            }
        }
        extra
    }

    /// The point masses (on their node, between nodes by the elements' interpolation along
    /// `lines` (module `mesh`), or hanging on a spring from its own DOF `hanging`): into `m` (a
    /// spring into `k`), or as identified parameters (returned).
    fn masses(
        &self,
        lines: &[LineElement],
        hanging: &[usize],
        k: &mut Entries,
        m: &mut Entries,
    ) -> Vec<Parameter> {
        let mut extra = Vec::new();
        let mut hanging_dof = hanging.iter();
        for (i, p) in self.chain.masses.iter().enumerate() {
            // (DOF, DOF, mass on them): translation m, rotation J of a rigidly attached mass.
            let carried: Entries = match p.spring {
                None => self.attached(lines, p),
                Some(spring) => {
                    let [w, _] = self.node_dofs[self.node_at(p.x)];
                    let own = *hanging_dof.next().expect("a DOF per hanging mass");
                    spring_entries(k, w, Some(own), spring);
                    vec![(own, own, p.mass)]
                }
            };
            if p.identify {
                // dM/dm: the rotary inertia scales with the mass.
                let mut dm = SparseSym::zero();
                for &(a, b, value) in &carried {
                    dm.push(a, b, value / p.mass);
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
                m.extend_from_slice(&carried);
            }
        }
        extra
    }

    /// The mass matrix entries of the rigidly attached point mass `p`: m on its node's
    /// translation and J on its rotation, or, between nodes (module `mesh`), m c c^T + J d d^T
    /// of the interpolations c, d of the translation and the rotation along `lines`.
    fn attached(&self, lines: &[LineElement], p: &PointMass) -> Entries {
        let on_node = self.node_near(p.x);
        let spread = |direction: Direction, value: f64| -> Entries {
            let terms = match on_node {
                Some(node) => {
                    let [w, theta] = self.node_dofs[node];
                    let dof = if direction == Direction::W { w } else { theta };
                    dof.map(|d| vec![(d, 1.0)]).unwrap_or_default()
                }
                None => terms_at(lines, p.x, direction).unwrap_or_default(),
            };
            outer(&terms, value).collect::<Entries>()
        };
        let mut carried = spread(Direction::W, p.mass);
        if p.rotary_inertia > 0.0 {
            carried.extend(spread(Direction::Theta, p.rotary_inertia));
        }
        carried
    }

    /// The sensors' masses on their translations, into `m`: m c c^T of the translation c^T u
    /// the sensor reads along `lines` (its node's, or between nodes the interpolation: module
    /// `mesh`); none where a support holds it.
    fn sensor_masses(&self, lines: &[LineElement], m: &mut Entries) {
        for s in self.chain.sensors.iter().filter(|s| s.mass > 0.0) {
            let Ok(terms) = terms_at(lines, s.x, Direction::W) else {
                continue;
            };
            m.extend(outer(&terms, s.mass));
        }
    }

    /// The joints' k1, k2 (eq. (17)), or a layered lap's k_n, k_s, with dK/dp (eq. (8)), and
    /// the joints' sites.
    fn joints(&self, laps: &Laps) -> (Vec<Parameter>, Vec<JointSite>) {
        let (chain, mesh, node_dofs) = (self.chain, &self.mesh, &self.node_dofs);
        let mut parameters = Vec::new();
        let mut joints = Vec::new();
        for (j, joint) in chain.joints.iter().enumerate() {
            let (a, b) = (mesh.beam_ends[j].1, mesh.beam_ends[j + 1].0);
            let first = parameters.len();
            let interface = laps.interface(j);
            if let (Some(patterns), Some(lap)) = (&interface, joint.active_lap()) {
                for (slot, pattern) in patterns.iter().enumerate() {
                    parameters.push(Parameter {
                        name: layered::parameter_name(j, chain.joints.len(), slot),
                        unit: LAP_UNIT,
                        value: [lap.k_n, lap.k_s][slot],
                        stiffness: pattern.clone(),
                        mass: SparseSym::zero(),
                        role: lap.roles[slot],
                    });
                }
            }
            let root = match (laps.roots(j), joint.active_lap().and_then(|l| l.k_r)) {
                (Some(pattern), Some(k_r)) => {
                    parameters.push(Parameter {
                        name: layered::root_name(j, chain.joints.len()),
                        unit: ROOT_UNIT,
                        value: k_r,
                        stiffness: pattern,
                        mass: SparseSym::zero(),
                        role: joint.active_lap().map_or(Role::Identified, |l| l.root_role),
                    });
                    Some(parameters.len() - 1)
                }
                _ => None,
            };
            let points = if interface.is_some() {
                &[][..]
            } else {
                &JointStiffness::ALL[..]
            };
            for (&kind, &role) in points.iter().zip(&joint.roles) {
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
                    name: parameter_name(j, chain.joints.len(), kind),
                    unit: kind.unit(),
                    value: kind.of(joint),
                    stiffness: pattern,
                    mass: SparseSym::zero(),
                    role,
                });
            }
            let beam_a = &chain.beams[j];
            joints.push(JointSite {
                x: mesh.nodes[a].x,
                w: [node_dofs[a][0], node_dofs[b][0]],
                theta: [node_dofs[a][1], node_dofs[b][1]],
                sections: [
                    beam_a.section_at(beam_a.length),
                    chain.beams[j + 1].section_at(0.0),
                ],
                parameters: [first, first + 1],
                lap: interface.is_some(),
                root,
            });
        }
        (parameters, joints)
    }

    /// The chain's ends that no support holds, with both DOFs.
    fn free_ends(&self) -> Vec<EndSite> {
        let nodes = &self.mesh.nodes;
        [0, nodes.len() - 1]
            .into_iter()
            .filter(|&node| {
                !self
                    .chain
                    .supports
                    .iter()
                    .any(|s| self.same(s.x, nodes[node].x))
            })
            .filter_map(|node| match self.node_dofs[node] {
                [Some(w), Some(theta)] => Some(EndSite {
                    x: nodes[node].x,
                    w,
                    theta,
                }),
                _ => None,
            })
            .collect()
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
fn spring_entries(out: &mut Entries, a: Option<usize>, b: Option<usize>, value: f64) {
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
