//! Levenberg-Marquardt for nonlinear least squares, min cost(x) = |r(x)|^2, within the linear
//! inequalities of module [`super::bounds`], behind a problem trait (argmin's split of
//! problem, solver and observer: the problem evaluates and linearises, the solver iterates,
//! an observer watches).
//!
//! One iteration, from the accepted point x with damping mu (starting at [`MU_START`]):
//! 1. the problem linearises at x ([`Problem::linearise`]): residual and Jacobian, or their
//!    QR-compressed triangle; the constraints active at x fix the null space the step stays in
//!    (module [`super::step`]);
//! 2. with a decrement tolerance set: converged ([`Termination::Decrement`]) when a full
//!    Gauss-Newton step would lower the cost by less than tolerance * max(cost, 1);
//! 3. trial steps s(mu) (QR with Marquardt's column scaling), x + s projected back onto the
//!    feasible side: a trial that cannot be projected, that the problem finds inadmissible
//!    ([`Problem::admissible`]) or cannot evaluate ([`Problem::evaluate`] fails) is a step too
//!    long, mu x [`GROW_REFUSED`]; a trial whose cost is not lower than the current (or not a
//!    number), mu x [`GROW_REJECTED`]; an accepted trial becomes x and mu / [`SHRINK`], or
//!    mu / [`SHRINK_AGREEING`] when its cost fell by at least [`AGREEING`] of the fall the
//!    linearised problem predicted (where the linearisation holds, damping only shortens
//!    the steps; MINPACK's trust region doubles after such a step), not below [`MU_MIN`].
//!    A trial of equal cost is refused: where the evaluations' round-off is all that is left,
//!    steps of vanishing length and equal cost could otherwise be taken until the iteration
//!    limit (seen in a calibration, which then failed at its minimum);
//! 4. no trial accepted before mu reaches [`MU_MAX`], or, with a decrement tolerance set,
//!    before the linearised problem predicts less than that tolerance's fall for the next
//!    trial (after a failed one: such a step is not worth an evaluation): no step lowers the
//!    cost, x is a minimum (inside, on a bound, or at the edge of the evaluable region:
//!    [`Termination::NoDescent`]);
//! 5. with a gain tolerance set: converged ([`Termination::SmallGain`]) when the accepted step
//!    lowered the cost by less than tolerance * cost;
//! 6. after the last allowed iteration: [`Termination::MaxIterations`] (not converged).
//!
//! Settings ([`LevenbergMarquardt`]): the iteration limit (at least 1), the decrement and gain
//! tolerances (each off unless set; within (0, 1)) and the starting damping (default
//! [`MU_START`], within [`MU_MIN`]..[`MU_MAX`]).
//!
//! Imports: faer and the modules of `optim`; nothing else of the crate.

use super::bounds::Bounds;
pub use super::step::Linearisation;
use super::step::Subproblem;

/// Starting damping (default).
pub const MU_START: f64 = 1e-3;
/// Smallest damping after an accepted step.
pub const MU_MIN: f64 = 1e-12;
/// Damping at which the search for a lower cost gives up.
pub const MU_MAX: f64 = 1e12;
/// Division of mu after an accepted step.
pub const SHRINK: f64 = 3.0;
/// Division of mu after an accepted step whose cost fell by at least [`AGREEING`] of what the
/// linearised problem predicted.
pub const SHRINK_AGREEING: f64 = 10.0;
/// The ratio of actual to predicted fall above which the linearisation agrees.
pub const AGREEING: f64 = 0.75;
/// Multiplication of mu after a trial whose cost is too high.
pub const GROW_REJECTED: f64 = 4.0;
/// Multiplication of mu after a trial that could not be projected, was inadmissible or could
/// not be evaluated.
pub const GROW_REFUSED: f64 = 10.0;

/// A nonlinear least-squares problem: cost(x) = |r(x)|^2 over unknowns x.
pub trait Problem {
    /// An evaluated point: its cost and what the linearisation needs.
    type State;
    /// Why a point cannot be evaluated. At the starting point it ends the solve; at a trial
    /// point it makes the step too long.
    type Error;

    /// Evaluates the point x.
    fn evaluate(&self, x: &[f64]) -> Result<Self::State, Self::Error>;

    /// The cost |r|^2 of an evaluated point.
    fn cost(&self, state: &Self::State) -> f64;

    /// The linearisation at an accepted point x of state `state`.
    fn linearise(&self, x: &[f64], state: &Self::State) -> Linearisation;

