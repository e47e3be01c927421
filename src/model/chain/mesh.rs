//! The finite-element mesh of a chain: nodes where the beams end and where something happens
//! (segment ends, supports, masses, sensors, requested nodes), elements between them.
//!
//! Nodes are numbered along the chain, beam by beam; every beam has its own end nodes, so a
//! joint's two nodes share one abscissa. Within a beam, each interval between break points gets
//! ceil(interval / h) elements of equal length (at least one), h = length / elements: a beam
//! without break points keeps exactly its `elements` elements, and the paper's uniform chains
//! mesh as they always did.
//!
//! A sensor, a rigidly attached point mass or a support of springs is a break point of its
//! own unless it lies within [`NEAR`] h of another break point or of its beam's ends: the
//! element between them, shorter than that, would be stiffer than its neighbours by more than
//! (1 / NEAR)^3 = 8000, and a sensor 5 um from a joint on a 5 mm mesh (1e9) left the
//! eigenproblem unsolvable. A sensor then reads the element's Hermite interpolation, exact for
//! the model; a mass (a sensor's, or a point mass with its rotary inertia) is spread by the
//! same interpolation, m c c^T; a support's grounded springs likewise, k c c^T. A mass on a
//! spring, a rigid support, an overlap's end or a requested node is always a node, and a rigid
//! support (it holds a node's motion) that close to another node is refused by the model
//! file's check ([`crowded_support`]).

use super::Chain;
use super::beam::Section;

/// A node of the mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshNode {
    /// Abscissa along the chain, m.
    pub x: f64,
    /// The beam it belongs to.
    pub beam: usize,
}

/// An element of the mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshElement {
    /// The beam it belongs to.
    pub beam: usize,
    /// Its two nodes.
    pub nodes: [usize; 2],
    /// Its length, m (the interval's length over its element count, not a difference of
    /// abscissae: the same bits as a uniform mesh's length / elements).
    pub length: f64,
    /// Its section.
    pub section: Section,
}

/// The mesh of a chain.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    /// Nodes in chain order.
    pub nodes: Vec<MeshNode>,
    /// Elements in chain order.
    pub elements: Vec<MeshElement>,
    /// First and last node of every beam.
    pub beam_ends: Vec<(usize, usize)>,
}

/// Break points closer than this fraction of a beam's length are one point.
pub(super) const MERGE: f64 = 1e-9;

/// Abscissae closer than this fraction of the chain's length are one position.
pub(super) const SAME_X: f64 = 1e-9;

/// A sensor, a rigidly attached mass or a support of springs closer than this fraction of its
/// beam's element length to another break point is not one (module docs).
pub(super) const NEAR: f64 = 0.05;

impl Mesh {
    /// Meshes `chain`.
    pub fn of(chain: &Chain) -> Mesh {
        let mut nodes = Vec::new();
        let mut elements = Vec::new();
        let mut beam_ends = Vec::new();
        let features = chain.feature_positions();
        let mut start = 0.0;
        for (b, beam) in chain.beams.iter().enumerate() {
            let length = beam.length;
            let mut breaks = breaks_of(chain, b, start, &features);
            let near = NEAR * beam.element_length();
            for s in chain.point_positions().into_iter().map(|x| x - start) {
                let clear = s > near && s < length - near;
                if clear && breaks.iter().all(|b| (b - s).abs() > near) {
                    breaks.push(s);
                }
            }
            breaks.sort_by(f64::total_cmp);
            let bounds: Vec<f64> = std::iter::once(0.0)
                .chain(breaks)
                .chain(std::iter::once(length))
                .collect();
            let h = beam.element_length();
            let first = nodes.len();
            nodes.push(MeshNode { x: start, beam: b });
            for w in bounds.windows(2) {
                let (a, z) = (w[0], w[1]);
                let span = z - a;
                let count = ((span / h) * (1.0 - 1e-9)).ceil().max(1.0) as usize;
                let l = span / count as f64;
                let section = beam.section_at(0.5 * (a + z));
                for e in 1..=count {
                    let x = if e == count {
                        start + z
                    } else {
                        start + (a + l * e as f64)
                    };
                    let node = nodes.len();
                    nodes.push(MeshNode { x, beam: b });
                    elements.push(MeshElement {
                        beam: b,
                        nodes: [node - 1, node],
                        length: l,
                        section,
                    });
                }
            }
            beam_ends.push((first, nodes.len() - 1));
            start += length;
        }
        layer_sections(chain, &nodes, &mut elements);
        Mesh {
            nodes,
            elements,
            beam_ends,
        }
    }
}

/// The break points of beam `b` (starting at abscissa `start`) strictly inside it, from its
/// start, in order, one per point: its segments' ends and the chain's `features` on it.
fn breaks_of(chain: &Chain, b: usize, start: f64, features: &[f64]) -> Vec<f64> {
    let length = chain.beams[b].length;
    let mut breaks: Vec<f64> = chain.beams[b]
        .segments
        .iter()
        .flat_map(|g| [g.from, g.to])
        .chain(features.iter().map(|&x| x - start))
        .filter(|&s| s > MERGE * length && s < length * (1.0 - MERGE))
        .collect();
    breaks.sort_by(f64::total_cmp);
    breaks.dedup_by(|a, b| (*a - *b).abs() <= MERGE * length);
    breaks
}

/// A node the mesh must place that lies within [`NEAR`] h of another (or of its beam's end)
/// without being on it: the element between them would be stiffer than its neighbours by more
/// than (1 / NEAR)^3 (module docs). Of a rigid support, which holds a node's motion and so
/// cannot be carried between nodes: (its index, the other point's abscissa, NEAR h).
pub fn crowded_support(chain: &Chain) -> Option<(usize, f64, f64)> {
    let features = chain.feature_positions();
    let mut start = 0.0;
    for (b, beam) in chain.beams.iter().enumerate() {
        let (length, near) = (beam.length, NEAR * beam.element_length());
        let points: Vec<f64> = std::iter::once(0.0)
            .chain(breaks_of(chain, b, start, &features))
            .chain(std::iter::once(length))
            .collect();
        for (i, support) in chain.supports.iter().enumerate() {
            let s = support.x - start;
            if !support.kind.holds_a_motion() || s < 0.0 || s > length {
                continue;
            }
            let crowding = points.iter().find(|&&p| {
                let d = (p - s).abs();
                d > MERGE * length && d <= near
            });
            if let Some(&p) = crowding {
                return Some((i, start + p, near));
            }
        }
        start += length;
    }
    None
}

/// Over the overlap of a joint that is a layered lap, the elements of the left beam carry the
/// upper layer's section, those of the right beam the lower layer's.
fn layer_sections(chain: &Chain, nodes: &[MeshNode], elements: &mut [MeshElement]) {
    for (j, a, b) in chain.overlaps() {
        let Some(lap) = chain.joints[j].active_lap() else {
            continue;
        };
        for e in elements.iter_mut() {
            let mid = 0.5 * (nodes[e.nodes[0]].x + nodes[e.nodes[1]].x);
            if mid > a && mid < b && (e.beam == j || e.beam == j + 1) {
                e.section = lap.layers[e.beam - j].section;
            }
        }
    }
}
