//! `layered_lap`: the point joints whose overlap the model file gives (`[joint.lap]`) replaced
//! by the layered lap over that overlap (`crate::model::chain::layered`): two layers joined by
//! an interface of normal and shear stiffness k_n, k_s per unit length, fitted in place of the
//! joint's k1, k2, and, where a layer is thinner than its beam, the rotational stiffness k_r
//! of the notch at its root (`crate::model::chain::notch`), fitted with them. Without k_r the
//! 1D layers are stiffer than the solid lap they stand for: plane sections carry the beam's
//! full section right up to the free face where the other layer ends.
//!
//! The fit is the calibration's (module `fit`): x = ln(p / p_0) for every joint parameter (the
//! laps' k_n, k_s, k_r and the other joints' k1, k2), the shape scales c_r, Levenberg-Marquardt,
//! with its own discrepancy (module `discrepancy`). A glued interface runs k_n, k_s to their
//! rigid end and is reported there as a limit (module `fit`'s `limits`).
//! The starts p_0 of k_n, k_s, k_r are points of a grid around their nominal values (the
//! model file's, or else the interface's natural scales:
//! [`crate::model::chain::Lap::shear_scale`] for k_s, 10^4 times
//! [`crate::model::chain::Lap::normal_scale`] for k_n, bolted contact being stiff in
//! compression, and the notch's bonded-limit stiffness for k_r): k_s at 10^-3 ... 10^3 of its
//! nominal value by half decades, k_n at 10^-2, 1, 10^2 of its, k_r at 1 and 10 times its (a
//! compliant interface makes the root stiffer than the bonded notch); every lap at the same
//! factors. The basins along k_s can be narrower than a decade: on the solid lap of a soft
//! uniform interface on nine sensors (`tests/fixtures/lap3d/soft-uniform-9`, k_s a third of
//! its scale) the fits from every start of a grid of whole decades ended at a fifth of the
//! interface's k_s or at twice it (deviance -464 and -446, 2.3% RMS left in the frequencies),
//! where the half-decade start next to it reaches it (-487, k_s within 6%; with shear,
//! 0.19% RMS).
//! A grid point that pairs a measured mode with an axial mode of the layers (the slip of a
//! soft interface brings them down among the bending modes) is no start.
//!
//! The fit has several basins along k_s: a fit from a start on the soft side can end with the
//! slip paired with a bending mode, or in a minimum between two pairings, where a start from
//! the bonded side descends to the interface the data show. So the lap is fitted from the
//! start of least chi^2 with only the shape scales fitted and from the best of the stiffest
//! k_s, then from the next by chi^2 until two fits pair every mode with a bending mode (five
//! starts at most: neighbouring starts often end in the same pairing with an axial mode), and
//! the one of least deviance is kept; where none does, the first start's outcome stands
//! (excluded with that reason, or its error). On the solid lap of a softer interface (a tenth
//! of the fixtures' k_n, k_t), three bolts on nine sensors
//! (`tests/fixtures/lap3d/soft-bolts-9`), every start of the grid in whole decades with k_s
//! below 10 times its scale ended in one of three minima of deviance -403 to -410 (the best
//! start: k_s a quarter of the interface's mean over the overlap, 5.3% RMS left in the
//! frequencies), every one from 10 times up in one of -489 (k_s within 4% of that mean; with
//! shear, 0.47% RMS).
//!
//! The lap is not nested in the point joint. Its likelihood-ratio statistic chi^2(point) -
//! chi^2(lap) is tested with one added parameter for the overlap's given geometry (k_n, k_s
//! are as many as k1, k2: a model with no more unknowns than the point joint is asked to
//! explain more, conservative) and one per fitted k_r.
//!
//! Size: k_s of the first lap, N/m per m.

use std::sync::Arc;

use super::{Candidate, CandidateError, Fit, Part, Stage, Tier};
use crate::diagnose::discrepancy;
use crate::diagnose::fit::{self, Calibration, Fitted};
use crate::diagnose::progress::Iterations;
use crate::model::chain::assembly::LAYERED_LAP;
use crate::model::effects::EffectContext;
use crate::structure::{Direction, Structure};

/// See the module docs.
#[derive(Debug, Clone, Copy)]
pub struct LayeredLap;

/// Factors of the grid of starts on the shear scale: 10^-3 ... 10^3 by half decades.
const SHEAR_FACTORS: [f64; 13] = [
    1e-3, 3.16e-3, 1e-2, 3.16e-2, 1e-1, 3.16e-1, 1.0, 3.16, 1e1, 3.16e1, 1e2, 3.16e2, 1e3,
];
/// Factors of the grid of starts on the normal scale.
const NORMAL_FACTORS: [f64; 3] = [1e-2, 1.0, 1e2];
/// Factors of the grid of starts on the roots' notch stiffness (the bonded limit: a real
/// interface makes the root stiffer).
const ROOT_FACTORS: [f64; 2] = [1.0, 10.0];

