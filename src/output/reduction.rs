//! The check of a diagnosis's reduced model against the full one, for the terminal: one line
//! of the basis and the largest differences, then one row per measured mode.

use std::io::{self, Write};

use super::table::write_table;
use crate::diagnose::reduce::{FREQUENCY_TOLERANCE, ReductionCheck};

/// The check, after the fitted parameters.
pub fn write_reduction(out: &mut dyn Write, c: &ReductionCheck) -> io::Result<()> {
    let outcome = if c.verified {
        format!("every frequency within {FREQUENCY_TOLERANCE:.0e}")
    } else {
        format!(
            "a frequency beyond {FREQUENCY_TOLERANCE:.0e}: the diagnosis above was made again on the full model"
        )
    };
    writeln!(
        out,
        "\nreduced model ({} basis vectors, {} of them added by enrichment) against one full solve at the final parameters: largest |f_reduced / f_full - 1| {:.1e}, largest 1 - MAC {:.1e}, largest error estimate {:.1e}; {outcome}",
        c.dimension,
        c.enriched,
        c.largest_frequency_difference,
        c.largest_mac_difference,
        c.largest_residual
    )?;
    let header = [
        "mode",
        "model mode",
        "f reduced (Hz)",
        "f full (Hz)",
        "rel. diff.",
        "1 - MAC",
        "error est.",
    ];
    let rows: Vec<Vec<String>> = c
        .modes
        .iter()
        .map(|m| {
            vec![
                m.mode.to_string(),
                m.model_mode.to_string(),
                format!("{:.6}", m.reduced_hz),
                format!("{:.6}", m.full_hz),
                format!("{:+.1e}", m.frequency_difference),
                format!("{:.1e}", m.mac_difference),
                format!("{:.1e}", m.residual),
            ]
        })
        .collect();
    write_table(out, &header, &rows)
}
