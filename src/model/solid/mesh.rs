//! The mesh of the lap specimen: two bars of bricks, the lower one from x = 0, the upper one
//! on top of it (z from the lower bar's thickness) from the start of the lap; over the lap the
//! top face of the lower bar and the bottom face of the upper one have nodes at the same
//! positions, joined pairwise by the interface springs.
//!
//! Frame: x along the bars from the lower bar's free end, y across the width (from 0 to the
//! width), z through the thickness from the lower bar's bottom face.
//!
//! Numbering: nodes by station along x (the stations of both bars merged; over the lap the
//! lower bar's node first), then across y, then up z, so that the matrices' bandwidth is
//! about three times the nodes of one or two cross-sections, the lap's springs included.
//!
//! May import: the solid's configuration, the shared input checks (the bolt patches' check).

use super::config::{Bolt, SolidConfig, divisions};
use crate::input::{FieldCheck, InputError, Number};

/// The mesh: node positions, bricks, interface node pairs.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    /// Node positions, m (0-based node numbers).
    pub nodes: Vec<[f64; 3]>,
    /// Bricks: their nodes in the order of [`super::hex`].
    pub bricks: Vec<[usize; 8]>,
    /// Interface pairs: (lower bar's node, upper bar's node, weight), the weight the
    /// tributary area of the pair, m^2, times the bolt patch's factor where it lies in one.
    pub pairs: Vec<(usize, usize, f64)>,
}

/// The stations (abscissae) of a segment `[from, to]` divided into `n` equal parts, without
/// the first.
fn stations(from: f64, to: f64, n: usize) -> impl Iterator<Item = f64> {
    (1..=n).map(move |i| {
        if i == n {
            to
        } else {
            from + (to - from) * i as f64 / n as f64
        }
    })
}

/// One bar: its stations along x, its z levels, and where its stations sit in the merged
/// list.
struct Bar {
    xs: Vec<f64>,
    zs: Vec<f64>,
    /// Merged station index of its first station.
    offset: usize,
}

impl Mesh {
    /// The mesh of `config`.
    pub fn of(config: &SolidConfig) -> Mesh {
        let [lower, upper] = &config.bars;
        let size = config.mesh.size;
        let lap_start = lower.length - config.overlap;
        let n_before = if lap_start > 0.0 {
            divisions(lap_start, size)
        } else {
            0
        };
        let n_lap = divisions(config.overlap, size);
        let lap_end = lap_start + upper.length;
        let n_after = if upper.length > config.overlap {
            divisions(upper.length - config.overlap, size)
        } else {
            0
        };
        let lap: Vec<f64> = stations(lap_start, lower.length, n_lap).collect();
        let mut x_lower = vec![0.0];
        x_lower.extend(stations(0.0, lap_start, n_before));
        x_lower.extend(&lap);
        let mut x_upper = vec![lap_start];
        x_upper.extend(&lap);
        x_upper.extend(stations(lower.length, lap_end, n_after));
        let layers = config.mesh.layers;
        let z_lower: Vec<f64> = std::iter::once(0.0)
            .chain(stations(0.0, lower.thickness, layers))
            .collect();
        let top = lower.thickness + upper.thickness;
        let z_upper: Vec<f64> = std::iter::once(lower.thickness)
            .chain(stations(lower.thickness, top, layers))
            .collect();
        let ny = divisions(config.width, size);
        let ys: Vec<f64> = std::iter::once(0.0)
            .chain(stations(0.0, config.width, ny))
            .collect();
        let bars = [
            Bar {
                xs: x_lower,
                zs: z_lower,
                offset: 0,
            },
            Bar {
                xs: x_upper,
                zs: z_upper,
                offset: n_before,
            },
        ];
        let ids = number(&bars, ys.len());
        let mut nodes = vec![[0.0; 3]; ids.iter().map(Vec::len).sum()];
        let mut bricks = Vec::new();
        for (bar, id) in bars.iter().zip(&ids) {
            let (nj, nk) = (ys.len(), bar.zs.len());
            let at = |i: usize, j: usize, k: usize| id[(i * nj + j) * nk + k];
            for (i, &x) in bar.xs.iter().enumerate() {
                for (j, &y) in ys.iter().enumerate() {
                    for (k, &z) in bar.zs.iter().enumerate() {
                        nodes[at(i, j, k)] = [x, y, z];
                    }
                }
            }
            bricks.extend(grid_bricks([bar.xs.len(), nj, nk], at));
        }
        let pairs = interface(&bars, &ids, &ys, &config.interface.bolts);
        Mesh {
            nodes,
            bricks,
            pairs,
        }
    }
}

impl Mesh {
    /// A box `[0, lx] x [0, ly] x [0, lz]` of `nx x ny x nz` equal bricks, nodes numbered x
    /// slowest, z fastest (a monolithic bar, a patch test), without interface.
    pub fn block(lengths: [f64; 3], divisions: [usize; 3]) -> Mesh {
        let axis = |d: usize| -> Vec<f64> {
            std::iter::once(0.0)
                .chain(stations(0.0, lengths[d], divisions[d]))
                .collect()
        };
        let (xs, ys, zs) = (axis(0), axis(1), axis(2));
        let (nj, nk) = (ys.len(), zs.len());
        let at = |i: usize, j: usize, k: usize| (i * nj + j) * nk + k;
        let mut nodes = Vec::with_capacity(xs.len() * nj * nk);
        for &x in &xs {
            for &y in &ys {
                for &z in &zs {
                    nodes.push([x, y, z]);
                }
            }
        }
        let bricks = grid_bricks([xs.len(), nj, nk], at);
        Mesh {
            nodes,
            bricks,
            pairs: Vec::new(),
        }
    }
}

