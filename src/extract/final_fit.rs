//! The final fit of the kept modes (step 5 of [`super`]): their poles refined when the
//! settings ask for it and the refinement is acceptable, the LSFD residues, the FRFs of the
//! model; in the automatic choice a mode whose MPC falls below `mpc_min` here is rejected and
//! the fit made again without it.

use faer::c64;

use super::choice::{self, Decision, Reason};
use super::stabilization::{ChartPole, Criteria};
use super::{ExtractError, Settings, frf, lsfd, refine, shapes};

fn frequency(s: c64) -> f64 {
    s.norm() / (2.0 * std::f64::consts::PI)
}

/// What the final fit works on.
pub(super) struct Problem<'a> {
    pub(super) omega: &'a [f64],
    pub(super) band: &'a frf::Band,
    pub(super) basis: lsfd::Basis,
    pub(super) responses: &'a [Vec<c64>],
    pub(super) criteria: &'a Criteria,
    pub(super) settings: &'a Settings,
}

/// The final fit of the kept modes: their poles, the least squares of the residues, the FRFs
/// of the model, and the decisions with the kept ones first, in the order of the poles.
pub(super) struct Fitted {
    pub(super) poles: Vec<c64>,
    pub(super) refined: bool,
    pub(super) ls: crate::optim::lstsq::LeastSquares,
    pub(super) fit: lsfd::Fit,
    pub(super) synthesized: Vec<Vec<c64>>,
    pub(super) decisions: Vec<Decision>,
}

/// Fits the kept modes of `decisions` (see [`Fitted`]); in the automatic choice, rejects
/// those whose MPC falls below `mpc_min` in the fit and fits again without them.
pub(super) fn fit_kept(
    p: &Problem,
    chart: &mut [ChartPole],
    mut decisions: Vec<Decision>,
) -> Result<Fitted, ExtractError> {
    let (lo, hi) = (p.band.lo, p.band.hi);
    loop {
        let kept = decisions.iter().filter(|d| d.mode.is_some()).count();
        enough_modes(kept, p.settings, p.criteria, (lo, hi))?;
        let start: Vec<c64> = decisions[..kept]
            .iter()
            .map(|d| chart[d.pole].pole)
            .collect();
        let (poles, refined) = final_poles(
            p.omega,
            p.band,
            start,
            p.basis,
            p.responses,
            p.criteria,
            p.settings,
        );
        let ls = lsfd::least_squares(p.omega, &p.band.weights, &poles, p.basis, p.responses);
        let fit = lsfd::unpack(&ls.x, poles.len(), p.basis, ls.rank);
        let mut complex = false;
        for ((d, pole), residues) in decisions.iter_mut().zip(&poles).zip(&fit.residues) {
            d.frequency_hz = frequency(*pole);
            d.damping_ratio = -pole.re / pole.norm();
            d.mpc = shapes::real_mode(residues).mpc;
            if p.settings.n_modes.is_none() && d.mpc < p.settings.mpc_min {
                d.rejected = Some(Reason::ComplexAfterFit {
                    mpc: d.mpc,
                    min: p.settings.mpc_min,
                });
                complex = true;
            }
        }
        if complex {
            decisions = choice::number_kept(chart, decisions);
            continue;
        }
        let synthesized = lsfd::synthesize(p.omega, &poles, p.basis, &fit);
        return Ok(Fitted {
            poles,
            refined,
            ls,
            fit,
            synthesized,
            decisions,
        });
    }
}

/// The poles the modes are given with: the chart's `start` refined when the settings ask for
/// it and the refined poles are [`acceptable`], else `start`; and whether they were refined.
fn final_poles(
    omega: &[f64],
    band: &frf::Band,
    start: Vec<c64>,
    basis: lsfd::Basis,
    responses: &[Vec<c64>],
    criteria: &Criteria,
    settings: &Settings,
) -> (Vec<c64>, bool) {
    if !settings.refine {
        return (start, false);
    }
    let r = refine::refine(omega, &band.weights, &start, basis, responses);
    if acceptable(&r.poles, &start, (band.lo, band.hi), criteria) {
        (r.poles, true)
    } else {
        (start, false)
    }
}

/// Whether `found` chains are enough: at least one, and the modes `settings` asks for.
fn enough_modes(
    found: usize,
    settings: &Settings,
    criteria: &Criteria,
    (lo, hi): (f64, f64),
) -> Result<(), ExtractError> {
    if found == 0 {
        return Err(ExtractError::NoModes {
            lo,
            hi,
            min_stable: criteria.min_stable,
            max_order: settings.max_order,
        });
    }
    if let Some(requested) = settings.n_modes
        && found < requested
    {
        return Err(ExtractError::TooFewModes {
            requested,
            found,
            min_stable: criteria.min_stable,
            lo,
            hi,
        });
    }
    Ok(())
}

/// Whether refined poles can replace the chart's: each stays stable, in the band, below the
/// damping bound and within the frequency tolerance of its start (in |delta s| / |s|), and no
/// two merge.
fn acceptable(refined: &[c64], start: &[c64], band: (f64, f64), criteria: &Criteria) -> bool {
    let each = refined.iter().zip(start).all(|(r, s)| {
        let f = frequency(*r);
        r.re < 0.0
            && r.im > 0.0
            && f >= band.0
            && f <= band.1
            && -r.re / r.norm() < criteria.max_damping
            && (r - s).norm() < criteria.frequency_tolerance * s.norm()
    });
    let distinct = refined.iter().enumerate().all(|(i, a)| {
        refined[i + 1..]
            .iter()
            .all(|b| (a - b).norm() > 1e-9 * a.norm())
    });
    each && distinct
}
