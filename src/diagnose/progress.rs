//! What a running diagnosis tells a watcher, step by step: the command line's log of a long
//! run (a diagnosis of a solid model of 2e5 DOFs takes hours). Plain data; the watcher
//! formats it.
//!
//! Every step is told from the thread that made it: candidates are fitted in parallel, so a
//! watcher is `Sync` and sees the steps of one pass in the order they finished.

use std::fmt;

use super::noise::NoiseEstimate;

/// The step of the diagnosis a step belongs to (module docs of [`super`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pass {
    /// The joint calibrated.
    Calibration,
    /// Every candidate fitted alone.
    Candidates,
    /// Causes put together: the model of this many causes.
    Together(usize),
}

/// One finished step.
#[derive(Debug, Clone)]
pub enum Step<'a> {
    /// The joint calibrated on every measured mode.
    Calibrated {
        /// chi^2 after the calibration.
        chi2: f64,
        /// Its iterations.
        iterations: usize,
    },
    /// An iteration of a candidate's fit (on a solid of 2e5 DOFs one takes minutes).
    Iteration {
        /// The candidate.
        candidate: &'a str,
        /// Which of its fits, for a candidate that fits more than one.
        variant: Option<&'a str>,
        /// The iteration, from 1.
        iteration: usize,
        /// chi^2 after it.
        chi2: f64,
    },
    /// A candidate fitted.
    Fitted {
        /// The candidate.
        candidate: &'a str,
        /// Its deviance, or why it has none.
        outcome: Result<f64, &'a (dyn std::error::Error + Send + Sync)>,
    },
    /// The yardstick of adequacy chosen: estimated, the stated noise kept, or the data's own
    /// standard errors.
    Noise(&'a NoiseEstimate),
}

/// Where the steps of a diagnosis go, and the pass they belong to.
#[derive(Clone, Copy)]
pub struct Watch<'a> {
    tell: &'a (dyn Fn(Pass, &Step) + Sync),
    pass: Pass,
}

impl<'a> Watch<'a> {
    /// Every step told to `tell`, from the first pass on.
    pub fn new(tell: &'a (dyn Fn(Pass, &Step) + Sync)) -> Self {
        Watch {
            tell,
            pass: Pass::Calibration,
        }
    }

    /// A watch that is told nothing.
    pub fn silent() -> Watch<'static> {
        Watch::new(&|_, _| {})
    }

    /// The same watch in pass `pass`.
    pub fn during(self, pass: Pass) -> Self {
        Watch { pass, ..self }
    }

    /// Tells `step`.
    pub fn tell(&self, step: &Step) {
        (self.tell)(self.pass, step);
    }
}

impl fmt::Debug for Watch<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Watch").field("pass", &self.pass).finish()
    }
}

/// An observer of a candidate's Levenberg-Marquardt iterations that tells each one.
pub struct Iterations<'a> {
    /// Where they go.
    pub watch: Watch<'a>,
    /// The candidate.
    pub candidate: &'a str,
    /// Its variant, if it has more than one.
    pub variant: Option<&'a str>,
}

impl crate::optim::Observer for Iterations<'_> {
    fn observe(&mut self, progress: &crate::optim::Progress) {
        self.watch.tell(&Step::Iteration {
            candidate: self.candidate,
            variant: self.variant,
            iteration: progress.iteration,
            chi2: progress.cost,
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;

    #[test]
    fn a_watch_tells_its_pass_with_every_step() {
        let seen = Mutex::new(Vec::new());
        let tell = |pass: Pass, step: &Step| {
            seen.lock().unwrap().push(format!("{pass:?} {step:?}"));
        };
        let watch = Watch::new(&tell);
        watch.tell(&Step::Calibrated {
            chi2: 1.5,
            iterations: 3,
        });
        let later = watch.during(Pass::Candidates);
        later.tell(&Step::Fitted {
            candidate: "joint_mass",
            outcome: Ok(2.5),
        });
        let mut observer = Iterations {
            watch: later,
            candidate: "c",
            variant: Some("v"),
        };
        crate::optim::Observer::observe(
            &mut observer,
            &crate::optim::Progress {
                iteration: 2,
                cost: 4.0,
                mu: 1e-3,
                accepted: true,
                trials: 1,
            },
        );
        assert_eq!(
            *seen.lock().unwrap(),
            [
                "Calibration Calibrated { chi2: 1.5, iterations: 3 }",
                "Candidates Fitted { candidate: \"joint_mass\", outcome: Ok(2.5) }",
                "Candidates Iteration { candidate: \"c\", variant: Some(\"v\"), iteration: 2, chi2: 4.0 }",
            ]
        );
        Watch::silent().tell(&Step::Calibrated {
            chi2: 0.0,
            iterations: 0,
        });
    }
}
