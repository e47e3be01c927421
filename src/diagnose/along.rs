//! The shape residuals of a fit in the order of the sensors along the structure: one sequence
//! per mode and direction, sorted by x. What a wrong model leaves in a mode shape is smooth
//! along these sequences; measurement noise is not (modules `whiteness` and `noise`).

use super::fit::Residuals;
use crate::measured::MeasuredModes;
use crate::structure::Direction;

/// One mode's shape residuals in one direction, in sensor order along x; values per unit
/// peak of the measured mode.
#[derive(Debug, Clone, PartialEq)]
pub struct Sequence {
    /// The measured mode's number (1 = the first elastic mode).
    pub mode: usize,
    /// Position of each sensor along the structure (m).
    pub x: Vec<f64>,
    /// Measured component.
    pub u: Vec<f64>,
    /// Residual of the fit.
    pub e: Vec<f64>,
}

impl Sequence {
    /// Whether the sensors are dense enough along the mode that a misfit is close to linear
    /// between neighbours: at least [`INTERVALS_PER_HALF_WAVE`] sensor intervals per
    /// half-wave, mode r having at most r + 1 half-waves (free ends).
    pub fn dense(&self) -> bool {
        self.x.len() >= 3
            && (self.x.len() - 1) as f64 >= INTERVALS_PER_HALF_WAVE * (self.mode + 1) as f64
    }
}

/// Fewest sensor intervals per half-wave of a mode for [`Sequence::dense`].
pub const INTERVALS_PER_HALF_WAVE: f64 = 2.0;

/// The shape residuals `res` of `measured`, one [`Sequence`] per mode and direction.
pub fn of_residuals(res: &Residuals, measured: &MeasuredModes) -> Vec<Sequence> {
    let mut shape = res.shape.iter();
    let mut out = Vec::new();
    for mode in measured.modes() {
        let values: Vec<(Direction, f64, f64, f64)> = mode
            .points
            .iter()
            .zip(shape.by_ref())
            .map(|(p, &(u, e))| (p.direction, p.x, u, e))
            .collect();
        let mut order: Vec<usize> = (0..values.len()).collect();
        order.sort_by(|&a, &b| {
            values[a]
                .0
                .cmp(&values[b].0)
                .then(values[a].1.total_cmp(&values[b].1))
        });
        for chunk in order.chunk_by(|&a, &b| values[a].0 == values[b].0) {
            out.push(Sequence {
                mode: mode.mode,
                x: chunk.iter().map(|&i| values[i].1).collect(),
                u: chunk.iter().map(|&i| values[i].2).collect(),
                e: chunk.iter().map(|&i| values[i].3).collect(),
            });
        }
    }
    out
}
