//! The solver on problems with known answers: Rosenbrock's valley as least squares, NIST's
//! certified Misra1a exponential fit, a linear problem, optima on a coordinate bound and on a
//! slanted face, a region where the problem cannot be evaluated; every termination reason, the
//! observer and the settings' ranges.

use std::cell::Cell;

use faer::Mat;

use super::*;
use crate::optim::lstsq;

/// Which hook refuses the points outside a problem's domain.
#[derive(Clone, Copy)]
enum Refusal {
    /// `Problem::evaluate` fails there.
    Evaluate,
    /// `Problem::admissible` is false there.
    Admissible,
}

/// A problem given by functions: r(x), its Jacobian (rows), bounds, and a domain outside which
/// the refusing hook says no (counted).
struct Given {
    residual: fn(&[f64]) -> Vec<f64>,
    jacobian: fn(&[f64]) -> Vec<Vec<f64>>,
    bounds: Bounds,
    domain: fn(&[f64]) -> bool,
    refusal: Refusal,
    refused: Cell<usize>,
}

impl Given {
    fn new(residual: fn(&[f64]) -> Vec<f64>, jacobian: fn(&[f64]) -> Vec<Vec<f64>>) -> Self {
        Given {
            residual,
            jacobian,
            bounds: Bounds::default(),
            domain: |_| true,
            refusal: Refusal::Evaluate,
            refused: Cell::new(0),
        }
    }

    fn inside(&self, x: &[f64]) -> bool {
        let inside = (self.domain)(x);
        if !inside {
            self.refused.set(self.refused.get() + 1);
        }
        inside
    }
}

impl Problem for Given {
    type State = Vec<f64>;
    type Error = &'static str;

    fn evaluate(&self, x: &[f64]) -> Result<Vec<f64>, &'static str> {
        match self.refusal {
            Refusal::Evaluate if !self.inside(x) => Err("outside the domain"),
            Refusal::Evaluate | Refusal::Admissible => Ok((self.residual)(x)),
        }
    }

    fn cost(&self, state: &Vec<f64>) -> f64 {
        state.iter().map(|r| r * r).sum()
    }

    fn linearise(&self, x: &[f64], state: &Vec<f64>) -> Linearisation {
        let rows = (self.jacobian)(x);
        Linearisation::Jacobian {
            residual: state.clone(),
            jacobian: Mat::from_fn(rows.len(), x.len(), |i, j| rows[i][j]),
        }
    }

    fn bounds(&self) -> Bounds {
        self.bounds.clone()
    }

    fn admissible(&self, x: &[f64]) -> bool {
        match self.refusal {
            Refusal::Admissible => self.inside(x),
            Refusal::Evaluate => true,
        }
    }
}

/// Records every progress report.
#[derive(Default)]
struct Log(Vec<Progress>);

impl Observer for Log {
    fn observe(&mut self, progress: &Progress) {
        self.0.push(*progress);
    }
}

/// Rosenbrock's function as least squares: r = (10 (x1 - x0^2), 1 - x0), minimum 0 at (1, 1).
fn rosenbrock() -> Given {
    Given::new(
        |x| vec![10.0 * (x[1] - x[0] * x[0]), 1.0 - x[0]],
        |x| vec![vec![-20.0 * x[0], 10.0], vec![-1.0, 0.0]],
    )
}

/// The calibration's settings: decrement 1e-8, 200 iterations.
fn by_decrement(max_iterations: usize) -> LevenbergMarquardt {
    LevenbergMarquardt::new(max_iterations)
        .unwrap()
        .with_decrement(1e-8)
        .unwrap()
}

/// The extraction's settings: gain 1e-12, 50 iterations.
fn by_gain() -> LevenbergMarquardt {
    LevenbergMarquardt::new(50)
        .unwrap()
        .with_gain(1e-12)
        .unwrap()
}

