//! `jointid diagnose`: calibrate, trace the residual to a missing effect, report.

use std::sync::{Mutex, PoisonError};
use std::time::{Duration, Instant};

use anyhow::{Context, bail};

use crate::cli::DiagnoseArgs;
use jointid::diagnose::absorbed::absorbed;
use jointid::diagnose::{
    DiagnoseError, DiagnoseSettings, Pass, Step, Watch, diagnose_solved, nominal_count,
};
use jointid::identify::Settings;
use jointid::measured::MeasuredModes;
use jointid::output::diagnose_log;
use jointid::output::diagnose_page::diagnose_page;
use jointid::output::diagnose_plots::diagnose_figures;
use jointid::output::guard::model_inputs;
use jointid::output::{check_outputs, commit_all, diagnose as out, stage};

use crate::commands::flagged;
use crate::commands::report::stage_page;

/// The library's settings and the flags that set them.
const FLAGS: [(&str, &str); 4] = [
    ("frequency_noise", "--frequency-noise"),
    ("shape_noise", "--shape-noise"),
    ("pairing_window", "--pairing-window"),
    ("causes", "--causes"),
];

pub fn run(args: &DiagnoseArgs) -> anyhow::Result<()> {
    let per_mode = match (args.n, args.m) {
        (None, None) => None,
        (Some(n), Some(m)) => Some(Settings {
            n,
            m,
            weighting: args.weighting,
        }),
        _ => bail!("--n and --m go together (or leave both out for the defaults)"),
    };
    let settings = DiagnoseSettings {
        noise: args.error.noise(),
        pairing: args.error.pairing(args.pair.clone()),
        per_mode,
        extended: args.extended,
        full_model: args.full_model,
        causes: args
            .causes
            .iter()
            .map(|c| c.split('+').map(|n| n.trim().to_string()).collect())
            .collect(),
    };
    settings.check().map_err(|e| flagged(e, &FLAGS))?;
    let mut inputs = model_inputs(&args.model);
    inputs.push(args.measured.clone());
    let inputs: Vec<&std::path::Path> = inputs.iter().map(|p| p.as_path()).collect();
    let mut outputs: Vec<&std::path::Path> = args.json.iter().map(|p| p.as_path()).collect();
    let index = args.plots.as_ref().map(|dir| dir.join("index.html"));
    outputs.extend(index.as_deref());
    check_outputs(&outputs, &inputs)?;
    let (model, nominal) = super::read_model_for(&args.model, &args.measured, |read, modes| {
        Some(nominal_count(read, modes, &settings))
    })?;
    // A chain whose beams were calibrated on a reference test: the same chain as typed.
    let typed =
        calibrated_chain(&args.model)?.map(|chain| (chain.typed().build(), chain.calibration));
    let measured = args
        .error
        .weighed(MeasuredModes::from_path(&args.measured, &model)?);
    let log = Log::new(HOLD, PACE, |line: &str| eprintln!("{line}"));
    let tell = |pass: Pass, step: &Step| log.tell(pass, step);
    let watch = if args.quiet {
        Watch::silent()
    } else {
        Watch::new(&tell)
    };
    let report = diagnose_solved(&model, &measured, settings.clone(), watch, nominal);
    log.end();
    let mut report = match report {
        // A setting refused once the model is known (a cause that does not apply to it).
        Err(DiagnoseError::Settings(e)) => return Err(flagged(e, &FLAGS)),
        other => other.with_context(|| format!("{}", args.measured.display()))?,
    };
    if let Some((typed, beams)) = &typed {
        let a = absorbed(typed, beams, &measured, &settings, &report).with_context(|| {
            format!(
                "{}: the joint on the beams as typed (before their calibration)",
                args.measured.display()
            )
        })?;
        report.reference = Some(a);
    }
    let mut staged = Vec::new();
    if let Some(path) = &args.json {
        staged.push(
            stage(path, |w| {
                serde_json::to_writer_pretty(&mut *w, &report).map_err(std::io::Error::other)
            })
            .with_context(|| format!("{}: cannot write", path.display()))?,
        );
    }
    if let Some(dir) = &args.plots {
        let figures = diagnose_figures(&report, &measured)?;
        let title = format!(
            "Diagnosis of {}: verdict {}",
            args.measured.display(),
            out::verdict_text(&report, false)
        );
        let page = diagnose_page(&title, &report, &figures);
        staged.extend(stage_page(dir, &figures, &page, &inputs)?);
    }
    commit_all(staged)?;
    super::to_stdout(|w| out::write_text(w, &report))
}

/// The chain of `model` when it is one whose beams were calibrated on a reference test.
fn calibrated_chain(model: &std::path::Path) -> anyhow::Result<Option<jointid::model::Chain>> {
    let text = jointid::input::read_file(model)?;
    match jointid::model::chain_from_toml(&text, model) {
        Ok(chain) if !chain.calibration.is_empty() => Ok(Some(chain)),
        _ => Ok(None),
    }
}

