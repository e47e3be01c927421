//! The paper's first step: the beams' models adjusted on the identified modes of a reference
//! specimen (the same beams in one piece, or one beam alone) before the joint is identified,
//! so that what the material and section values typed in get wrong does not land in the joint.
//!
//! The reference specimen is derived from the jointed model (module [`specimen`]). Its unknowns
//! are factors of the beams' material, E (with G) or rho, one for a group of beams or one per
//! beam, each x = ln(factor) (module [`scaled`]). They are fitted by the weighted least squares
//! of module `diagnose::fit`, frequencies and shapes of every measured mode, with the model's
//! own discrepancy estimated beside them (module `diagnose::discrepancy`): a beam model of a
//! real bar misses its modes by more than their measurement error, and a standard error that
//! ignored it would claim more than the data hold. The standard errors are those of the fit
//! under that error model, linearised at the optimum (of ln factor, times the factor).
//!
//! Frequencies and shapes scaled to no unit tell E from rho only through what is neither
//! (point masses, springs): where the beams make all of K and all of M, E and rho together
//! are refused ([`CalibrateError::OnlyTheRatio`]).
//!
//! Layer 6 (diagnosis and results; see the crate docs): may import the layers below
//! ([`crate::model`], [`crate::measured`], [`crate::modal`], [`crate::optim`],
//! [`crate::structure`]) and, without a circle, [`crate::diagnose`], whose fit it uses.

pub mod adjusted;
pub mod scaled;
pub mod specimen;

use std::sync::Arc;

pub use scaled::{Property, Scaled, Unknown};
pub use specimen::{Specimen, specimen_chain};

use crate::diagnose::discrepancy;
use crate::diagnose::fit::{
    self, Calibration, Discrepancy, FitError, Fitted, Noise, SHAPE_FLOOR, residuals,
};
use crate::diagnose::pairing::PairingRule;
use crate::measured::MeasuredModes;
use crate::modal::{ModalError, ModalSolution};
use crate::model::chain::{BeamCalibration, Chain, Factor};
use crate::model::effects::{Effect, EffectContext};
use crate::optim::Silent;

/// Why a calibration is refused.
#[derive(Debug, thiserror::Error)]
pub enum CalibrateError {
    /// A specimen of a beam the chain does not have.
    #[error("beam {beam} does not exist: the model has {beams} beam(s) (beam:1 to beam:{beams})")]
    NoSuchBeam {
        /// The beam asked for, 1-based.
        beam: usize,
        /// Beams of the model.
        beams: usize,
    },
    /// A monolithic specimen of a layered-lap joint.
    #[error(
        "joint {joint} is a layered lap (kind = \"lap\"): its layers tied are no monolithic specimen here; calibrate on one beam alone (beam:K)"
    )]
    LapJoint {
        /// The joint, 1-based.
        joint: usize,
    },
    /// A `--fit` entry that is not one.
    #[error("\"{given}\": a fit is youngs_modulus or density, optionally :each (one per beam)")]
    UnknownFit {
        /// The entry (shortened).
        given: String,
    },
    /// A property asked twice.
    #[error("{property} is asked twice: give it once (:each for one factor per beam)")]
    Twice {
        /// Its name.
        property: &'static str,
    },
    /// E and rho where nothing tells them apart.
    #[error(
        "only the ratio of E to rho shows in this specimen (no mass or spring besides the beams): fit one of them"
    )]
    OnlyTheRatio,
    /// The specimen's eigenproblem.
    #[error("the reference specimen has no eigensolution")]
    Modal(#[from] ModalError),
    /// The fit.
    #[error("the reference test does not fit the specimen")]
    Fit(#[from] FitError),
}

/// What a calibration is asked.
#[derive(Debug, Clone, PartialEq)]
pub struct Request {
    /// The specimen of the reference test.
    pub specimen: Specimen,
    /// The unknowns: a property, and whether one factor per beam.
    pub fits: Vec<(Property, bool)>,
    /// The stated measurement noise.
    pub noise: Noise,
    /// How the measured modes pair with the specimen's.
    pub pairing: PairingRule,
    /// Weigh by the data's own standard errors where every mode carries them.
    pub measured_std: bool,
    /// The reference test's name, recorded in the calibrated model.
    pub reference: String,
}

/// Parses `--fit` entries: `youngs_modulus`, `density`, each optionally `:each`.
pub fn parse_fits(entries: &[String]) -> Result<Vec<(Property, bool)>, CalibrateError> {
    let mut out: Vec<(Property, bool)> = Vec::new();
    for entry in entries {
        let (name, each) = match entry.strip_suffix(":each") {
            Some(name) => (name, true),
            None => (entry.as_str(), false),
        };
        let property = match name {
            "youngs_modulus" => Property::YoungsModulus,
            "density" => Property::Density,
            _ => {
                return Err(CalibrateError::UnknownFit {
                    given: entry.chars().take(40).collect(),
                });
            }
        };
        if out.iter().any(|(p, _)| *p == property) {
            return Err(CalibrateError::Twice {
                property: property.name(),
            });
        }
        out.push((property, each));
    }
    Ok(out)
}

/// One fitted factor.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct FactorEstimate {
    /// The unknown.
    #[serde(flatten)]
    pub unknown: Unknown,
    /// The factor of the typed values, and its standard error.
    pub factor: Factor,
}

