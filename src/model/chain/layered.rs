//! The layered lap in the chain's structure: over a joint's overlap ([`super::lap`]) the two
//! beams are two Euler-Bernoulli layers with axial motion, joined by the interface elements of
//! [`super::interface`]; the interface's k_n and k_s are the joint's parameters in place of
//! k1, k2 (K is linear in them).
//!
//! DOFs. The chain's own DOFs keep their numbers and meanings: over the overlap the left
//! beam's nodes (left of the joint's abscissa) are the upper layer's, the right beam's nodes
//! (right of it) the lower layer's, and a sensor there reads that layer. Appended after them,
//! in this order:
//! - per beam that a lap touches, the axial displacement `beam<b>.<k>:x` at every node k of its
//!   part outside the overlaps: a bar of two-node elements on the beam's mesh, unless a
//!   clamped or pinned support holds it. The layers' offsets couple bending to this axial
//!   motion, and the first axial mode of a free lapped bar (c / (2 L), 4.2 kHz for 0.6 m of
//!   steel) is near enough to the bending modes measured that a rigid part would stiffen them:
//!   by 2.6% on the sixth mode of the 3D half-lap of `tests/fixtures/lap3d`;
//! - per lap, the upper layer's w, theta where the left beam has no node (right of the
//!   joint), then the lower layer's (left of it); each layer's axial displacement at every
//!   overlap node and at the middle of every overlap element (`lap<j>.upper<k>:x`,
//!   `lap<j>.upper<k>m:x`; quadratic bar elements);
//! - where the lap's k_r is given, the layer's own rotation at each notched root
//!   (`lap<j>.upper0:theta`, `lap<j>.lower<n>:theta`; [`super::notch`]): the layer's first
//!   (last) element and the interface there take it, the beam keeps the node's, and the
//!   parameter k_r joins the two, dK/dk_r = sum over the roots of (e_beam - e_layer)(...)^T.
//!
//! Where a layer continues into its beam (the upper layer at the overlap's start, the lower at
//! its end), plane sections tie its axial displacement to the beam's: u = U_b - offset theta,
//! theta the beam's (a notch's hinge lies at the layer's centroid).
//! Where the beam has no part outside the overlap the layer's end is axially free. The axial
//! translation of every group of beams joined by laps is a rigid-body mode unless a support
//! holds one of them: it adds one to the chain's count.

use super::Chain;
use super::beam::{Beam, element_mass, element_stiffness};
use super::interface::{
    bar_mass, bar_stiffness, linear_bar_mass, linear_bar_stiffness, normal, shear,
};
use super::joint::Joint;
use super::lap::{LAP_PARAMETERS, Lap, ROOT_PARAMETER};
use super::mesh::{Mesh, MeshElement};
use super::support::{Support, SupportKind};
use crate::input::{FieldCheck, InputError};
use crate::structure::{Direction, DofInfo, LineElement, SparseSym};

/// A DOF of an element as a combination of global DOFs: sum of coefficient x DOF.
type Combo = Vec<(usize, f64)>;

/// How the part of a beam outside the overlaps moves axially.
#[derive(Debug, Clone, PartialEq)]
enum Outer {
    /// No lap touches the beam, or it has no part outside its overlaps.
    Absent,
    /// Held by a clamped or pinned support.
    Held,
    /// Free: a bar along it ([`OuterBar`]).
    Free(OuterBar),
}

/// The axial motion of a beam's part outside the overlaps: two-node bar elements on the
/// beam's own mesh, an axial DOF at each of their nodes. The part's axial flexibility couples
/// through the layers' offsets to the bending modes near the first axial mode.
#[derive(Debug, Clone, PartialEq)]
struct OuterBar {
    /// Per mesh node of the part: (the node, its axial DOF).
    dofs: Vec<(usize, usize)>,
    /// Per element of the part: its two axial DOFs, its length, EA and mass per length.
    elements: Vec<([usize; 2], f64, f64, f64)>,
}