/// From the classical start (-1.2, 1) down the curved valley to (1, 1); the observer sees every
/// iteration, in order, with the costs it reports never rising.
#[test]
fn rosenbrock_reaches_the_minimum_and_the_observer_sees_every_iteration() {
    let problem = rosenbrock();
    let mut log = Log::default();
    let solution = by_decrement(200)
        .minimise_observed(&problem, vec![-1.2, 1.0], &mut log)
        .unwrap();
    assert_eq!(solution.termination, Termination::Decrement);
    assert!(solution.termination.converged());
    // Zero residual at the minimum: the decrement is about the cost itself, below 1e-8, so
    // |1 - x0| = |r_1| < 1e-4 and |x1 - x0^2| < 1e-5.
    assert!(solution.cost < 1e-8, "{}", solution.cost);
    assert!((solution.x[0] - 1.0).abs() < 1e-4, "{:?}", solution.x);
    assert!(
        (solution.x[1] - solution.x[0].powi(2)).abs() < 1e-5,
        "{:?}",
        solution.x
    );
    assert!(
        (solution.start_cost - 24.2).abs() < 1e-13,
        "{}",
        solution.start_cost
    );
    // With the gain test it goes on to the exact minimum, where no step lowers the cost.
    let tight = by_gain().minimise(&problem, vec![-1.2, 1.0]).unwrap();
    assert_eq!(tight.termination, Termination::NoDescent);
    assert!(
        tight.x.iter().all(|x| (x - 1.0).abs() < 1e-14),
        "{:?}",
        tight.x
    );
    let iterations: Vec<usize> = log.0.iter().map(|p| p.iteration).collect();
    assert_eq!(iterations, (1..=solution.iterations).collect::<Vec<_>>());
    let accepted = log.0.iter().filter(|p| p.accepted).count();
    assert_eq!(accepted, solution.accepted);
    assert!(log.0.windows(2).all(|w| w[1].cost <= w[0].cost));
    let last = log.0.last().unwrap();
    assert_eq!(
        (last.cost, last.accepted, last.trials),
        (solution.cost, false, 0)
    );
    // The first trial, at the starting damping, raises the cost; the second, damped 4 times
    // more, is taken.
    assert_eq!(
        (log.0[0].trials, log.0[0].mu),
        (2, MU_START * GROW_REJECTED)
    );
}

const MISRA_X: [f64; 14] = [
    77.6, 114.9, 141.1, 190.8, 239.9, 289.0, 332.8, 378.4, 434.8, 477.3, 536.8, 593.1, 689.1, 760.0,
];
const MISRA_Y: [f64; 14] = [
    10.07, 14.73, 17.94, 23.93, 29.61, 35.18, 40.02, 44.82, 50.76, 55.05, 61.01, 66.40, 75.47,
    81.78,
];

/// NIST StRD nonlinear regression "Misra1a" (Misra, dental research monomolecular adsorption,
/// 1978): y = b1 (1 - exp(-b2 x)), 14 observations. Certified (NIST ITL, "Statistical Reference
/// Datasets", https://www.itl.nist.gov/div898/strd/nls/data/misra1a.shtml):
/// b1 = 2.3894212918E+02 (sd 2.7070075241E+00), b2 = 5.5015643181E-04 (sd 7.2668688436E-06),
/// residual sum of squares 1.2455138894E-01. The unknowns differ by six orders of magnitude:
/// Marquardt's column scaling has to carry the step.
fn misra1a() -> Given {
    Given::new(
        |b| {
            MISRA_X
                .iter()
                .zip(MISRA_Y)
                .map(|(x, y)| b[0] * (1.0 - (-b[1] * x).exp()) - y)
                .collect()
        },
        |b| {
            MISRA_X
                .iter()
                .map(|x| vec![1.0 - (-b[1] * x).exp(), b[0] * x * (-b[1] * x).exp()])
                .collect()
        },
    )
}

