//! Amplitude dependence of a joint across excitation levels: per mode, the modal stiffness
//! lambda = (2 pi f)^2 and the damping ratio against the response amplitude, fitted by three
//! laws (constant, power law, Segalman's four-parameter Iwan model), one chosen by AICc, with
//! standard errors and uncertainty bands (docs/method.md, "Amplitude dependence").
//!
//! The steps, in the order of the data:
//! - [`levels`]: the levels file (which modes file and amplitude source per level);
//! - [`load`](mod@load): the modes and amplitudes of every level, per mode;
//! - [`iwan`]: the Iwan model's closed forms (secant stiffness, dissipation) and derivatives;
//! - [`laws`]: the three laws of stiffness and damping against amplitude;
//! - [`fit`](mod@fit): weighted least squares of one law, the extra variance of the scatter;
//! - [`select`]: every law on one mode, the choice, the bands;
//! - [`joint`]: with a joint parameter named, the same on the joint's own stiffness and
//!   damping per level, and the frequencies before and after.
//!
//! Entry point: [`fit_levels`]. Returns data; `crate::output::amplitude` writes it.
//!
//! Layer 6 (diagnosis and results; see the crate docs): may import the layers below
//! ([`crate::input`], [`crate::optim`], [`crate::uff`], [`crate::model`], [`crate::measured`],
//! [`crate::identify`], [`crate::modal`]).

pub mod fit;
pub mod iwan;
pub mod joint;
pub mod laws;
pub mod levels;
pub mod load;
pub mod select;

use std::path::PathBuf;

pub use fit::{Series, Weights};
pub use iwan::{Iwan, Segalman};
pub use joint::{JointData, LevelError};
pub use laws::{LAWS, Law, Regime};
pub use levels::Levels;
pub use load::{ModeData, Row, load};
pub use select::{BandPoint, Judged, ModeFit, fit_mode};