/// Every bolt patch of `config` (read from `file`) holds at least one interface node.
pub fn check_bolts(config: &SolidConfig, file: &std::path::Path) -> Result<(), InputError> {
    let mesh = Mesh::of(config);
    for (i, bolt) in config.interface.bolts.iter().enumerate() {
        let hit = mesh
            .pairs
            .iter()
            .any(|&(a, _, _)| bolt.contains(mesh.nodes[a][0], mesh.nodes[a][1]));
        if !hit {
            return Err(FieldCheck { file }.invalid(
                format!("interface.bolt[{i}].radius"),
                Number(bolt.radius),
                format!(
                    "no interface node lies within it at mesh.size = {} m: give a larger radius or a smaller mesh.size",
                    Number(config.mesh.size)
                ),
            ));
        }
    }
    Ok(())
}

/// The bricks of a structured grid of `n` nodes per axis whose node (i, j, k) is `at(i, j, k)`.
fn grid_bricks(n: [usize; 3], at: impl Fn(usize, usize, usize) -> usize) -> Vec<[usize; 8]> {
    let mut bricks = Vec::with_capacity((n[0] - 1) * (n[1] - 1) * (n[2] - 1));
    for i in 0..n[0] - 1 {
        for j in 0..n[1] - 1 {
            for k in 0..n[2] - 1 {
                bricks.push([
                    at(i, j, k),
                    at(i + 1, j, k),
                    at(i + 1, j + 1, k),
                    at(i, j + 1, k),
                    at(i, j, k + 1),
                    at(i + 1, j, k + 1),
                    at(i + 1, j + 1, k + 1),
                    at(i, j + 1, k + 1),
                ]);
            }
        }
    }
    bricks
}

/// Node numbers of each bar, indexed `(i * ny + j) * nz + k`: station by station of the
/// merged list, the lower bar's nodes before the upper bar's at a shared station.
fn number(bars: &[Bar; 2], ny: usize) -> [Vec<usize>; 2] {
    let stations = bars
        .iter()
        .map(|b| b.offset + b.xs.len())
        .max()
        .unwrap_or(0);
    let mut ids = [
        vec![0; bars[0].xs.len() * ny * bars[0].zs.len()],
        vec![0; bars[1].xs.len() * ny * bars[1].zs.len()],
    ];
    let mut next = 0;
    for g in 0..stations {
        for (bar, id) in bars.iter().zip(ids.iter_mut()) {
            let Some(i) = g.checked_sub(bar.offset).filter(|&i| i < bar.xs.len()) else {
                continue;
            };
            let nk = bar.zs.len();
            for j in 0..ny {
                for k in 0..nk {
                    id[(i * ny + j) * nk + k] = next;
                    next += 1;
                }
            }
        }
    }
    ids
}

/// The half-widths of the intervals around each station of `xs`: the tributary length.
fn tributary(xs: &[f64]) -> Vec<f64> {
    (0..xs.len())
        .map(|i| {
            let left = if i > 0 { xs[i] - xs[i - 1] } else { 0.0 };
            let right = if i + 1 < xs.len() {
                xs[i + 1] - xs[i]
            } else {
                0.0
            };
            0.5 * (left + right)
        })
        .collect()
}

/// The interface pairs over the lap: the lower bar's top nodes and the upper bar's bottom
/// nodes at its stations, weighted by their tributary area and any bolt patch's factor.
fn interface(
    bars: &[Bar; 2],
    ids: &[Vec<usize>; 2],
    ys: &[f64],
    bolts: &[Bolt],
) -> Vec<(usize, usize, f64)> {
    let (lower, upper) = (&bars[0], &bars[1]);
    let lap: Vec<f64> = lower.xs[upper.offset..].to_vec();
    let (tx, ty) = (tributary(&lap), tributary(ys));
    let ny = ys.len();
    let (nk_lower, nk_upper) = (lower.zs.len(), upper.zs.len());
    let mut pairs = Vec::with_capacity(lap.len() * ny);
    for (i, &x) in lap.iter().enumerate() {
        for (j, &y) in ys.iter().enumerate() {
            let a = ids[0][((upper.offset + i) * ny + j) * nk_lower + nk_lower - 1];
            let b = ids[1][(i * ny + j) * nk_upper];
            let factor: f64 = bolts
                .iter()
                .filter(|bolt| bolt.contains(x, y))
                .map(|bolt| bolt.factor)
                .fold(1.0, f64::max);
            pairs.push((a, b, tx[i] * ty[j] * factor));
        }
    }
    pairs
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::solid::config::tests::small;

    #[test]
    fn the_lap_faces_meet_node_for_node_and_the_areas_sum_to_the_lap() {
        let config = small();
        let mesh = Mesh::of(&config);
        assert_eq!((3 * mesh.nodes.len()) as f64, config.dof_count());
        let area: f64 = mesh.pairs.iter().map(|p| p.2).sum();
        assert!((area - config.overlap * config.width).abs() < 1e-15);
        for &(a, b, _) in &mesh.pairs {
            assert_eq!(mesh.nodes[a], mesh.nodes[b]);
            assert_eq!(mesh.nodes[a][2], config.bars[0].thickness);
        }
        // Every node is numbered once.
        let mut seen = vec![false; mesh.nodes.len()];
        for b in &mesh.bricks {
            for &n in b {
                seen[n] = true;
            }
        }
        assert!(seen.iter().all(|&s| s));
    }
}