/// Both of NIST's starts, with either convergence test, reach the certified optimum; the
/// covariance of [`lstsq::inverse_gram`] gives the certified standard deviations.
#[test]
fn misra1a_reaches_the_certified_values() {
    let problem = misra1a();
    let certified = [2.3894212918e2, 5.5015643181e-4];
    let sd = [2.7070075241, 7.2668688436e-6];
    // With the decrement test (1e-8 absolute, the cost being below 1) the cost is within
    // 1e-8 of the minimum: the unknowns within sqrt(1e-8 / s^2) = 1e-3 of their standard
    // deviations (s^2 = cost / 12), b1 to 1.2e-5 relative, b2 to 1.4e-5. With the gain test
    // the iteration goes on until the steps gain nothing: to the certified digits.
    // The certified sum of squares has 11 digits: within 5e-12 of the minimum.
    for start in [[500.0, 1e-4], [250.0, 5e-4]] {
        for (solver, reason, tolerance, cost_tolerance) in [
            (by_decrement(200), Termination::Decrement, 2e-5, 1e-8),
            (by_gain(), Termination::SmallGain, 1e-9, 1e-11),
        ] {
            let solution = solver.minimise(&problem, start.to_vec()).unwrap();
            assert_eq!(solution.termination, reason, "{start:?}");
            for (k, (b, c)) in solution.x.iter().zip(certified).enumerate() {
                let relative = (b - c) / c;
                assert!(
                    relative.abs() < tolerance,
                    "{start:?} b{}: {relative:e}",
                    k + 1
                );
            }
            let rss = solution.cost - 1.2455138894e-1;
            assert!(rss.abs() < cost_tolerance, "{start:?}: {rss:e}");
            let Linearisation::Jacobian { jacobian, .. } =
                problem.linearise(&solution.x, &solution.state)
            else {
                unreachable!("the problem gives Jacobians")
            };
            let covariance = lstsq::inverse_gram(jacobian.as_ref()).unwrap();
            let variance = solution.cost / 12.0;
            for (k, s) in sd.iter().enumerate() {
                let se = (variance * covariance[(k, k)]).sqrt();
                assert!((se - s).abs() < tolerance * s, "sd b{}: {se:e}", k + 1);
            }
        }
    }
}

/// A linear problem, r = A x - b: with a negligible starting damping the first step is the
/// least-squares solution, and the next iteration finds nothing left to remove.
#[test]
fn a_linear_problem_is_solved_in_one_step() {
    // A = [[1, 1], [1, 2], [1, 3], [1, 4]], b = (6, 5, 7, 10): the least-squares line
    // through (1, 6), (2, 5), (3, 7), (4, 10) is 3.5 + 1.4 t.
    let problem = Given::new(
        |x| {
            [6.0, 5.0, 7.0, 10.0]
                .iter()
                .enumerate()
                .map(|(i, b)| x[0] + x[1] * (i + 1) as f64 - b)
                .collect()
        },
        |_| (1..=4).map(|t| vec![1.0, t as f64]).collect(),
    );
    let solver = by_decrement(200).with_start_damping(MU_MIN).unwrap();
    let solution = solver.minimise(&problem, vec![0.0, 0.0]).unwrap();
    assert_eq!(solution.accepted, 1);
    assert_eq!(solution.iterations, 2);
    assert_eq!(solution.termination, Termination::Decrement);
    assert!((solution.x[0] - 3.5).abs() < 1e-10 && (solution.x[1] - 1.4).abs() < 1e-10);
    // The residual sum of squares of that line: 1.1^2 + 1.3^2 + 1.1^2 + 0.9^2 = 4.2.
    assert!((solution.cost - 4.2).abs() < 1e-10, "{}", solution.cost);
}

/// A linear problem with nearly dependent columns from the default damping: the
/// linearisation is exact, every step removes what it predicted, and mu falls by
/// [`SHRINK_AGREEING`] after each until the damping no longer holds back the weak direction.
#[test]
fn where_the_linearisation_agrees_the_damping_falls_fast() {
    // A = [[1, 1], [1, 1.001], [1, 1.002], [1, 1.003]]: cond(A) about 1.8e3, and Marquardt's
    // damping of 1e-3 holds back its weak direction.
    let problem = Given::new(
        |x| {
            [1.0, 2.0, 2.5, 4.0]
                .iter()
                .enumerate()
                .map(|(i, b)| x[0] + x[1] * (1.0 + 1e-3 * i as f64) - b)
                .collect()
        },
        |_| (0..4).map(|i| vec![1.0, 1.0 + 1e-3 * i as f64]).collect(),
    );
    let mut log = Log::default();
    let solution = by_decrement(200)
        .minimise_observed(&problem, vec![0.0, 0.0], &mut log)
        .unwrap();
    assert_eq!(solution.termination, Termination::Decrement);
    let steps: Vec<&Progress> = log.0.iter().filter(|p| p.accepted).collect();
    assert!(steps.len() >= 3, "{} steps", steps.len());
    for pair in steps.windows(2) {
        let ratio = pair[0].mu / pair[1].mu;
        assert!(
            (ratio / SHRINK_AGREEING - 1.0).abs() < 1e-12,
            "mu fell by {ratio}"
        );
    }
    // Seven steps; twelve when mu fell by SHRINK = 3 after each.
    assert!(steps.len() <= 8, "{} steps", steps.len());
    // The least-squares line through (1 + 1e-3 i, b_i) leaves (-0.05, -0.1, 0.35, -0.2):
    // cost 0.175, reached to within the decrement tolerance (1e-8 of max(cost, 1)).
    let excess = solution.cost - 0.175;
    assert!((-1e-12..1e-8).contains(&excess), "{}", solution.cost);
}

