//! Scans: a family of effects indexed by one coordinate (a position along the beams, the
//! length of a joint region), every member fitted with the joints and the best kept.
//!
//! The coordinate is estimated by its profile likelihood: the deviance of the best fit at each
//! member of the scan, every member under the joint-only fit's error model, minimised over the
//! members; the best member is then fitted again with its own discrepancy (module
//! `discrepancy`), and that is the candidate's fit. The coordinate's standard error is half the
//! width of the set where the deviance <= its minimum + 1 (the profile-likelihood interval of
//! one standard deviation), at least half the step to the neighbouring members, since the
//! scan cannot resolve finer. The best of N members is the largest of N likelihood-ratio
//! statistics: the selection counts a scan as N hypotheses
//! ([`super::Candidate::hypotheses`]), and its information criterion counts the coordinate as
//! one more parameter.

use std::sync::Arc;

use rayon::prelude::*;

use super::effect::fit_effect;
use super::{Candidate, CandidateError, Fit, Stage, Tier};
use crate::diagnose::fit::Estimate;
use crate::diagnose::report::Profile;
use crate::model::effects::{Effect, EffectContext, region_lengths, scan};

/// The members of a scan on a structure: each with its coordinate.
type Members = fn(&EffectContext) -> Vec<(f64, Arc<dyn Effect>)>;

/// A scan candidate (see the module docs).
#[derive(Debug, Clone)]
pub struct Scan {
    name: &'static str,
    tier: Tier,
    describe: &'static str,
    /// Name of the coordinate in reports, and its unit.
    coordinate: (&'static str, &'static str),
    members: Members,
}

/// A region of changed bending stiffness at every joint, its length scanned
/// ([`crate::model::effects::JointRegion`]).
pub fn joint_region() -> Scan {
    Scan {
        name: "joint_region",
        tier: Tier::Extended,
        describe: "bending stiffness EI (1 + d) over a region on both sides of every joint, d > -1 per joint (softer or stiffer than the beams), the region's length (both sides of joint 1, m) scanned on the mesh by its profile likelihood; size = d, the mean over the joints",
        coordinate: ("length", "m"),
        members: |ctx| {
            region_lengths(ctx)
                .into_iter()
                .map(|r| (r.length(ctx), Arc::new(r) as Arc<dyn Effect>))
                .collect()
        },
    }
}

/// A change of the bending stiffness of one beam element, its position scanned
/// ([`crate::model::effects::LocalStiffness`]).
pub fn local_stiffness() -> Scan {
    Scan {
        name: "local_stiffness",
        tier: Tier::Extended,
        describe: "bending stiffness EI (1 + d) of one beam element (a crack, a weld, a corroded stretch), d > -1, its position (the element's middle, m) scanned over every element by its profile likelihood; size = d",
        coordinate: ("x", "m"),
        members: |ctx| {
            scan(ctx)
                .into_iter()
                .map(|e| {
                    let line = &ctx.structure.sites.elements[e.element].line;
                    (
                        0.5 * (line.x[0] + line.x[1]),
                        Arc::new(e) as Arc<dyn Effect>,
                    )
                })
                .collect()
        },
    }
}

impl Scan {
    fn members(&self, ctx: &EffectContext) -> Vec<(f64, Arc<dyn Effect>)> {
        (self.members)(ctx)
            .into_iter()
            .filter(|(_, e)| e.applies(ctx))
            .collect()
    }
}