/// The structure with the layered laps, if the model gives one.
fn alternative(ctx: &EffectContext) -> Option<&Arc<Structure>> {
    ctx.structure
        .alternatives
        .iter()
        .find(|a| a.name == LAYERED_LAP)
        .map(|a| &a.structure)
}

/// The indices (into the parameters) of every lap's k_n, k_s and, where its roots are
/// notched, k_r.
fn lap_parameters(structure: &Structure) -> Vec<[Option<usize>; 3]> {
    structure
        .sites
        .joints
        .iter()
        .filter(|j| j.lap)
        .map(|j| [Some(j.parameters[0]), Some(j.parameters[1]), j.root])
        .collect()
}

/// The context of `structure` with every lap's (k_n, k_s, k_r) at `factors` times their
/// nominal values.
fn context_at(stage: &Stage, structure: &Structure, factors: [f64; 3]) -> Arc<EffectContext> {
    let mut s = structure.clone();
    for lap in lap_parameters(structure) {
        for (k, i) in lap.iter().enumerate() {
            if let Some(i) = *i {
                s.parameters[i].value *= factors[k];
            }
        }
    }
    Arc::new(EffectContext {
        structure: s,
        sensors: stage.ctx.sensors.clone(),
        first_elastic_hz: stage.ctx.first_elastic_hz,
    })
}

/// Share of a mode's translational motion (sum of squares of its mass-normalised axial and
/// transverse components) beyond which it is an axial mode: the lap's offset layers couple
/// bending to the bars' axial motion, and a bending mode near the first axial one carries a
/// large axial part (four tenths in the 3D lap's sixth mode), while the slip of a soft
/// interface is axial almost entirely.
const AXIAL_SHARE: f64 = 0.8;

/// The first measured mode (1-based) that `fitted` pairs with an axial mode of the layers
/// (a model mode whose translational motion is more than [`AXIAL_SHARE`] axial: transverse
/// sensors barely see it, and a MAC on a few of them may still resemble a bending mode).
pub(super) fn axial_pair(fitted: &Fitted) -> Option<usize> {
    let structure = &fitted.configured.structure;
    let y = fitted.modal.vectors();
    let share = |s: usize, d: Direction| -> f64 {
        (0..structure.dof_count())
            .filter(|&i| structure.dofs.get(i).direction == d)
            .map(|i| y[(i, s)].powi(2))
            .sum()
    };
    fitted
        .pairing
        .model_index
        .iter()
        .position(|&s| {
            let (x, w) = (share(s, Direction::X), share(s, Direction::W));
            x > AXIAL_SHARE * (x + w)
        })
        .map(|r| r + 1)
}

/// A start: the factors of the grid point (k_n, k_s, k_r) and the context at them.
type Start = ([f64; 3], Arc<EffectContext>);

/// The starts: the grid points that pair every measured mode with a bending mode, by
/// increasing chi^2 with only the shape scales fitted.
fn starts(stage: &Stage, structure: &Structure) -> Result<Vec<Start>, CandidateError> {
    let mut found: Vec<(f64, [f64; 3], Arc<EffectContext>)> = Vec::new();
    let mut failure = None;
    let roots: &[f64] = if lap_parameters(structure).iter().any(|l| l[2].is_some()) {
        &ROOT_FACTORS
    } else {
        &[1.0]
    };
    let calibration = Calibration {
        discrepancy: stage.start(),
        ..stage.calibration.clone()
    };
    let grid = NORMAL_FACTORS
        .iter()
        .flat_map(|&n| SHEAR_FACTORS.iter().map(move |&s| (n, s)))
        .flat_map(|(n, s)| roots.iter().map(move |&r| [n, s, r]));
    for factors in grid {
        let ctx = context_at(stage, structure, factors);
        match fit::as_given(&ctx, stage.measured, &calibration) {
            Ok(f) if axial_pair(&f).is_none() => found.push((f.chi2, factors, ctx)),
            Ok(_) => {}
            Err(e) => {
                failure.get_or_insert(e);
            }
        }
    }
    // A stable sort: of equal chi^2 the grid's first.
    found.sort_by(|a, b| a.0.total_cmp(&b.0));
    match (found.is_empty(), failure) {
        (false, _) => Ok(found
            .into_iter()
            .map(|(_, factors, ctx)| (factors, ctx))
            .collect()),
        (true, Some(e)) => Err(e.into()),
        (true, None) => Err(CandidateError::Undetermined("no start".into())),
    }
}

/// The order in which the starts are fitted (module docs): the best (least chi^2 with only the
/// shape scales fitted), the best with the stiffest interface shear of the grid (the bonded
/// side of the basins along k_s), then the others by chi^2.
fn ordered(mut starts: Vec<Start>) -> Vec<Arc<EffectContext>> {
    let stiffest = SHEAR_FACTORS[SHEAR_FACTORS.len() - 1];
    // Second, unless it is already first or second.
    if let Some(i) = starts
        .iter()
        .position(|(f, _)| f[1] == stiffest)
        .filter(|&i| i > 1)
    {
        let bonded = starts.remove(i);
        starts.insert(1, bonded);
    }
    starts.into_iter().map(|(_, ctx)| ctx).collect()
}