/// r = (x0 + 1, x1 - 2) with x0 >= 0: the free minimum (-1, 2) is outside; the solver stops
/// on the bound, x0 exactly 0, and converges along it.
#[test]
fn an_optimum_on_a_coordinate_bound() {
    let mut problem = Given::new(
        |x| vec![x[0] + 1.0, x[1] - 2.0],
        |_| vec![vec![1.0, 0.0], vec![0.0, 1.0]],
    );
    problem.bounds = Bounds::new(vec![vec![(0, 1.0)]]);
    let solution = by_decrement(200)
        .minimise(&problem, vec![1.0, 0.0])
        .unwrap();
    assert_eq!(solution.termination, Termination::Decrement);
    assert_eq!(solution.x[0], 0.0);
    assert!((solution.x[1] - 2.0).abs() < 1e-6, "{:?}", solution.x);
    assert!((solution.cost - 1.0).abs() < 1e-10, "{}", solution.cost);
}

/// r = (m - 1, J - 5) in the cone m >= 0, J >= 0, 4 m - J >= 0: the free minimum (1, 5) lies
/// beyond the face 4 m = J; the constrained one is its orthogonal projection (21, 84) / 17.
#[test]
fn an_optimum_on_a_slanted_face() {
    let mut problem = Given::new(
        |x| vec![x[0] - 1.0, x[1] - 5.0],
        |_| vec![vec![1.0, 0.0], vec![0.0, 1.0]],
    );
    problem.bounds = Bounds::new(vec![
        vec![(0, 1.0)],
        vec![(1, 1.0)],
        vec![(0, 4.0), (1, -1.0)],
    ]);
    for solver in [by_decrement(200), by_gain()] {
        let solution = solver.minimise(&problem, vec![1.0, 1.0]).unwrap();
        assert!(
            solution.termination.converged(),
            "{:?}",
            solution.termination
        );
        assert!(
            (4.0 * solution.x[0] - solution.x[1]).abs() < 1e-12,
            "{:?}",
            solution.x
        );
        assert!(
            (solution.x[0] - 21.0 / 17.0).abs() < 1e-6,
            "{:?}",
            solution.x
        );
        // The distance squared from (1, 5) to the face: (4 - 5)^2 / 17.
        assert!(
            (solution.cost - 1.0 / 17.0).abs() < 1e-10,
            "{}",
            solution.cost
        );
    }
}

/// r = x^2 - 2 from x = 0.5, where the problem can be evaluated only up to x = 2: the first
/// three trials (2.25, 2.23, 2.09) are steps too long, refused with mu x 10 each, the fourth
/// (mu = 1) is taken; then on to sqrt(2). An inadmissible point is handled alike.
#[test]
fn a_region_that_cannot_be_evaluated_makes_steps_too_long() {
    let mut runs = Vec::new();
    for refusal in [Refusal::Evaluate, Refusal::Admissible] {
        let mut problem = Given::new(|x| vec![x[0] * x[0] - 2.0], |x| vec![vec![2.0 * x[0]]]);
        problem.domain = |x| x[0] <= 2.0;
        problem.refusal = refusal;
        let mut log = Log::default();
        let solution = by_gain()
            .minimise_observed(&problem, vec![0.5], &mut log)
            .unwrap();
        assert!(
            solution.termination.converged(),
            "{:?}",
            solution.termination
        );
        assert!(
            (solution.x[0] - 2.0_f64.sqrt()).abs() < 1e-14,
            "{:?}",
            solution.x
        );
        assert_eq!(problem.refused.get(), 3);
        let first = log.0[0];
        assert_eq!((first.trials, first.accepted), (4, true));
        assert!((first.mu - 1.0).abs() < 1e-12, "{}", first.mu);
        runs.push((solution.x, log.0));
    }
    assert_eq!(runs[0], runs[1]);
}