impl Candidate for Scan {
    fn name(&self) -> &'static str {
        self.name
    }

    fn tier(&self) -> Tier {
        self.tier
    }

    fn describe(&self) -> &'static str {
        self.describe
    }

    fn hypotheses(&self, ctx: &EffectContext) -> usize {
        self.members(ctx).len().max(1)
    }

    fn applies(&self, ctx: &EffectContext) -> bool {
        !self.members(ctx).is_empty()
    }

    /// Every member fitted on `stage` (in parallel) under the joint-only fit's error model;
    /// the best physical one fitted again with its own discrepancy.
    fn fit(&self, stage: &Stage) -> Result<Fit, CandidateError> {
        let members = self.members(stage.ctx);
        let outcomes: Vec<(f64, Result<Fit, CandidateError>)> = members
            .par_iter()
            .map(|(x, e)| (*x, fit_effect(e, stage, false)))
            .collect();
        // The deviance of every member that fitted to a physical size.
        let points: Vec<(f64, Option<f64>)> = outcomes
            .iter()
            .map(|(x, f)| {
                let physical = f.as_ref().ok().filter(|f| f.excluded.is_none());
                (*x, physical.map(|f| f.deviance))
            })
            .collect();
        let mut fitted = Vec::new();
        let mut failure = None;
        for (i, (_, outcome)) in outcomes.into_iter().enumerate() {
            match outcome {
                Ok(fit) => fitted.push((i, fit)),
                Err(e) => {
                    failure.get_or_insert(e);
                }
            }
        }
        let best = (0..fitted.len())
            .filter(|&k| points[fitted[k].0].1.is_some())
            .min_by(|&a, &b| fitted[a].1.deviance.total_cmp(&fitted[b].1.deviance));
        let Some(best) = best else {
            // No physical member: the best of those fitted (excluded, with its reason), or
            // why the members failed.
            let least = fitted
                .into_iter()
                .min_by(|a, b| a.1.deviance.total_cmp(&b.1.deviance));
            return match (least, failure) {
                (Some((_, fit)), _) => Ok(fit),
                (None, Some(e)) => Err(e),
                (None, None) => Err(CandidateError::Undetermined(
                    "the scan has no member".into(),
                )),
            };
        };
        let (best, _) = fitted.swap_remove(best);
        let mut fit = fit_effect(&members[best].1, stage, true)?;
        let profile = profile(self.coordinate, &points, best);
        let (lo, hi) = profile.interval;
        fit.parameters.push(Estimate {
            name: format!("{}.{}", self.name, self.coordinate.0),
            unit: self.coordinate.1,
            value: profile.best,
            se: (0.5 * (hi - lo)).max(half_step(&points, best)),
            limit: None,
        });
        fit.describe = format!(
            "{}; best {} = {:.4} {} of {} scanned",
            self.describe,
            self.coordinate.0,
            profile.best,
            self.coordinate.1,
            points.len()
        );
        fit.profile = Some(profile);
        Ok(fit)
    }
}

/// The profile of `points` (coordinate, deviance) whose minimum is at `best`.
fn profile(
    coordinate: (&str, &'static str),
    points: &[(f64, Option<f64>)],
    best: usize,
) -> Profile {
    let (x_best, chi2_min) = (points[best].0, points[best].1.unwrap_or(f64::INFINITY));
    let within: Vec<f64> = points
        .iter()
        .filter(|(_, c)| c.is_some_and(|c| c <= chi2_min + 1.0))
        .map(|(x, _)| *x)
        .collect();
    let lo = within.iter().copied().fold(x_best, f64::min);
    let hi = within.iter().copied().fold(x_best, f64::max);
    Profile {
        coordinate: coordinate.0.to_string(),
        unit: coordinate.1,
        points: points.to_vec(),
        best: x_best,
        interval: (lo, hi),
    }
}

/// Half the distance from member `best` to its nearest neighbour in coordinate (0 for a scan
/// of one member: its coordinate is given, not estimated).
fn half_step(points: &[(f64, Option<f64>)], best: usize) -> f64 {
    let x = points[best].0;
    let nearest = points
        .iter()
        .enumerate()
        .filter(|&(i, _)| i != best)
        .map(|(_, (y, _))| (y - x).abs())
        .filter(|d| *d > 0.0)
        .fold(f64::INFINITY, f64::min);
    if nearest.is_finite() {
        0.5 * nearest
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// chi^2 along a coordinate: the interval is where chi^2 <= min + 1, the step the nearest
    /// neighbour's half distance; failed members do not count.
    #[test]
    fn the_profile_interval_and_the_step() {
        let points = [
            (0.01, Some(50.0)),
            (0.02, Some(20.5)),
            (0.03, Some(20.0)),
            (0.045, None),
            (0.06, Some(20.9)),
            (0.08, Some(40.0)),
        ];
        let p = profile(("length", "m"), &points, 2);
        assert_eq!(p.best, 0.03);
        assert_eq!(p.interval, (0.02, 0.06));
        assert!((half_step(&points, 2) - 0.005).abs() < 1e-15);
        assert!((half_step(&points, 5) - 0.01).abs() < 1e-15);
        assert_eq!(half_step(&points[..1], 0), 0.0);
    }
}
