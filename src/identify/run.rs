//! The identification of a set of measured modes, each its own way: the paper's system on its
//! shape (eq. (5)-(16)), else its parameter from its frequency alone ([`frequency_only`]),
//! else nothing, with why. What `jointid identify` and the Python package run: the settings
//! are checked before the eigensolution (minutes on a large model), the fallbacks of the
//! modes run in parallel, each one's result the same as alone.

use rayon::prelude::*;

use super::frequency_only::{self, Choice, Fallback, FrequencyError, FrequencyOutcome};
use super::reach::Ends;
use super::{Identifier, IdentifyError, ModeOutcome, Selection, Settings, Weighting};
use crate::input::{Number, RELATIVE_STD, SettingError};
use crate::measured::{MeasuredMode, MeasuredModes};
use crate::modal::{Mechanism, ModalError, ModalSolution, check_elastic, reduced};
use crate::structure::{ModeBeyondModel, Parameter, Structure};

/// What to identify and how: the paper's settings (n, m, weighting; all three, or none to
/// identify every mode from its frequency alone), the parameters (`params`: names, or
/// `["auto"]` to choose them per mode; all by default), the measured modes (all by default)
/// and the relative standard deviation of a frequency without its own standard error.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Request {
    /// Basis size n.
    pub n: Option<usize>,
    /// Retained equations m.
    pub m: Option<usize>,
    /// Weighting of the equations.
    pub weighting: Option<Weighting>,
    /// The parameters of the paper's system, by name (or `auto`).
    pub params: Option<Vec<String>>,
    /// The measured modes to identify.
    pub modes: Option<Vec<usize>>,
    /// Relative standard deviation of a frequency, from 1e-12 to below 1.
    pub frequency_noise: Option<f64>,
}

