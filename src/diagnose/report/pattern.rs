//! Where the misfit of a fit sits: the chi^2 of every mode (frequency against shape) and the
//! stretches of the beams where the shape residuals concentrate.

use serde::Serialize;

use crate::diagnose::fit::{Fitted, Noise, residuals};
use crate::measured::MeasuredModes;

/// The chi^2 one measured mode carries in a fit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ModeChi2 {
    /// Measured mode r.
    pub mode: usize,
    /// From its frequency.
    pub frequency: f64,
    /// From its shape components.
    pub shape: f64,
}

/// A stretch of the beams where the shape residual concentrates.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Region {
    /// First abscissa of the stretch, m.
    pub x_from: f64,
    /// Last abscissa, m.
    pub x_to: f64,
    /// Its share of the shape chi^2 (all modes).
    pub share: f64,
}

/// Where the remaining misfit sits: by mode (frequency against shape) and along the beams.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ResidualPattern {
    /// Every mode, the largest total chi^2 first.
    pub modes: Vec<ModeChi2>,
    /// The frequencies' share of the whole chi^2.
    pub frequency_share: f64,
    /// Stretches of the sensors whose summed squared shape residual (over modes) is at least
    /// half the largest one, the largest share first.
    pub regions: Vec<Region>,
}

impl ResidualPattern {
    /// Per measured mode (in measured order): the frequency's chi^2 and every shape value's
    /// (abscissa, z^2) of `fitted` under `noise` with shape floor `floor` (the residuals
    /// weighted as in the fit, module `fit`).
    fn contributions(
        fitted: &Fitted,
        measured: &MeasuredModes,
        noise: Noise,
        floor: f64,
    ) -> Vec<(f64, Vec<(f64, f64)>)> {
        let residuals = residuals(fitted, measured);
        let mut shape = residuals.shape.iter();
        measured
            .modes()
            .iter()
            .zip(&residuals.frequency)
            .map(|(m, rf)| {
                let values = m
                    .points
                    .iter()
                    .zip(shape.by_ref())
                    .map(|(p, &(u, e))| {
                        (
                            p.x,
                            (e / (noise.shape * (u * u + floor * floor).sqrt())).powi(2),
                        )
                    })
                    .collect();
                ((rf / noise.frequency).powi(2), values)
            })
            .collect()
    }

    /// Every mode's chi^2 in `fitted`, in measured order ([`Self::of`]'s terms).
    pub fn by_mode(
        fitted: &Fitted,
        measured: &MeasuredModes,
        noise: Noise,
        floor: f64,
    ) -> Vec<ModeChi2> {
        Self::contributions(fitted, measured, noise, floor)
            .into_iter()
            .zip(measured.modes())
            .map(|((frequency, values), m)| ModeChi2 {
                mode: m.mode,
                frequency,
                shape: values.iter().map(|(_, z)| z).sum(),
            })
            .collect()
    }

    /// The (abscissa, z^2) of every shape value of measured mode `r` in `fitted`.
    pub fn of_mode(
        fitted: &Fitted,
        measured: &MeasuredModes,
        r: usize,
        noise: Noise,
        floor: f64,
    ) -> Vec<(f64, f64)> {
        Self::contributions(fitted, measured, noise, floor)
            .swap_remove(r)
            .1
    }

    /// The pattern of `fitted` on `measured` under `noise` with shape floor `floor` (the
    /// residuals weighted as in the fit, module `fit`).
    pub fn of(fitted: &Fitted, measured: &MeasuredModes, noise: Noise, floor: f64) -> Self {
        let contributions = Self::contributions(fitted, measured, noise, floor);
        let mut modes = Vec::new();
        let mut at_x: Vec<(f64, f64)> = Vec::new();
        for (m, (frequency, values)) in measured.modes().iter().zip(contributions) {
            let mut shape_chi2 = 0.0;
            for (x, z2) in values {
                shape_chi2 += z2;
                match at_x.iter_mut().find(|(y, _)| (y - x).abs() <= 1e-9) {
                    Some(slot) => slot.1 += z2,
                    None => at_x.push((x, z2)),
                }
            }
            modes.push(ModeChi2 {
                mode: m.mode,
                frequency,
                shape: shape_chi2,
            });
        }
        let frequency_total: f64 = modes.iter().map(|m| m.frequency).sum();
        let total = frequency_total + modes.iter().map(|m| m.shape).sum::<f64>();
        modes.sort_by(|a, b| (b.frequency + b.shape).total_cmp(&(a.frequency + a.shape)));
        at_x.sort_by(|a, b| a.0.total_cmp(&b.0));
        let shape_total: f64 = at_x.iter().map(|(_, z)| z).sum();
        let largest = at_x.iter().map(|(_, z)| *z).fold(0.0, f64::max);
        let mut regions: Vec<Region> = Vec::new();
        let mut open = false;
        for &(x, z) in &at_x {
            if largest > 0.0 && z >= 0.5 * largest {
                match regions.last_mut() {
                    Some(r) if open => {
                        r.x_to = x;
                        r.share += z / shape_total;
                    }
                    _ => regions.push(Region {
                        x_from: x,
                        x_to: x,
                        share: z / shape_total,
                    }),
                }
                open = true;
            } else {
                open = false;
            }
        }
        regions.sort_by(|a, b| b.share.total_cmp(&a.share));
        ResidualPattern {
            modes,
            frequency_share: if total > 0.0 {
                frequency_total / total
            } else {
                0.0
            },
            regions,
        }
    }
}