/// How many starts are fitted at most ([`ordered`]): two fits that pair every mode with a
/// bending mode are sought among them, past starts whose fit pairs one with an axial mode.
const STARTS_TRIED: usize = 5;

impl Candidate for LayeredLap {
    fn name(&self) -> &'static str {
        LAYERED_LAP
    }

    fn tier(&self) -> Tier {
        Tier::Default
    }

    fn describe(&self) -> &'static str {
        "the point joints whose overlap the model file gives ([joint.lap]) replaced by the layered lap: the two beams as two layers over the overlap, joined by an interface of normal and shear stiffness k_n, k_s per unit length fitted in place of k1, k2, with the rotational stiffness k_r of the layers' notched roots; size = k_s of the first lap (N/m per m)"
    }

    fn applies(&self, ctx: &EffectContext) -> bool {
        alternative(ctx).is_some()
    }

    fn part(&self) -> Option<Part> {
        Some(Part::Lap)
    }

    fn fit(&self, stage: &Stage) -> Result<Fit, CandidateError> {
        let structure = alternative(stage.ctx).ok_or_else(|| {
            CandidateError::Undetermined("the model file gives no joint's overlap".into())
        })?;
        let measured = stage.measured;
        let mut told = Iterations {
            watch: stage.watch,
            candidate: LAYERED_LAP,
            variant: None,
        };
        // The fits from the starts in order ([`ordered`]) until two pair every measured mode
        // with a bending mode: of those, the one of least deviance; else the first start's
        // outcome.
        let mut best: Option<Fit> = None;
        let mut bending = 0;
        let mut first: Option<Result<Fit, CandidateError>> = None;
        let ordered = ordered(starts(stage, structure)?);
        for ctx in ordered.iter().take(STARTS_TRIED) {
            if bending == 2 {
                break;
            }
            let outcome = fit_from(ctx, stage, &mut told).map(|fitted| {
                let (parameters, added, size) = summary(&fitted);
                let excluded = axial_pair(&fitted).map(|r| {
                    format!("the fit pairs measured mode {r} with an axial mode of the layers")
                });
                Fit::of_model(
                    measured,
                    fitted,
                    parameters,
                    size,
                    self.describe().to_string(),
                    added,
                    excluded,
                )
            });
            match outcome {
                Ok(fit) if fit.excluded.is_none() => {
                    bending += 1;
                    if best.as_ref().is_none_or(|b| fit.deviance < b.deviance) {
                        best = Some(fit);
                    }
                }
                other => {
                    first.get_or_insert(other);
                }
            }
        }
        match (best, first) {
            (Some(fit), _) => Ok(fit),
            (None, Some(outcome)) => outcome,
            (None, None) => Err(CandidateError::Undetermined("no start".into())),
        }
    }
}

/// The lap's fit with its own discrepancy from the start `ctx`.
fn fit_from(
    ctx: &Arc<EffectContext>,
    stage: &Stage,
    told: &mut Iterations,
) -> Result<Fitted, CandidateError> {
    let measured = stage.measured;
    Ok(discrepancy::fit_with(
        measured,
        stage.calibration,
        stage.start(),
        |cal, from| match from {
            Some(from) => fit::refit(ctx, measured, cal, &[], from, told),
            None => fit::fit(ctx, measured, cal, &[], told),
        },
    )?)
}

/// The laps' fitted parameters in `fitted` (k_n, k_s, k_r of each), the unknowns the laps add
/// to the point joint's model (one for the overlap's given geometry, one per fitted k_r), and
/// the size (k_s of the first lap) with its standard error.
pub(super) fn summary(fitted: &Fitted) -> (Vec<fit::Estimate>, usize, (f64, f64)) {
    let laps = lap_parameters(&fitted.configured.structure);
    // The estimates are the identified parameters' in model order (a fixed k_n or k_s
    // has none).
    let estimate = |i: usize| {
        let identified = fitted.configured.structure.identified_indices();
        let at = identified.iter().position(|&p| p == i)?;
        Some(fitted.estimates[at].clone())
    };
    let parameters: Vec<fit::Estimate> = laps
        .iter()
        .flatten()
        .flatten()
        .filter_map(|&i| estimate(i))
        .collect();
    // One added parameter for the overlap's given geometry, one per fitted k_r.
    let added = 1 + laps
        .iter()
        .filter_map(|l| l[2])
        .filter(|&i| estimate(i).is_some())
        .count();
    let first_ks = laps.first().and_then(|l| l[1]);
    let size = first_ks.map_or(0.0, |i| fitted.configured.structure.parameters[i].value);
    let size_se = first_ks.and_then(estimate).map_or(0.0, |e| e.se);
    (parameters, added, (size, size_se))
}