    /// The feasible region (default: everywhere).
    fn bounds(&self) -> Bounds {
        Bounds::default()
    }

    /// Whether a feasible trial point may be evaluated at all (default: always).
    fn admissible(&self, _x: &[f64]) -> bool {
        true
    }
}

/// Why the iteration stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum Termination {
    /// Converged: a full Gauss-Newton step would remove less than the decrement tolerance
    /// times max(cost, 1).
    Decrement,
    /// Converged: the last accepted step removed less than the gain tolerance times the cost.
    SmallGain,
    /// No step lowers the cost, whatever its damping: a minimum, possibly on a bound or at the
    /// edge of the region where the problem can be evaluated.
    NoDescent,
    /// The iteration limit came first: not converged.
    MaxIterations,
}

impl Termination {
    /// Whether the iteration ended at a minimum (every reason but the iteration limit).
    pub fn converged(self) -> bool {
        match self {
            Termination::Decrement | Termination::SmallGain | Termination::NoDescent => true,
            Termination::MaxIterations => false,
        }
    }
}

/// The outcome of a solve.
#[derive(Debug, Clone)]
pub struct Solution<S> {
    /// The last accepted point.
    pub x: Vec<f64>,
    /// Its state.
    pub state: S,
    /// Its cost.
    pub cost: f64,
    /// The cost at the start.
    pub start_cost: f64,
    /// Iterations begun (linearisations made).
    pub iterations: usize,
    /// Steps accepted.
    pub accepted: usize,
    /// Why the iteration stopped.
    pub termination: Termination,
}

/// What an observer sees at the end of every iteration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// The iteration, from 1.
    pub iteration: usize,
    /// The cost after it.
    pub cost: f64,
    /// The damping of its last trial (of the accepted one if any; the current damping when
    /// the iteration converged before any trial).
    pub mu: f64,
    /// Whether it accepted a step.
    pub accepted: bool,
    /// Trial points it tried.
    pub trials: usize,
}

/// Watches the iteration (for progress and logs); the default does nothing.
pub trait Observer {
    /// Called at the end of every iteration, the last included.
    fn observe(&mut self, _progress: &Progress) {}
}

/// The observer that does nothing.
#[derive(Debug, Clone, Copy, Default)]
pub struct Silent;

impl Observer for Silent {}

/// A setting out of its range.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("Levenberg-Marquardt setting {name} = {value:e} is invalid: it must be {allowed}")]
pub struct SettingError {
    /// The setting.
    pub name: &'static str,
    /// The value refused.
    pub value: f64,
    /// What is allowed.
    pub allowed: &'static str,
}

/// The solver and its settings (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LevenbergMarquardt {
    max_iterations: usize,
    decrement: Option<f64>,
    gain: Option<f64>,
    mu_start: f64,
}

/// The outcome of one iteration's search for an acceptable trial.
struct Search<S> {
    /// The accepted point, its state and its cost.
    step: Option<(Vec<f64>, S, f64)>,
    /// The damping of the last trial.
    mu: f64,
    /// Trials made.
    trials: usize,
}

fn tolerance(name: &'static str, value: f64) -> Result<f64, SettingError> {
    if value > 0.0 && value < 1.0 {
        Ok(value)
    } else {
        Err(SettingError {
            name,
            value,
            allowed: "within (0, 1)",
        })
    }
}

impl LevenbergMarquardt {
    /// At most `max_iterations` iterations (at least 1), no convergence test (set one with
    /// [`Self::with_decrement`] or [`Self::with_gain`]), damping from [`MU_START`].
    pub fn new(max_iterations: usize) -> Result<Self, SettingError> {
        if max_iterations == 0 {
            return Err(SettingError {
                name: "max_iterations",
                value: 0.0,
                allowed: "at least 1",
            });
        }
        Ok(Self {
            max_iterations,
            decrement: None,
            gain: None,
            mu_start: MU_START,
        })
    }

    /// Converged when a full Gauss-Newton step would remove less than `tolerance` *
    /// max(cost, 1), tolerance within (0, 1).
    pub fn with_decrement(mut self, tolerance: f64) -> Result<Self, SettingError> {
        self.decrement = Some(self::tolerance("decrement tolerance", tolerance)?);
        Ok(self)
    }

    /// Converged when an accepted step removes less than `tolerance` * cost, tolerance within
    /// (0, 1).
    pub fn with_gain(mut self, tolerance: f64) -> Result<Self, SettingError> {
        self.gain = Some(self::tolerance("gain tolerance", tolerance)?);
        Ok(self)
    }