impl OuterBar {
    /// The axial DOF of mesh node `node`, which must be the part's.
    fn at(&self, node: usize) -> usize {
        self.dofs
            .iter()
            .find(|(n, _)| *n == node)
            .map(|(_, d)| *d)
            .expect("a layer's root is a node of its beam's outer part")
    }
}

/// A layer's notched root (`super::notch`): the beam's rotation and the layer's, which a
/// spring of stiffness k_r joins.
#[derive(Debug, Clone, Copy)]
struct Hinge {
    /// The beam's theta at the root.
    beam: Option<usize>,
    /// The layer's own theta there.
    layer: usize,
    /// The chain's element (index into the mesh's) that the layer begins or ends with, and
    /// which of its ends (0, 1) is the root.
    element: (usize, usize),
}

/// One lap's DOFs.
#[derive(Debug, Clone)]
struct LapDofs {
    joint: usize,
    lap: Lap,
    /// The overlap's nodes, m.
    xs: Vec<f64>,
    /// Index in `xs` of the joint's abscissa.
    joint_node: usize,
    /// Per layer (upper, lower), per node: (w, theta).
    bend: [Vec<[Option<usize>; 2]>; 2],
    /// Per layer, per node: the axial displacement of the layer's centroid.
    axial: [Vec<Combo>; 2],
    /// Per layer, per element: the axial DOF of its middle.
    mids: [Vec<usize>; 2],
    /// The notched roots, when the lap's k_r is given.
    hinges: Vec<Hinge>,
}

/// The layered laps of a chain (see the module docs).
#[derive(Debug, Clone, Default)]
pub(super) struct Laps {
    laps: Vec<LapDofs>,
    outer: Vec<Outer>,
    rigid: usize,
}

/// The name of parameter `k` (0: k_n, 1: k_s) of joint `joint` of `count`.
pub fn parameter_name(joint: usize, count: usize, k: usize) -> String {
    if count == 1 {
        LAP_PARAMETERS[k].to_string()
    } else {
        format!("joint{}.{}", joint + 1, LAP_PARAMETERS[k])
    }
}

/// The name of the roots' rotational stiffness of joint `joint` of `count`.
pub fn root_name(joint: usize, count: usize) -> String {
    if count == 1 {
        ROOT_PARAMETER.to_string()
    } else {
        format!("joint{}.{ROOT_PARAMETER}", joint + 1)
    }
}

/// Whether a support of `kind` holds the beam along its axis.
fn holds_axial(kind: SupportKind) -> bool {
    match kind {
        SupportKind::Clamped | SupportKind::Pinned => true,
        SupportKind::Guided | SupportKind::Spring { .. } => false,
    }
}

fn push_dof(infos: &mut Vec<DofInfo>, label: String, x: f64, direction: Direction) -> usize {
    infos.push(DofInfo {
        label,
        position: [x, 0.0, 0.0],
        direction,
        node: None,
    });
    infos.len() - 1
}

impl Laps {
    /// Numbers the laps' DOFs after those in `infos` (the chain's, `node_dofs` per mesh node).
    pub(super) fn number(
        chain: &Chain,
        mesh: &Mesh,
        node_dofs: &[[Option<usize>; 2]],
        tol: f64,
        infos: &mut Vec<DofInfo>,
    ) -> Laps {
        let active: Vec<(usize, Lap, f64, f64)> = chain
            .overlaps()
            .into_iter()
            .filter_map(|(j, a, b)| Some((j, *chain.joints[j].active_lap()?, a, b)))
            .collect();
        if active.is_empty() {
            return Laps::default();
        }
        let inside = |beam: usize, mid: f64| {
            active
                .iter()
                .any(|&(j, _, a, b)| (beam == j || beam == j + 1) && mid > a && mid < b)
        };
        let mut outer = vec![Outer::Absent; chain.beams.len()];
        for (beam, slot) in outer.iter_mut().enumerate() {
            if !active.iter().any(|&(j, ..)| beam == j || beam == j + 1) {
                continue;
            }
            let (from, to) = (chain.beam_start(beam), chain.beam_start(beam + 1));
            let part: Vec<&MeshElement> = mesh
                .elements
                .iter()
                .filter(|e| {
                    let mid = 0.5 * (mesh.nodes[e.nodes[0]].x + mesh.nodes[e.nodes[1]].x);
                    e.beam == beam && !inside(beam, mid)
                })
                .collect();
            let held = chain
                .supports
                .iter()
                .any(|s| holds_axial(s.kind) && s.x >= from - tol && s.x <= to + tol);
            *slot = match (part.is_empty(), held) {
                (true, _) => Outer::Absent,
                (false, true) => Outer::Held,
                (false, false) => Outer::Free(outer_bar(beam, &part, mesh, infos)),
            };
        }
        let laps = active
            .into_iter()
            .map(|(j, lap, a, b)| number_lap(j, lap, (a, b), mesh, node_dofs, tol, &outer, infos))
            .collect();
        let rigid = axial_groups(chain.beams.len(), &active_joints(chain), &outer);
        Laps { laps, outer, rigid }
    }