/// How long the log holds its lines back: a run that ends sooner logs nothing.
const HOLD: Duration = Duration::from_secs(2);
/// Least time between two logged iterations of a fit: a long fit shows it is moving, a quick
/// one does not fill the log.
const PACE: Duration = Duration::from_secs(10);

/// The log of the diagnosis's steps (module `jointid::output::diagnose_log`), each line given
/// to `write`: held back for the first `hold`, then every line as its step finishes; an
/// iteration of a fit only when `pace` has passed since the last line.
struct Log<W> {
    start: Instant,
    hold: Duration,
    pace: Duration,
    lines: Mutex<Lines>,
    write: W,
}

/// What the log has done so far.
struct Lines {
    /// The lines held back, until the first step after the hold writes them.
    held: Option<Vec<String>>,
    /// When the last line was logged (held or written).
    last: Option<Duration>,
}

impl<W: Fn(&str)> Log<W> {
    fn new(hold: Duration, pace: Duration, write: W) -> Self {
        Log {
            start: Instant::now(),
            hold,
            pace,
            lines: Mutex::new(Lines {
                held: Some(Vec::new()),
                last: None,
            }),
            write,
        }
    }

    fn tell(&self, pass: Pass, step: &Step) {
        let mut lines = self.lines.lock().unwrap_or_else(PoisonError::into_inner);
        // Under the lock: the times of the lines in their order.
        let elapsed = self.start.elapsed();
        let soon = lines.last.is_some_and(|t| elapsed < t + self.pace);
        if matches!(step, Step::Iteration { .. }) && soon {
            return;
        }
        lines.last = Some(elapsed);
        let line = diagnose_log::line(elapsed.as_secs_f64(), pass, step);
        match lines.held.as_mut() {
            Some(held) if elapsed < self.hold => held.push(line),
            _ => {
                self.release(&mut lines);
                (self.write)(&line);
            }
        }
    }

    /// The end of the steps: the lines held back written if the run outlasted the hold.
    fn end(&self) {
        let mut lines = self.lines.lock().unwrap_or_else(PoisonError::into_inner);
        if self.start.elapsed() >= self.hold {
            self.release(&mut lines);
        }
    }

    /// Writes the lines held back, and holds no more.
    fn release(&self, lines: &mut Lines) {
        for earlier in lines.held.take().into_iter().flatten() {
            (self.write)(&earlier);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn steps<W: Fn(&str)>(log: &Log<W>) {
        log.tell(
            Pass::Calibration,
            &Step::Calibrated {
                chi2: 2.0,
                iterations: 4,
            },
        );
        log.tell(
            Pass::Candidates,
            &Step::Fitted {
                candidate: "sensor_mass",
                outcome: Ok(3.0),
            },
        );
    }

    /// Within the hold nothing is written, past it the held lines first, in order (by the
    /// next step or by the end); an iteration within the pace of the last line is left out.
    #[test]
    fn the_log_holds_its_lines_back_then_writes_them_in_order() {
        let written = Mutex::new(Vec::new());
        let write = |l: &str| written.lock().unwrap().push(l.to_string());
        let hour = Duration::from_secs(3600);
        let held = Log::new(hour, Duration::ZERO, write);
        steps(&held);
        held.end();
        assert!(written.lock().unwrap().is_empty());
        // A run that outlasts the hold after its last step: the end writes what was held.
        let late = Log::new(Duration::from_millis(20), Duration::ZERO, write);
        steps(&late);
        std::thread::sleep(Duration::from_millis(30));
        late.end();
        assert_eq!(written.lock().unwrap().len(), 2);
        written.lock().unwrap().clear();
        let log = Log::new(Duration::from_millis(20), hour, write);
        steps(&log);
        std::thread::sleep(Duration::from_millis(30));
        // An iteration within the pace is left out, a fit is not.
        log.tell(
            Pass::Candidates,
            &Step::Iteration {
                candidate: "frequency_dependence",
                variant: Some("one alpha"),
                iteration: 1,
                chi2: 3.0,
            },
        );
        log.tell(
            Pass::Candidates,
            &Step::Fitted {
                candidate: "joint_mass",
                outcome: Ok(1.0),
            },
        );
        let lines = written.lock().unwrap();
        let ends: Vec<&str> = lines
            .iter()
            .map(|l| &l[l.find("] ").unwrap() + 2..])
            .collect();
        assert_eq!(
            ends,
            [
                "calibration: joint calibrated: chi^2 2.0 after 4 iterations",
                "candidates: sensor_mass fitted: deviance 3.0",
                "candidates: joint_mass fitted: deviance 1.0",
            ]
        );
        drop(lines);
        // Without a pace every iteration is written: two more lines.
        let paced = Log::new(Duration::ZERO, Duration::ZERO, write);
        for iteration in [1, 2] {
            paced.tell(
                Pass::Calibration,
                &Step::Iteration {
                    candidate: "frequency_dependence",
                    variant: Some("one alpha"),
                    iteration,
                    chi2: 3.0,
                },
            );
        }
        assert_eq!(written.lock().unwrap().len(), 3 + 2);
    }
}
