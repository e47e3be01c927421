//! Running a call's work off the interpreter: on its own thread, in a rayon pool of the
//! requested size, the GIL released; the calling thread wakes every [`TICK`] to let Python
//! handle its signals, so that Ctrl-C raises `KeyboardInterrupt` within a tick. The work is
//! then told to stop (a study stops within a block of trials) and is abandoned: its result,
//! whenever it comes, is dropped.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::Duration;

use pyo3::prelude::*;

use crate::errors;

/// How often the waiting thread looks at Python's signals.
const TICK: Duration = Duration::from_millis(50);

/// The most worker threads a call may ask for, per core (as the CLI's `--threads`).
const THREADS_PER_CORE: usize = 8;

/// The worker pool of a call: `threads` workers, or one per core.
pub fn pool(threads: Option<usize>) -> PyResult<rayon::ThreadPool> {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let limit = THREADS_PER_CORE * cores;
    if let Some(t) = threads.filter(|t| !(1..=limit).contains(t)) {
        return Err(errors::setting(format!(
            "threads = {t} is invalid: it must be from 1 to {limit} ({THREADS_PER_CORE} per core, {cores} core(s) here)"
        )));
    }
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
        .map_err(|e| errors::computation(format!("cannot start the worker threads: {e}")))
}

/// Runs `work` (given the stop flag) on a worker thread inside a pool of `threads`, the GIL
/// released; returns its result, or the exception a signal handler raised (KeyboardInterrupt
/// on Ctrl-C) after setting the stop flag.
pub fn run<T, F>(py: Python<'_>, threads: Option<usize>, work: F) -> PyResult<T>
where
    T: Send + 'static,
    F: FnOnce(&AtomicBool) -> PyResult<T> + Send + 'static,
{
    run_watched(py, threads, work, |_| Ok(()))
}

/// [`run`], with `tick` called with the GIL at every tick (to report progress; an error it
/// returns stops the work as a signal does).
pub fn run_watched<T, F>(
    py: Python<'_>,
    threads: Option<usize>,
    work: F,
    mut tick: impl FnMut(Python<'_>) -> PyResult<()>,
) -> PyResult<T>
where
    T: Send + 'static,
    F: FnOnce(&AtomicBool) -> PyResult<T> + Send + 'static,
{
    let pool = pool(threads)?;
    let stop = Arc::new(AtomicBool::new(false));
    let (tx, rx) = mpsc::channel();
    let flag = Arc::clone(&stop);
    std::thread::Builder::new()
        .name("jointid-call".into())
        .spawn(move || {
            let result = pool.install(|| work(&flag));
            // The caller may have gone (interrupted): the result is then dropped.
            let _ = tx.send(result);
        })
        .map_err(|e| errors::computation(format!("cannot start the call's thread: {e}")))?;
    let mut rx = rx;
    loop {
        let (received, back) = py.detach(move || (rx.recv_timeout(TICK), rx));
        rx = back;
        match received {
            Ok(result) => return result,
            Err(mpsc::RecvTimeoutError::Timeout) => {
                if let Err(e) = py.check_signals().and_then(|()| tick(py)) {
                    stop.store(true, Ordering::Relaxed);
                    return Err(e);
                }
            }
            Err(mpsc::RecvTimeoutError::Disconnected) => {
                return Err(errors::computation(
                    "the call's thread ended without a result (a bug of jointid: please report it)",
                ));
            }
        }
    }
}