    /// Rigid-body modes the laps add: the free axial translations.
    pub(super) fn rigid(&self) -> usize {
        self.rigid
    }

    /// The layers' elements the chain's elements do not cover (the upper layer right of the
    /// joint, the lower left of it), the layers' axial elements and the outer parts' bars.
    pub(super) fn base(&self, k: &mut SparseSym, m: &mut SparseSym) {
        for bar in self.outer.iter().filter_map(|o| match o {
            Outer::Free(bar) => Some(bar),
            _ => None,
        }) {
            for &(dofs, l, ea, mass) in &bar.elements {
                let ends = dofs.map(|d| vec![(d, 1.0)]);
                add_combined(k, &ends, &linear_bar_stiffness(ea, l));
                add_combined(m, &ends, &linear_bar_mass(mass, l));
            }
        }
        for lap in &self.laps {
            let n = lap.xs.len();
            for (layer, range) in [(0, lap.joint_node..n - 1), (1, 0..lap.joint_node)] {
                let section = lap.lap.layers[layer].section;
                for i in range {
                    let l = lap.xs[i + 1] - lap.xs[i];
                    let [a, b] = [lap.bend[layer][i], lap.bend[layer][i + 1]];
                    let dofs = [a[0], a[1], b[0], b[1]];
                    k.add_element(&dofs, &element_stiffness(&section, l), 1.0);
                    m.add_element(&dofs, &element_mass(&section, l), 1.0);
                }
            }
            for layer in 0..2 {
                let s = lap.lap.layers[layer].section;
                for i in 0..n - 1 {
                    let l = lap.xs[i + 1] - lap.xs[i];
                    let dofs = lap.bar(layer, i);
                    add_combined(k, &dofs, &bar_stiffness(s.youngs_modulus * s.area, l));
                    add_combined(m, &dofs, &bar_mass(s.mass_per_length(), l));
                }
            }
        }
    }

    /// dK/dk_n and dK/dk_s of joint `joint`, if it is a layered lap.
    pub(super) fn interface(&self, joint: usize) -> Option<[SparseSym; 2]> {
        let lap = self.laps.iter().find(|l| l.joint == joint)?;
        let (mut kn, mut ks) = (SparseSym::zero(), SparseSym::zero());
        let d = lap.lap.layers.map(|l| l.to_interface);
        for i in 0..lap.xs.len() - 1 {
            let l = lap.xs[i + 1] - lap.xs[i];
            let bend: Vec<Combo> = (0..2)
                .flat_map(|layer| {
                    let [a, b] = [lap.bend[layer][i], lap.bend[layer][i + 1]];
                    [a[0], a[1], b[0], b[1]]
                })
                .map(|dof| dof.map(|d| vec![(d, 1.0)]).unwrap_or_default())
                .collect();
            let bend: [Combo; 8] = bend.try_into().expect("8 bending DOFs");
            add_combined(&mut kn, &bend, &normal(l));
            let [u0, u1] = [lap.bar(0, i), lap.bar(1, i)];
            let all: [Combo; 14] = std::array::from_fn(|k| match k {
                0..8 => bend[k].clone(),
                8..11 => u0[k - 8].clone(),
                _ => u1[k - 11].clone(),
            });
            add_combined(&mut ks, &all, &shear(l, d));
        }
        Some([kn, ks])
    }