/// One measured mode, before and after.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ModeFit {
    /// Its number in the measured file.
    pub mode: usize,
    /// Measured frequency, Hz.
    pub measured_hz: f64,
    /// The specimen's frequency with the typed values, relative error.
    pub typed_error: f64,
    /// With the calibrated values.
    pub calibrated_error: f64,
}

/// The outcome of a calibration.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Calibrated {
    /// The specimen (`monolithic`, `beam:K`).
    pub specimen: String,
    /// Every factor.
    pub factors: Vec<FactorEstimate>,
    /// What the beam model misses beyond the measurement error after the calibration.
    pub discrepancy: Discrepancy,
    /// chi^2 of the calibrated specimen under the measurement error alone, and its degrees of
    /// freedom.
    pub chi2: f64,
    /// Data minus unknowns.
    pub dof: usize,
    /// RMS of the relative frequency errors with the typed values, %.
    pub typed_rms_pct: f64,
    /// With the calibrated values, %.
    pub calibrated_rms_pct: f64,
    /// Mode by mode.
    pub modes: Vec<ModeFit>,
    /// Where the calibrated frequencies still miss beyond the measurement error and their
    /// errors trend with frequency: the factors absorb an effect the beam model lacks (shear,
    /// rotary inertia, a wrong support) and are the model's, not the material's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub trend: Option<Trend>,
    /// What the calibrated model file records, beam by beam.
    pub records: Vec<BeamCalibration>,
}

/// A trend of the relative frequency errors with frequency: e_r = a + slope log10(f_r),
/// ordinary least squares.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Trend {
    /// Change of the relative error per decade of frequency.
    pub per_decade: f64,
    /// The slope in its standard errors (from the scatter about the line).
    pub sigmas: f64,
}

/// Slope of a trend beyond which it is reported, in its standard errors.
pub const TREND_SIGMAS: f64 = 3.0;

