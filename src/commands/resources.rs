//! The machine's limits, checked before a run starts: a request beyond them is an error that
//! names what to change, never an abort half-way.

use anyhow::bail;

/// The share of the machine's memory one run may plan to use.
const MEMORY_SHARE: f64 = 0.8;

/// Total physical memory in bytes (Linux `/proc/meminfo`), if known.
fn machine_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kib.checked_mul(1024)
}

/// Refuses `need` bytes when they exceed the machine's share; `what` names the run and
/// `change` the fields that reduce it.
pub fn check_memory(need: u64, what: &str, change: &str) -> anyhow::Result<()> {
    let Some(total) = machine_memory() else {
        return Ok(());
    };
    let allowed = (total as f64 * MEMORY_SHARE) as u64;
    if need > allowed {
        bail!(
            "{what} needs {:.1} GB of memory at its peak; this machine has {:.1} GB ({:.0}% may be planned): reduce {change}",
            need as f64 / 1e9,
            total as f64 / 1e9,
            MEMORY_SHARE * 100.0
        );
    }
    Ok(())
}