    /// dK/dk_r of joint `joint`, if it is a layered lap with notched roots.
    pub(super) fn roots(&self, joint: usize) -> Option<SparseSym> {
        let lap = self.laps.iter().find(|l| l.joint == joint)?;
        if lap.hinges.is_empty() {
            return None;
        }
        let mut k = SparseSym::zero();
        for h in &lap.hinges {
            let dofs = [
                h.beam.map(|b| vec![(b, 1.0)]).unwrap_or_default(),
                vec![(h.layer, 1.0)],
            ];
            add_combined(&mut k, &dofs, &[[1.0, -1.0], [-1.0, 1.0]]);
        }
        Some(k)
    }

    /// The chain's elements with the layers' own rotations at their notched roots.
    pub(super) fn hinge(&self, lines: &mut [LineElement]) {
        for h in self.laps.iter().flat_map(|l| &l.hinges) {
            let (element, end) = h.element;
            lines[element].dofs[2 * end + 1] = Some(h.layer);
        }
    }
}

impl LapDofs {
    /// The axial DOFs of element `i` of layer `layer`: its two nodes and its middle.
    fn bar(&self, layer: usize, i: usize) -> [Combo; 3] {
        [
            self.axial[layer][i].clone(),
            self.axial[layer][i + 1].clone(),
            vec![(self.mids[layer][i], 1.0)],
        ]
    }
}

/// The bar along the outer part `part` (its elements, in chain order) of beam `beam`, its
/// axial DOFs numbered after those in `infos` (`beam<b>.<k>:x`, k counting the part's nodes).
fn outer_bar(
    beam: usize,
    part: &[&MeshElement],
    mesh: &Mesh,
    infos: &mut Vec<DofInfo>,
) -> OuterBar {
    let mut dofs: Vec<(usize, usize)> = Vec::new();
    let mut dof_of = |node: usize, infos: &mut Vec<DofInfo>| {
        // The part's elements are in chain order: a node is its predecessor's last.
        if let Some(&(_, d)) = dofs.last().filter(|(n, _)| *n == node) {
            return d;
        }
        let label = format!("beam{beam}.{}:x", dofs.len());
        let d = push_dof(infos, label, mesh.nodes[node].x, Direction::X);
        dofs.push((node, d));
        d
    };
    let elements = part
        .iter()
        .map(|e| {
            let ends = [dof_of(e.nodes[0], infos), dof_of(e.nodes[1], infos)];
            let s = e.section;
            (
                ends,
                e.length,
                s.youngs_modulus * s.area,
                s.mass_per_length(),
            )
        })
        .collect();
    OuterBar { dofs, elements }
}