/// Why the modes cannot be identified, by what is at fault.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// A setting of the request (named as the library names it: `n`, `params`, `modes`,
    /// `frequency_noise`, ...).
    #[error(transparent)]
    Setting(#[from] SettingError),
    /// The model identifies nothing.
    #[error(transparent)]
    Model(IdentifyError),
    /// The model's eigensolution failed.
    #[error("modal solution: {0}")]
    Modal(#[from] ModalError),
    /// The model is a mechanism beyond its rigid-body modes.
    #[error(transparent)]
    Mechanism(#[from] Mechanism),
    /// A measured mode the model or the basis has no mode for.
    #[error(transparent)]
    Beyond(#[from] ModeBeyondModel),
    /// A measured mode the method cannot work with.
    #[error(transparent)]
    Measured(IdentifyError),
    /// A measured shape cannot be projected on the sub-basis.
    #[error(
        "{0}: lower n to the shape components the modes have, or identify each mode's parameter from its frequency alone"
    )]
    Projection(IdentifyError),
}

/// How one measured mode was identified.
#[derive(Debug, Clone)]
pub enum Way {
    /// By the paper's system on its shape.
    Paper(ModeOutcome),
    /// From its frequency alone, and why.
    Frequency(FrequencyOutcome, Fallback),
    /// Not at all: why it fell back, and why its frequency could not identify it either.
    Unsolved(Fallback, FrequencyError),
}

/// One measured mode's identification.
#[derive(Debug, Clone)]
pub struct ModeResult {
    /// Mode r.
    pub mode: usize,
    /// Its measured frequency, Hz.
    pub frequency_hz: f64,
    /// The frequency of the model mode it pairs with, Hz.
    pub model_frequency_hz: f64,
    /// How it was identified.
    pub way: Way,
}

/// The identification of the requested modes, in their order.
#[derive(Debug, Clone)]
pub struct Identified {
    /// The parameters of the paper's system.
    pub params: Vec<Parameter>,
    /// Every identified parameter of the model (a frequency's choice).
    pub all: Vec<Parameter>,
    /// The modes.
    pub modes: Vec<ModeResult>,
}

/// Identifies the modes `request` asks for of `measured` (checked against `model`).
pub fn identify_modes(
    model: &Structure,
    measured: &MeasuredModes,
    request: &Request,
) -> Result<Identified, RunError> {
    identify_modes_solved(model, measured, request, None)
}

/// How many of the nominal model's lowest pairs [`identify_modes`] solves for `request`
/// (rigid-body modes included, `model`'s rigid-body count taken as it is): the paper's
/// basis n, or every pair the modes pair with, and as many again as the modes and two for a
/// reduced model's basis ([`reduced::applies`]); none when the request's modes are not
/// among `measured`'s.
pub fn nominal_count(
    model: &Structure,
    measured: &MeasuredModes,
    request: &Request,
) -> Option<usize> {
    let modes = selected(request.modes.as_deref(), measured).ok()?;
    let (count, basis) = counts(model, &modes, request.n);
    let paper = request.n.is_some() && request.m.is_some() && request.weighting.is_some();
    Some(basis.filter(|_| !paper).unwrap_or(count))
}

/// The pairs of the paper's basis or of the modes' frequencies, and of a reduced model's
/// basis when one applies.
fn counts(model: &Structure, modes: &[&MeasuredMode], n: Option<usize>) -> (usize, Option<usize>) {
    let reach = modes.iter().map(|m| m.mode + model.rigid).max();
    let count = n.or(reach).unwrap_or(model.rigid + 1);
    // A large external model's frequency fallbacks solve on a reduced model (module
    // `crate::modal::reduced`) built on these pairs: as many again as the modes, and two.
    let size = model.dof_count();
    let basis = reduced::applies(model).then(|| (count + modes.len() + 2).min(size));
    (count, basis)
}

/// The request's frequency noise, when given: a relative standard deviation from 1e-12 to
/// below 1.
fn check_frequency_noise(noise: Option<f64>) -> Result<(), RunError> {
    match noise {
        Some(v) if !(v.is_finite() && v >= RELATIVE_STD.0 && v < 1.0) => Err(SettingError::new(
            "frequency_noise",
            Number(v),
            "a relative standard deviation from 1e-12 to below 1",
        )
        .into()),
        _ => Ok(()),
    }
}

/// As [`identify_modes`], the nominal model's pairs taken from `nominal` (a solve of `model`
/// as it is, [`crate::model::from_path_solved`], with its factor) when it holds as many as
/// [`nominal_count`]: the same pairs, not solved twice.
pub fn identify_modes_solved(
    model: &Structure,
    measured: &MeasuredModes,
    request: &Request,
    nominal: Option<ModalSolution>,
) -> Result<Identified, RunError> {
    check_frequency_noise(request.frequency_noise)?;
    let all = model.identified();
    if all.is_empty() {
        // before the eigensolution, and the same refusal with or without frequencies alone
        return Err(RunError::Model(IdentifyError::NoParameters));
    }
    let (params, selection, choice) = chosen(request.params.as_deref(), &all)?;
    let settings = match (request.n, request.m, request.weighting) {
        (Some(n), Some(m), Some(weighting)) => {
            let s = Settings::new(n, m, weighting, model)?;
            s.check_equations(params.len(), model.rigid)?;
            Some(s)
        }
        _ => None,
    };
    let modes = selected(request.modes.as_deref(), measured)?;
    for mode in &modes {
        model.model_mode(mode.mode)?;
        if let Some(s) = &settings {
            super::basis_index(mode.mode, model.rigid, s.n).map_err(RunError::Measured)?;
        }
    }
    let matrices = model.assemble();
    // the paper's basis of n pairs, or every pair the modes' frequencies pair with
    let reach = modes.iter().map(|m| m.mode + model.rigid).max();
    let (count, basis) = counts(model, &modes, request.n);
    // The nominal solve's factor of K - sigma M, for the reduced model's basis (the same
    // factor, not made twice).
    let factored = basis.filter(|_| settings.is_none());
    let solve = factored.unwrap_or(count);
    let mut modal = match nominal.filter(|n| n.len() == solve) {
        Some(given) => given,
        None if factored.is_some() => ModalSolution::lowest_of_factored(&matrices, solve)?,
        None => ModalSolution::lowest_of(&matrices, count)?,
    };
    let factor = modal.take_factor();
    check_elastic(&matrices, &modal, model.rigid)?;
    let identifier = settings
        .map(|settings| Identifier::new(&modal, params.clone(), model.rigid, settings))
        .transpose()
        .map_err(RunError::Model)?;
    let planned = planned(identifier.as_ref(), modes, selection)?;
    let falls_back = planned.iter().any(|(_, plan)| plan.is_err());
    let attached = match basis {
        Some(b) if falls_back => {
            let (nominal, factor) = if modal.len() >= b {
                (modal.clone(), factor)
            } else {
                drop(factor);
                let mut nominal = ModalSolution::lowest_of_factored(&matrices, b)?;
                let factor = nominal.take_factor();
                (nominal, factor)
            };
            let directions: Vec<_> = params.iter().map(|p| (&p.stiffness, &p.mass)).collect();
            let wanted = model.rigid..(reach.unwrap_or(count) + 2).min(nominal.len());
            Some(reduced::attach(
                model,
                &nominal,
                factor,
                &directions,
                wanted,
            )?)
        }
        _ => {
            drop(factor);
            None
        }
    };
    let model = attached.as_ref().unwrap_or(model);
    let ends = Ends::new(model, reach.unwrap_or(count));
    let modes = planned
        .into_par_iter()
        .map(|(mode, plan)| {
            let way = match plan {
                Ok(o) => Way::Paper(o),
                Err(why) => {
                    let f_std = mode
                        .frequency_std
                        .map(|s| s / mode.frequency_hz)
                        .or(request.frequency_noise);
                    let f = model
                        .model_mode(mode.mode)
                        .map_err(FrequencyError::from)
                        .and_then(|t| {
                            frequency_only::identify_within(
                                model,
                                t,
                                mode.mode,
                                mode.frequency_hz,
                                f_std,
                                choice,
                                Some(&ends),
                            )
                        });
                    match f {
                        Ok(f) => Way::Frequency(f, why),
                        Err(FrequencyError::Modal(e)) => return Err(RunError::Modal(e)),
                        Err(e) => Way::Unsolved(why, e),
                    }
                }
            };
            let paired = model.model_mode(mode.mode)?;
            Ok(ModeResult {
                mode: mode.mode,
                frequency_hz: mode.frequency_hz,
                model_frequency_hz: modal.frequency_hz(paired),
                way,
            })
        })
        .collect::<Result<Vec<ModeResult>, RunError>>()?;
    Ok(Identified { params, all, modes })
}

/// A mode and its paper's outcome, or why it falls back to its frequency alone.
type Planned<'a> = (&'a MeasuredMode, Result<ModeOutcome, Fallback>);

