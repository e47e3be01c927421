//! What no model explains, mode by mode, when the verdict is `unexplained`: which measured
//! modes, in their frequency or their shape, by how much with the model that comes closest
//! (so with every model at least that), and the physics the library lacks for that pattern
//! where it can be said.
//!
//! A mode's frequency remains when every model's standardised error z = (f - f_m) /
//! (sigma_f f_m) has z^2 above the chi-square (1 dof) quantile of `level` / modes
//! (Bonferroni over the modes; the diagnosis passes its lack-of-fit level,
//! `crate::diagnose::FIT_ALPHA`); its shape remains when every model's shape chi^2 of that
//! mode (as in [`ResidualPattern`], dof = its values - 1 for the fitted scale) has P(chi^2)
//! below `level` / modes. The models are the joint-only fit and every candidate with a model
//! of its own that fitted and is physical.

use serde::Serialize;

use super::pattern::ResidualPattern;
use super::summary::ErrorSummary;
use crate::diagnose::fit::{Fitted, Noise, residuals};
use crate::diagnose::noise::NoiseEstimate;
use crate::measured::MeasuredModes;
use crate::stats::{chi2_isf, chi2_sf};

/// A shape residual of one sensor carrying at least this share of a mode's shape chi^2 makes
/// the misfit local.
pub const LOCAL_SHARE: f64 = 0.5;

/// How one measured mode misses with every model.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Misfit {
    /// Its frequency.
    Frequency {
        /// The closest model's error, %.
        error_pct: f64,
        /// The same in standard deviations of the working frequency noise.
        sigmas: f64,
    },
    /// Its shape.
    Shape {
        /// The largest MAC any model reaches.
        mac: f64,
        /// The closest model's shape chi^2 of the mode.
        chi2: f64,
        /// Its degrees of freedom (values - 1).
        dof: usize,
    },
}

/// The physics the library lacks for a pattern, where it can be said.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Lacking {
    /// The shape misfit sits at one sensor: a local change of the structure near it, or that
    /// sensor's own error (position, direction, calibration).
    LocalChange {
        /// The sensor's abscissa, m.
        x: f64,
        /// Its share of the mode's shape chi^2.
        share: f64,
        /// Whether the extended library's local candidates (local stiffness, joint region)
        /// were tried.
        extended_tried: bool,
    },
    /// The shape and the frequency of the mode miss, the shape's misfit spread along it: a
    /// change of stiffness or mass along the structure that no candidate places.
    Distributed {
        /// Whether the extended library was tried.
        extended_tried: bool,
    },
    /// The shape misses, spread along the mode, while its frequency fits: a change along the
    /// structure whose frequency shift the joint's calibration offsets, motion the planar
    /// bending model does not hold (torsion or the other bending plane mixing in, a close
    /// mode), or sensors placed or directed otherwise than the model says.
    ShapeMixing {
        /// Whether the extended library was tried.
        extended_tried: bool,
    },
    /// The frequency misses while the mode's shape fits: a change the sensors do not resolve,
    /// a joint that depends on the vibration amplitude, or a frequency dependence other than
    /// a power law.
    FrequencyOnly,
}

/// One mode and what remains of it with every model.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Remaining {
    /// Measured mode r.
    pub mode: usize,
    /// Frequency or shape, and how large.
    pub misfit: Misfit,
    /// The model that comes closest (`joint only` or a candidate's name).
    pub closest: String,
    /// What the library lacks for it, where it can be said.
    pub lacking: Option<Lacking>,
}

/// A model's view of every mode: frequency z and shape chi^2.
struct View<'a> {
    name: &'a str,
    z: Vec<f64>,
    shape: Vec<f64>,
    summary: ErrorSummary,
    fitted: &'a Fitted,
}

/// What remains of `measured` with every one of `models` (name, fit), judged under
/// `estimate`'s working noise at `level` (module docs); `extended_tried` when the extended
/// library was searched.
pub fn remains(
    models: &[(&str, &Fitted)],
    measured: &MeasuredModes,
    (estimate, level): (&NoiseEstimate, f64),
    extended_tried: bool,
) -> Vec<Remaining> {
    let modes = measured.modes();
    let n = modes.len().max(1) as f64;
    let (noise, floor) = (estimate.working, estimate.working_floor);
    let views: Vec<View> = models
        .iter()
        .map(|&(name, fitted)| {
            let pattern = ResidualPattern::by_mode(fitted, measured, noise, floor);
            let z = residuals(fitted, measured)
                .frequency
                .iter()
                .enumerate()
                .map(|(r, e)| {
                    let sigma = estimate
                        .frequency_sigmas
                        .as_ref()
                        .map_or(noise.frequency, |s| s[r]);
                    e / sigma
                })
                .collect();
            View {
                name,
                z,
                shape: pattern.iter().map(|m| m.shape).collect(),
                summary: ErrorSummary::of(fitted, measured, estimate),
                fitted,
            }
        })
        .collect();
    if views.is_empty() {
        return Vec::new();
    }
    let z_limit = chi2_isf(level / n, 1.0).sqrt();
    let mut out = Vec::new();
    for (r, m) in modes.iter().enumerate() {
        let closest_f = (0..views.len())
            .min_by(|&a, &b| views[a].z[r].abs().total_cmp(&views[b].z[r].abs()))
            .unwrap_or(0);
        let closest_s = (0..views.len())
            .min_by(|&a, &b| views[a].shape[r].total_cmp(&views[b].shape[r]))
            .unwrap_or(0);
        let dof = m.values.len().saturating_sub(1);
        let shape_remains = dof > 0 && chi2_sf(views[closest_s].shape[r], dof as f64) < level / n;
        let v = &views[closest_f];
        let frequency_remains = v.z[r].abs() > z_limit;
        if frequency_remains {
            out.push(Remaining {
                mode: m.mode,
                misfit: Misfit::Frequency {
                    error_pct: v.summary.modes[r].frequency_error_pct,
                    sigmas: v.z[r],
                },
                closest: v.name.to_string(),
                lacking: (!shape_remains).then_some(Lacking::FrequencyOnly),
            });
        }
        if shape_remains {
            let v = &views[closest_s];
            let mac = views
                .iter()
                .map(|v| v.summary.modes[r].mac)
                .fold(0.0, f64::max);
            out.push(Remaining {
                mode: m.mode,
                misfit: Misfit::Shape {
                    mac,
                    chi2: v.shape[r],
                    dof,
                },
                closest: v.name.to_string(),
                lacking: Some(shape_lacking(
                    (v.fitted, measured, r),
                    (noise, floor),
                    frequency_remains,
                    extended_tried,
                )),
            });
        }
    }
    out
}

/// Local when one sensor carries at least [`LOCAL_SHARE`] of mode `r`'s shape chi^2 in
/// `fitted`; else distributed when the mode's frequency misses too, mixing when it fits.
fn shape_lacking(
    (fitted, measured, r): (&Fitted, &MeasuredModes, usize),
    (noise, floor): (Noise, f64),
    frequency_remains: bool,
    extended_tried: bool,
) -> Lacking {
    let z2 = ResidualPattern::of_mode(fitted, measured, r, noise, floor);
    let total: f64 = z2.iter().map(|(_, z)| z).sum();
    let largest = z2
        .iter()
        .copied()
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .filter(|_| total > 0.0);
    match largest {
        Some((x, z)) if z >= LOCAL_SHARE * total => Lacking::LocalChange {
            x,
            share: z / total,
            extended_tried,
        },
        _ if frequency_remains => Lacking::Distributed { extended_tried },
        _ => Lacking::ShapeMixing { extended_tried },
    }
}