/// The trend of `errors` (relative) with the frequencies `hz`, when it is significant
/// ([`TREND_SIGMAS`]) and the frequencies miss by more than twice their stated noise
/// (`discrepancy` beyond `noise`); None with fewer than three modes.
pub fn trend(hz: &[f64], errors: &[f64], discrepancy: f64, noise: f64) -> Option<Trend> {
    let n = hz.len();
    if n < 3 || discrepancy <= 2.0 * noise {
        return None;
    }
    let x: Vec<f64> = hz.iter().map(|f| f.log10()).collect();
    let mean = |v: &[f64]| v.iter().sum::<f64>() / n as f64;
    let (mx, me) = (mean(&x), mean(errors));
    let sxx: f64 = x.iter().map(|v| (v - mx).powi(2)).sum();
    if sxx <= 0.0 {
        return None;
    }
    let slope = x
        .iter()
        .zip(errors)
        .map(|(a, e)| (a - mx) * (e - me))
        .sum::<f64>()
        / sxx;
    let scatter: f64 = x
        .iter()
        .zip(errors)
        .map(|(a, e)| (e - me - slope * (a - mx)).powi(2))
        .sum::<f64>()
        / (n - 2) as f64;
    let se = (scatter / sxx).sqrt().max(f64::MIN_POSITIVE);
    let sigmas = slope / se;
    (sigmas.abs() >= TREND_SIGMAS).then_some(Trend {
        per_decade: slope,
        sigmas,
    })
}

/// The unknowns of `fits` on the beams of `specimen`.
pub fn unknowns(chain: &Chain, specimen: Specimen, fits: &[(Property, bool)]) -> Vec<Unknown> {
    let beams = specimen::beams_of(chain, specimen);
    let mut out = Vec::new();
    for &(property, each) in fits {
        if each && beams.len() > 1 {
            out.extend(beams.iter().map(|&b| Unknown {
                property,
                beams: vec![b],
                name: format!("{}.beam{}", property.name(), b + 1),
            }));
        } else {
            out.push(Unknown {
                property,
                beams: beams.clone(),
                name: property.name().to_string(),
            });
        }
    }
    out
}

/// Calibrates the beams of `chain` on the reference modes `measured` of `request.specimen`
/// (module docs). `measured` is read on the specimen's structure
/// ([`specimen_chain`]`(chain, specimen).build()`).
pub fn calibrate(
    chain: &Chain,
    measured: &MeasuredModes,
    request: &Request,
) -> Result<Calibrated, CalibrateError> {
    let structure = specimen_chain(chain, request.specimen)?.build();
    let unknowns = unknowns(chain, request.specimen, &request.fits);
    let scaled = Scaled::of(chain, request.specimen, &unknowns)?;
    let both = request.fits.len() == 2;
    if both && scaled.only_ratio(&structure) {
        return Err(CalibrateError::OnlyTheRatio);
    }
    let modal = ModalSolution::lowest_of(&structure.assemble(), structure.rigid + 1)?;
    let ctx = Arc::new(EffectContext::new(
        structure.clone(),
        &measured.points(),
        modal.frequency_hz(structure.rigid),
    ));
    let calibration = Calibration {
        noise: request.noise,
        discrepancy: Discrepancy::default(),
        pairing: request.pairing.clone(),
        shape_floor: SHAPE_FLOOR,
        measured_std: request.measured_std,
    };
    let effects: Vec<Arc<dyn Effect>> = vec![Arc::new(scaled)];
    let typed = fit::as_given(&ctx, measured, &calibration)?;
    let fitted = discrepancy::fit_with(
        measured,
        &calibration,
        Discrepancy::default(),
        |c, from| match from {
            Some(from) => fit::refit(&ctx, measured, c, &effects, from, &mut Silent),
            None => fit::fit(&ctx, measured, c, &effects, &mut Silent),
        },
    )?;
    let factors: Vec<FactorEstimate> = unknowns
        .into_iter()
        .zip(&fitted.estimates)
        .map(|(unknown, e)| {
            let value = e.value.exp();
            FactorEstimate {
                unknown,
                factor: Factor {
                    value,
                    se: value * e.se,
                },
            }
        })
        .collect();
    Ok(outcome(
        chain,
        measured,
        request,
        &calibration,
        [&typed, &fitted],
        factors,
    ))
}