/// The paper's system on each mode's shape (`identifier`: None to use frequencies alone), or
/// why the mode falls back to its frequency alone; an error where the projection cannot be
/// made.
fn planned<'a>(
    identifier: Option<&Identifier>,
    modes: Vec<&'a MeasuredMode>,
    selection: Selection,
) -> Result<Vec<Planned<'a>>, RunError> {
    let mut planned = Vec::new();
    for mode in modes {
        let shape = identifier
            .map(|id| id.identify_selected(mode, id.basis_index(mode.mode)?, selection))
            .transpose();
        let plan = match shape {
            Ok(Some(o)) if o.relative.is_ok() => Ok(o),
            Ok(Some(o)) => Err(Fallback::RankDeficient(o)),
            Ok(None) => Err(Fallback::Asked),
            Err(e @ IdentifyError::Projection { .. }) => return Err(RunError::Projection(e)),
            Err(e) => return Err(RunError::Measured(e)),
        };
        planned.push((mode, plan));
    }
    Ok(planned)
}

/// The parameters of the paper's system (`names`), its selection, and the parameter a mode's
/// frequency identifies (the one named when `names` names one, else the most sensitive).
pub fn chosen(
    names: Option<&[String]>,
    all: &[Parameter],
) -> Result<(Vec<Parameter>, Selection, Choice), SettingError> {
    let names = match names {
        None => return Ok((all.to_vec(), Selection::All, Choice::MostSensitive)),
        Some([auto]) if auto == "auto" => {
            return Ok((all.to_vec(), Selection::Auto, Choice::MostSensitive));
        }
        Some(names) if names.iter().any(|n| n == "auto") => {
            return Err(SettingError::new(
                "params",
                names.join(","),
                "`auto` chooses the parameters on each mode and is given alone, not with names",
            ));
        }
        Some(names) => names,
    };
    let mut chosen: Vec<Parameter> = Vec::with_capacity(names.len());
    for name in names {
        let Some(p) = all.iter().find(|p| &p.name == name) else {
            let known: Vec<&str> = all.iter().map(|p| p.name.as_str()).collect();
            return Err(SettingError::new(
                "params",
                name,
                format!("the model identifies {} (or give `auto`)", known.join(", ")),
            ));
        };
        if chosen.iter().any(|c| &c.name == name) {
            return Err(SettingError::new(
                "params",
                names.join(","),
                format!("it lists {name} twice"),
            ));
        }
        chosen.push(p.clone());
    }
    let choice = match chosen.as_slice() {
        [one] => Choice::Named(all.iter().position(|p| p.name == one.name).unwrap_or(0)),
        _ => Choice::MostSensitive,
    };
    Ok((chosen, Selection::All, choice))
}

/// The measured modes `list` asks for (every one by default).
pub fn selected<'a>(
    list: Option<&[usize]>,
    measured: &'a MeasuredModes,
) -> Result<Vec<&'a MeasuredMode>, SettingError> {
    let Some(list) = list else {
        return Ok(measured.modes().iter().collect());
    };
    let text = || {
        let v: Vec<String> = list.iter().map(|r| r.to_string()).collect();
        v.join(",")
    };
    if let Some(r) = list
        .iter()
        .enumerate()
        .find_map(|(i, r)| list[..i].contains(r).then_some(r))
    {
        return Err(SettingError::new(
            "modes",
            text(),
            format!("it lists mode {r} twice"),
        ));
    }
    list.iter()
        .map(|&r| {
            measured.get(r).ok_or_else(|| {
                let have: Vec<String> = measured
                    .modes()
                    .iter()
                    .map(|m| m.mode.to_string())
                    .collect();
                SettingError::new(
                    "modes",
                    text(),
                    format!(
                        "it asks for mode {r}, which the measured modes do not hold (they have modes {})",
                        have.join(",")
                    ),
                )
            })
        })
        .collect()
}