/// At the exact minimum no step lowers the cost: the damping grows from 1e-3 by 4 until it
/// reaches 1e12 (25 trials) and the solver reports no descent, x unchanged.
#[test]
fn at_the_minimum_no_step_descends() {
    let problem = Given::new(
        |x| vec![x[0] - 1.0, 2.0 * x[0] - 2.0],
        |_| vec![vec![1.0], vec![2.0]],
    );
    let mut log = Log::default();
    let solution = by_gain()
        .minimise_observed(&problem, vec![1.0], &mut log)
        .unwrap();
    assert_eq!(solution.termination, Termination::NoDescent);
    assert!(solution.termination.converged());
    assert_eq!((solution.iterations, solution.accepted), (1, 0));
    assert_eq!(solution.x, [1.0]);
    assert_eq!(log.0.len(), 1);
    assert_eq!((log.0[0].trials, log.0[0].accepted), (25, false));
}

/// A cost that no step changes though its linearisation promises a full decrement (the
/// evaluations' round-off, or a Jacobian that disagrees with them): every trial has the same
/// cost, is refused, and the solver ends with no descent at once instead of taking steps of
/// equal cost until its iteration limit.
#[test]
fn steps_of_equal_cost_are_refused() {
    let problem = Given::new(|_| vec![1.0], |_| vec![vec![1.0]]);
    let solution = by_decrement(200).minimise(&problem, vec![0.0]).unwrap();
    assert_eq!(solution.termination, Termination::NoDescent);
    assert_eq!((solution.iterations, solution.accepted), (1, 0));
    assert_eq!(solution.x, [0.0]);
}

/// A cost that rises along the step its Jacobian promises (r = 1e-3 + |x|, J = 1 at x = 0):
/// with a decrement tolerance the trials stop once the next one could not remove that
/// tolerance's fall (1 - (mu / (1 + mu))^2 < 1e-2: mu past 198, 9 trials from 1e-3, not the 25
/// up to [`MU_MAX`]), x unchanged.
#[test]
fn trials_stop_where_no_step_could_remove_the_tolerance() {
    let problem = Given::new(|x| vec![1e-3 + x[0].abs()], |_| vec![vec![1.0]]);
    let mut log = Log::default();
    let solution = by_decrement(200)
        .minimise_observed(&problem, vec![0.0], &mut log)
        .unwrap();
    assert_eq!(solution.termination, Termination::NoDescent);
    assert_eq!(solution.x, [0.0]);
    assert_eq!((log.0[0].trials, log.0[0].accepted), (9, false));
}

/// Three iterations are not enough for Rosenbrock's valley.
#[test]
fn the_iteration_limit_is_reported() {
    let solution = by_decrement(3)
        .minimise(&rosenbrock(), vec![-1.2, 1.0])
        .unwrap();
    assert_eq!(solution.termination, Termination::MaxIterations);
    assert!(!solution.termination.converged());
    assert_eq!(solution.iterations, 3);
    assert!(solution.cost < solution.start_cost);
}

/// A starting point that cannot be evaluated ends the solve with the problem's error.
#[test]
fn an_unevaluable_start_is_the_problems_error() {
    let mut problem = rosenbrock();
    problem.domain = |x| x[0] > 0.0;
    let error = by_gain().minimise(&problem, vec![-1.2, 1.0]).unwrap_err();
    assert_eq!(error, "outside the domain");
}

#[test]
fn settings_out_of_range_are_refused_with_the_range() {
    assert_eq!(
        LevenbergMarquardt::new(0).unwrap_err().to_string(),
        "Levenberg-Marquardt setting max_iterations = 0e0 is invalid: it must be at least 1"
    );
    let solver = LevenbergMarquardt::new(10).unwrap();
    assert_eq!(
        solver.with_gain(1.0).unwrap_err().to_string(),
        "Levenberg-Marquardt setting gain tolerance = 1e0 is invalid: it must be within (0, 1)"
    );
    assert!(solver.with_decrement(0.0).is_err());
    assert!(solver.with_decrement(f64::NAN).is_err());
    assert!(solver.with_start_damping(0.0).is_err());
    assert!(solver.with_start_damping(MU_MAX).is_err());
    assert!(solver.with_decrement(1e-8).is_ok());
}