/// An amplitude fit that cannot be made.
#[derive(Debug, thiserror::Error)]
pub enum AmplitudeError {
    /// The levels file or the model.
    #[error(transparent)]
    Input(#[from] crate::input::InputError),
    /// A measured-modes file.
    #[error(transparent)]
    Measured(#[from] crate::measured::MeasuredError),
    /// An FRF file.
    #[error(transparent)]
    Uff(#[from] crate::uff::UffError),
    /// The joint's stiffness cannot be had from a level's frequency.
    #[error("the joint's stiffness: {0}")]
    Joint(String),
    /// A file whose content does not serve the fit.
    #[error("{file}: {message}")]
    Data {
        /// The file.
        file: PathBuf,
        /// What is wrong and what is allowed.
        message: String,
    },
}

/// A parameter of a fitted law, or a quantity derived from them.
#[derive(Debug, Clone, PartialEq)]
pub struct Estimate {
    /// Name (`lambda_0`, `F_S`, `phi_max_min`, ...).
    pub name: String,
    /// Value.
    pub value: f64,
    /// Standard error (NaN when the data do not determine it, or for a bound).
    pub std: f64,
}

/// One mode's data and fit.
#[derive(Debug, Clone, PartialEq)]
pub struct ModeResult {
    /// The data.
    pub data: ModeData,
    /// The fit.
    pub fit: ModeFit,
    /// With a joint parameter named: its data, fit and the frequencies before and after.
    pub joint: Option<JointResult>,
}

/// The joint's stiffness and damping of one mode against amplitude ([`joint`]).
#[derive(Debug, Clone, PartialEq)]
pub struct JointResult {
    /// The joint's parameter and damping per level.
    pub data: JointData,
    /// The laws fitted on them.
    pub fit: ModeFit,
    /// Per level: the frequencies with the constant and the chosen law's joint.
    pub errors: Vec<LevelError>,
}

/// Every mode of a levels file.
#[derive(Debug, Clone, PartialEq)]
pub struct AmplitudeFit {
    /// Unit of the excitation ("" when not given).
    pub excitation_unit: String,
    /// One result per mode.
    pub modes: Vec<ModeResult>,
}

/// Reads the levels of `levels` and fits every mode (module docs); with `joint` (the name of
/// one of the model's identified parameters) also the joint's stiffness and damping.
pub fn fit_levels(levels: &Levels, joint: Option<&str>) -> Result<AmplitudeFit, AmplitudeError> {
    let model = crate::model::from_path(&levels.model)?;
    let param = joint
        .map(|name| {
            let names: Vec<String> = model.identified().iter().map(|p| p.name.clone()).collect();
            names.iter().position(|n| *n == name).ok_or_else(|| {
                AmplitudeError::Input(crate::input::InputError::Invalid {
                    file: levels.model.clone(),
                    path: "--joint".into(),
                    value: format!("\"{name}\""),
                    allowed: format!(
                        "the name of one of the model's identified parameters: {}",
                        names.join(", ")
                    ),
                })
            })
        })
        .transpose()?;
    let data = load(levels, &model)?;
    if param.is_some() {
        // The joint comes from each mode's frequency on the model mode it pairs with by order.
        for d in &data {
            model.model_mode(d.mode).map_err(|e| AmplitudeError::Data {
                file: levels.levels[0].modes.clone(),
                message: format!("{e}: --joint needs the model mode of every mode"),
            })?;
        }
    }
    let modes = data
        .into_iter()
        .map(|data| {
            let fit = fit_mode(&data.series());
            let joint = param
                .map(|param| -> Result<JointResult, AmplitudeError> {
                    let jd = joint::joint_data(&model, param, &data)?;
                    let jfit = fit_mode(&jd.series());
                    let errors = joint::level_errors(&model, param, &data, &jd, &jfit)?;
                    Ok(JointResult {
                        data: jd,
                        fit: jfit,
                        errors,
                    })
                })
                .transpose()?;
            Ok(ModeResult { data, fit, joint })
        })
        .collect::<Result<_, AmplitudeError>>()?;
    Ok(AmplitudeFit {
        excitation_unit: levels.excitation_unit.clone(),
        modes,
    })
}

/// The parameters of a judged law with their standard errors, then for the Iwan law
/// Segalman's F_S and beta: under macroslip with standard errors by the delta method (the
/// conversion's gradient by central differences); under microslip, where phi_max is only
/// bounded (above the largest amplitude, below where S = 0), their values at both bounds
/// (`_at_phi_max_min`, `_at_phi_max_max`, no standard error). The Iwan quantities are
/// computed on the scaled amplitude of the fit ([`fit::Fitted::evaluate`]): F_S and phi_max
/// are then multiplied by the reference amplitude, beta is a ratio.
pub fn estimates(judged: &Judged) -> Vec<Estimate> {
    let f = &judged.fitted;
    let names = f.law.parameters(f.regime);
    let std = |i: usize| {
        f.covariance
            .as_ref()
            .map_or(f64::NAN, |c| c[i][i].max(0.0).sqrt())
    };
    let mut out: Vec<Estimate> = names
        .iter()
        .enumerate()
        .map(|(i, n)| Estimate {
            name: n.to_string(),
            value: f.parameters[i],
            std: std(i),
        })
        .collect();
    if f.law == Law::Iwan {
        match f.regime {
            Regime::Macroslip => out.extend(segalman_estimates(f)),
            Regime::Microslip => out.extend(microslip_bounds(f)),
        }
    }
    out
}

/// The Iwan element of scaled parameters `q` with phi_max (scaled) `phi`.
fn scaled_iwan(q: &[f64], phi: f64) -> Iwan {
    Iwan {
        k_t: q[0],
        chi: q[1],
        r: q[2],
        phi_max: phi,
    }
}

/// F_S and beta of a macroslip Iwan fit, with standard errors by the delta method.
fn segalman_estimates(f: &fit::Fitted) -> Vec<Estimate> {
    let p = &f.scaled;
    let s = scaled_iwan(p, p[4]).segalman();
    [("F_S", s.f_s, f.reference), ("beta", s.beta, 1.0)]
        .into_iter()
        .map(|(k, value, unit)| {
            let pick = |q: &[f64]| {
                let m = scaled_iwan(q, q[4]).segalman();
                if k == "F_S" { m.f_s } else { m.beta }
            };
            let grad: Vec<f64> = (0..p.len())
                .map(|j| {
                    let h = 1e-6 * p[j].abs().max(1e-300);
                    let (mut up, mut down) = (p.clone(), p.clone());
                    up[j] += h;
                    down[j] -= h;
                    (pick(&up) - pick(&down)) / (2.0 * h)
                })
                .collect();
            let var = f.scaled_covariance.as_ref().map_or(f64::NAN, |c| {
                (0..p.len())
                    .map(|a| {
                        (0..p.len())
                            .map(|b| grad[a] * c[a][b] * grad[b])
                            .sum::<f64>()
                    })
                    .sum()
            });
            Estimate {
                name: k.to_string(),
                value: value * unit,
                std: var.max(0.0).sqrt() * unit,
            }
        })
        .collect()
}

/// phi_max's bounds of a microslip Iwan fit (the largest amplitude, where S = 0), with F_S
/// and beta at each.
fn microslip_bounds(f: &fit::Fitted) -> Vec<Estimate> {
    let p = &f.scaled;
    // The scaled amplitudes reach 1 (the reference is the largest amplitude).
    let lo = 1.0;
    let e = p[1] + 1.0;
    let hi = if p[2] > 0.0 {
        (p[0] * e / p[2]).powf(1.0 / e)
    } else {
        f64::INFINITY
    };
    let mut out = Vec::new();
    for (suffix, phi) in [("min", lo), ("max", hi)] {
        let s = scaled_iwan(p, phi).segalman();
        for (name, value) in [
            (format!("phi_max_{suffix}"), phi * f.reference),
            (format!("F_S_at_phi_max_{suffix}"), s.f_s * f.reference),
            (format!("beta_at_phi_max_{suffix}"), s.beta),
        ] {
            out.push(Estimate {
                name,
                value,
                std: f64::NAN,
            });
        }
    }
    out
}