    /// The starting damping, within [`MU_MIN`]..[`MU_MAX`] (a tiny one makes the first step
    /// Gauss-Newton's).
    pub fn with_start_damping(mut self, mu: f64) -> Result<Self, SettingError> {
        if !(MU_MIN..MU_MAX).contains(&mu) {
            return Err(SettingError {
                name: "start damping",
                value: mu,
                allowed: "within [1e-12, 1e12)",
            });
        }
        self.mu_start = mu;
        Ok(self)
    }

    /// Minimises `problem` from x (module docs). Fails only when x cannot be evaluated.
    pub fn minimise<P: Problem>(
        &self,
        problem: &P,
        x: Vec<f64>,
    ) -> Result<Solution<P::State>, P::Error> {
        self.minimise_observed(problem, x, &mut Silent)
    }

    /// As [`Self::minimise`], `observer` called at the end of every iteration.
    pub fn minimise_observed<P: Problem, O: Observer + ?Sized>(
        &self,
        problem: &P,
        mut x: Vec<f64>,
        observer: &mut O,
    ) -> Result<Solution<P::State>, P::Error> {
        let mut state = problem.evaluate(&x)?;
        let mut cost = problem.cost(&state);
        let start_cost = cost;
        let bounds = problem.bounds();
        let mut mu = self.mu_start;
        let (mut iterations, mut accepted) = (0, 0);
        let mut termination = Termination::MaxIterations;
        for iteration in 1..=self.max_iterations {
            iterations = iteration;
            let sub = Subproblem::new(problem.linearise(&x, &state), &bounds, &x);
            if let Some(tolerance) = self.decrement
                && sub.decrement() < tolerance * cost.max(1.0)
            {
                observer.observe(&Progress {
                    iteration,
                    cost,
                    mu,
                    accepted: false,
                    trials: 0,
                });
                termination = Termination::Decrement;
                break;
            }
            let search = self.search(problem, &sub, &bounds, &x, cost, &mut mu);

            let gain = search
                .step
                .as_ref()
                .map(|(_, _, value)| (cost - value) / cost.max(f64::MIN_POSITIVE));
            if let Some((trial, candidate, value)) = search.step {
                x = trial;
                state = candidate;
                cost = value;
                accepted += 1;
            }
            observer.observe(&Progress {
                iteration,
                cost,
                mu: search.mu,
                accepted: gain.is_some(),
                trials: search.trials,
            });
            let Some(gain) = gain else {
                termination = Termination::NoDescent;
                break;
            };
            if let Some(tolerance) = self.gain
                && gain < tolerance
            {
                termination = Termination::SmallGain;
                break;
            }
        }
        Ok(Solution {
            x,
            state,
            cost,
            start_cost,
            iterations,
            accepted,
            termination,
        })
    }

    /// Trial steps of growing damping until one is accepted or mu reaches [`MU_MAX`]
    /// (module docs, step 3).
    fn search<P: Problem>(
        &self,
        problem: &P,
        sub: &Subproblem,
        bounds: &Bounds,
        x: &[f64],
        cost: f64,
        mu: &mut f64,
    ) -> Search<P::State> {
        let mut search = Search {
            step: None,
            mu: *mu,
            trials: 0,
        };
        while *mu < MU_MAX {
            let s = sub.step(*mu);
            // After a failed trial, a step that could not remove the decrement tolerance is
            // not worth an evaluation: no step worth trying lowers the cost.
            if let Some(tolerance) = self.decrement
                && search.trials > 0
                && sub.predicted(&s) < tolerance * cost.max(1.0)
            {
                break;
            }
            search.trials += 1;
            search.mu = *mu;
            let trial = x.iter().zip(&s).map(|(a, b)| a + b).collect();
            let Some(trial) = bounds.project(trial) else {
                *mu *= GROW_REFUSED;
                continue;
            };
            if !problem.admissible(&trial) {
                *mu *= GROW_REFUSED;
                continue;
            }
            let Ok(candidate) = problem.evaluate(&trial) else {
                *mu *= GROW_REFUSED;
                continue;
            };
            let value = problem.cost(&candidate);
            if value < cost {
                let agrees = cost - value >= AGREEING * sub.predicted(&s);
                let shrink = if agrees { SHRINK_AGREEING } else { SHRINK };
                *mu = (*mu / shrink).max(MU_MIN);
                search.step = Some((trial, candidate, value));
                return search;
            }
            *mu *= GROW_REJECTED;
        }
        search
    }
}

#[cfg(test)]
mod tests;