/// The calibration's outcome from its two fits, the typed specimen's and the calibrated one's,
/// `calibration` the measurement error alone.
fn outcome(
    chain: &Chain,
    measured: &MeasuredModes,
    request: &Request,
    calibration: &Calibration,
    [typed, fitted]: [&Fitted; 2],
    factors: Vec<FactorEstimate>,
) -> Calibrated {
    let (before, after) = (residuals(typed, measured), residuals(fitted, measured));
    let rms = |e: &[f64]| 100.0 * (e.iter().map(|x| x * x).sum::<f64>() / e.len() as f64).sqrt();
    let modes = measured
        .modes()
        .iter()
        .zip(before.frequency.iter().zip(&after.frequency))
        .map(|(m, (&b, &a))| ModeFit {
            mode: m.mode,
            measured_hz: m.frequency_hz,
            typed_error: b,
            calibrated_error: a,
        })
        .collect();
    let hz: Vec<f64> = measured.modes().iter().map(|m| m.frequency_hz).collect();
    let trend = trend(
        &hz,
        &after.frequency,
        fitted.discrepancy.frequency,
        request.noise.frequency,
    );
    Calibrated {
        specimen: request.specimen.to_string(),
        trend,
        discrepancy: fitted.discrepancy.clone(),
        chi2: fit::chi2_of(&after, measured, calibration),
        dof: fitted.dof,
        typed_rms_pct: rms(&before.frequency),
        calibrated_rms_pct: rms(&after.frequency),
        modes,
        records: records(chain, &factors, &request.reference),
        factors,
    }
}

/// Beam by beam, what the calibrated model records: its factors composed with those of an
/// earlier calibration of the same beam (the standard error of the new one, relative).
fn records(chain: &Chain, factors: &[FactorEstimate], reference: &str) -> Vec<BeamCalibration> {
    let mut out: Vec<BeamCalibration> = Vec::new();
    for (b, _) in chain.beams.iter().enumerate() {
        let earlier = chain.calibration.iter().find(|c| c.beam == b);
        let of = |property: Property| {
            let new = factors
                .iter()
                .find(|f| f.unknown.property == property && f.unknown.beams.contains(&b))?;
            let before = earlier.and_then(|c| match property {
                Property::YoungsModulus => c.stiffness,
                Property::Density => c.density,
            });
            let value = before.map_or(1.0, |f| f.value) * new.factor.value;
            Some(Factor {
                value,
                se: value * new.factor.se / new.factor.value,
            })
        };
        let (stiffness, density) = (of(Property::YoungsModulus), of(Property::Density));
        if stiffness.is_none() && density.is_none() {
            continue;
        }
        out.push(BeamCalibration {
            beam: b,
            stiffness: stiffness.or(earlier.and_then(|c| c.stiffness)),
            density: density.or(earlier.and_then(|c| c.density)),
            reference: Some(reference.to_string()),
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_straight_trend_is_found_with_its_slope_and_a_flat_scatter_is_not() {
        let hz = [100.0, 300.0, 1000.0, 3000.0, 10000.0];
        let line: Vec<f64> = hz
            .iter()
            .zip([1.0, -1.0, 1.0, -1.0, 1.0])
            .map(|(f, s)| -0.01 + 0.02 * f64::log10(*f / 100.0) + 1e-4 * s)
            .collect();
        let t = trend(&hz, &line, 0.01, 0.001).unwrap();
        assert!((t.per_decade - 0.02).abs() < 1e-3, "{t:?}");
        assert!(t.sigmas > 10.0);
        // Within twice the stated noise: nothing to report.
        assert!(trend(&hz, &line, 0.0015, 0.001).is_none());
        let flat = [1e-3, -1e-3, 2e-3, -2e-3, 1e-3];
        assert!(trend(&hz, &flat, 0.01, 0.001).is_none());
        assert!(trend(&hz[..2], &line[..2], 0.01, 0.001).is_none());
    }
}