/// The DOFs of the lap of joint `j` over (a, b).
#[allow(clippy::too_many_arguments)]
fn number_lap(
    j: usize,
    lap: Lap,
    (a, b): (f64, f64),
    mesh: &Mesh,
    node_dofs: &[[Option<usize>; 2]],
    tol: f64,
    outer: &[Outer],
    infos: &mut Vec<DofInfo>,
) -> LapDofs {
    let (left, right, xs) = overlap_nodes(j, (a, b), mesh, tol);
    let joint_node = left.len() - 1;
    let names = ["upper", "lower"];
    let new_node = |layer: usize, k: usize, infos: &mut Vec<DofInfo>| {
        let at = |d: Direction| format!("lap{}.{}{k}:{d}", j + 1, names[layer]);
        [
            Some(push_dof(infos, at(Direction::W), xs[k], Direction::W)),
            Some(push_dof(
                infos,
                at(Direction::Theta),
                xs[k],
                Direction::Theta,
            )),
        ]
    };
    let upper: Vec<[Option<usize>; 2]> = (0..xs.len())
        .map(|k| match left.get(k) {
            Some(&n) => node_dofs[n],
            None => new_node(0, k, infos),
        })
        .collect();
    let lower: Vec<[Option<usize>; 2]> = (0..xs.len())
        .map(|k| match k.checked_sub(joint_node) {
            Some(r) => node_dofs[right[r]],
            None => new_node(1, k, infos),
        })
        .collect();
    let mut bend = [upper, lower];
    // The layers' ends that continue into their beams: the upper's first node, the lower's
    // last.
    let ends = [(0, j), (xs.len() - 1, j + 1)];
    let roots = [left[0], right[right.len() - 1]];
    let mut hinges = Vec::new();
    for layer in 0..2 {
        let (end, beam) = ends[layer];
        let continues = matches!(outer[beam], Outer::Free(_) | Outer::Held);
        if !(continues && lap.k_r.is_some() && lap.notches[layer].is_some()) {
            continue;
        }
        let label = format!("lap{}.{}{end}:{}", j + 1, names[layer], Direction::Theta);
        let theta = push_dof(infos, label, xs[end], Direction::Theta);
        bend[layer][end][1] = Some(theta);
        let element = mesh
            .elements
            .iter()
            .position(|e| e.beam == beam && e.nodes[layer] == roots[layer])
            .expect("a layer begins or ends with an element of its beam");
        hinges.push(Hinge {
            beam: node_dofs[roots[layer]][1],
            layer: theta,
            element: (element, layer),
        });
    }
    let axial: [Vec<Combo>; 2] = std::array::from_fn(|layer| {
        let (end, beam) = ends[layer];
        let offset = lap.layers[layer].offset;
        (0..xs.len())
            .map(|k| {
                // At its root a layer's axial motion is the beam section's at the layer's
                // centroid (the notch's hinge lies there).
                let theta = if k == end {
                    node_dofs[roots[layer]][1]
                } else {
                    bend[layer][k][1]
                };
                let tie = |u: Option<usize>| -> Combo {
                    u.map(|u| (u, 1.0))
                        .into_iter()
                        .chain(theta.map(|t| (t, -offset)).filter(|_| offset != 0.0))
                        .collect()
                };
                match (k == end, &outer[beam]) {
                    (true, Outer::Free(bar)) => tie(Some(bar.at(roots[layer]))),
                    (true, Outer::Held) => tie(None),
                    _ => {
                        let label = format!("lap{}.{}{k}:x", j + 1, names[layer]);
                        vec![(push_dof(infos, label, xs[k], Direction::X), 1.0)]
                    }
                }
            })
            .collect()
    });
    let mids = midpoint_dofs(j, &xs, names, infos);
    LapDofs {
        joint: j,
        lap,
        xs,
        joint_node,
        bend,
        axial,
        mids,
        hinges,
    }
}

/// The mesh nodes over the overlap (a, b) of joint `j`: those of beam j from a on (the
/// joint's node last), those of beam j + 1 up to b (the joint's node first), and the
/// abscissae of the lap's stations (the two lists joined at the joint's node).
fn overlap_nodes(
    j: usize,
    (a, b): (f64, f64),
    mesh: &Mesh,
    tol: f64,
) -> (Vec<usize>, Vec<usize>, Vec<f64>) {
    let left: Vec<usize> = (0..mesh.nodes.len())
        .filter(|&n| mesh.nodes[n].beam == j && mesh.nodes[n].x >= a - tol)
        .collect();
    let right: Vec<usize> = (0..mesh.nodes.len())
        .filter(|&n| mesh.nodes[n].beam == j + 1 && mesh.nodes[n].x <= b + tol)
        .collect();
    let xs: Vec<f64> = left
        .iter()
        .chain(&right[1..])
        .map(|&n| mesh.nodes[n].x)
        .collect();
    (left, right, xs)
}

/// Each layer's axial DOF at the middle of every segment between the stations `xs`.
fn midpoint_dofs(
    j: usize,
    xs: &[f64],
    names: [&str; 2],
    infos: &mut Vec<DofInfo>,
) -> [Vec<usize>; 2] {
    std::array::from_fn(|layer| {
        (0..xs.len() - 1)
            .map(|i| {
                let label = format!("lap{}.{}{i}m:x", j + 1, names[layer]);
                push_dof(infos, label, 0.5 * (xs[i] + xs[i + 1]), Direction::X)
            })
            .collect()
    })
}

/// The joints that are layered laps.
fn active_joints(chain: &Chain) -> Vec<usize> {
    (0..chain.joints.len())
        .filter(|&j| chain.joints[j].active_lap().is_some())
        .collect()
}

/// The free axial translations: the groups of beams joined by the laps of `joints` that no
/// support holds.
fn axial_groups(beams: usize, joints: &[usize], outer: &[Outer]) -> usize {
    // Beam b's group is the run of beams joined by laps that contains it.
    let mut count = 0;
    let mut b = 0;
    while b < beams {
        let mut end = b;
        while joints.contains(&end) {
            end += 1;
        }
        if end > b && !(b..=end).any(|i| outer[i] == Outer::Held) {
            count += 1;
        }
        b = end + 1;
    }
    count
}

/// Adds the symmetric `block` on the DOF combinations `dofs`: sum_ij block_ij c_i c_j. Each
/// term and its mirror are listed together with the same value (c_i c_j first, which is
/// exact to commute), so that the assembled matrix is symmetric entry by entry, bit for bit.
fn add_combined<const N: usize>(out: &mut SparseSym, dofs: &[Combo; N], block: &[[f64; N]; N]) {
    for i in 0..N {
        for j in i..N {
            let v = block[i][j];
            if v == 0.0 {
                continue;
            }
            for (a, &(gi, ci)) in dofs[i].iter().enumerate() {
                for (b, &(gj, cj)) in dofs[j].iter().enumerate() {
                    if i == j && b < a {
                        continue;
                    }
                    let w = v * (ci * cj);
                    // The term (j, b; i, a) of the full sum, unless it is this one.
                    let mirrored = i != j || a != b;
                    if gi == gj {
                        out.push(gi, gi, if mirrored { 2.0 * w } else { w });
                    } else {
                        out.add(gi, gj, w);
                    }
                }
            }
        }
    }
}

/// Refuses overlaps that meet on a beam: the two half lengths on beam b must add up to at
/// most its length.
pub(crate) fn check_overlaps(
    beams: &[Beam],
    joints: &[Joint],
    check: &FieldCheck,
) -> Result<(), InputError> {
    for j in 1..joints.len() {
        let (Some(before), Some(after)) = (joints[j - 1].lap, joints[j].lap) else {
            continue;
        };
        let reach = 0.5 * (before.length + after.length);
        if reach > beams[j].length * (1.0 + 1e-12) {
            return Err(check.invalid(
                format!("joint[{j}].lap.length"),
                after.length,
                format!(
                    "its overlap and joint[{}]'s ({} m) would meet on beam[{j}] ({} m): the two half lengths must add up to at most the beam's length",
                    j - 1,
                    before.length,
                    beams[j].length
                ),
            ));
        }
    }
    Ok(())
}

/// Refuses a support on an overlap (from its start to its end).
pub(crate) fn check_supports(
    beams: &[Beam],
    joints: &[Joint],
    supports: &[Support],
    check: &FieldCheck,
) -> Result<(), InputError> {
    let mut start = 0.0;
    for (j, joint) in joints.iter().enumerate() {
        start += beams[j].length;
        let Some(lap) = joint.lap else { continue };
        let (a, b) = lap.span(start);
        let tol = 1e-9 * (b - a);
        if let Some((i, s)) = supports
            .iter()
            .enumerate()
            .find(|(_, s)| s.x >= a - tol && s.x <= b + tol)
        {
            return Err(check.invalid(
                format!("support[{i}].x"),
                s.x,
                format!(
                    "it lies on joint[{j}]'s overlap, from {a} to {b} m, where the beams are two layers: a support must lie outside the overlap"
                ),
            ));
        }
    }
    Ok(())
}
