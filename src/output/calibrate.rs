//! The terminal summary of `jointid calibrate`: the factors with their standard errors, the
//! frequency errors of the reference specimen before and after, and the discrepancy left.

use std::io::{self, Write};

use crate::calibrate::Calibrated;

/// Writes the summary of `c`.
pub fn write_text(w: &mut dyn Write, c: &Calibrated) -> io::Result<()> {
    writeln!(w, "reference specimen: {}", c.specimen)?;
    writeln!(
        w,
        "{:<28} {:>10} {:>10} {:>8}",
        "factor of the typed value", "value", "se", "beams"
    )?;
    for f in &c.factors {
        let beams: Vec<String> = f
            .unknown
            .beams
            .iter()
            .map(|b| (b + 1).to_string())
            .collect();
        writeln!(
            w,
            "{:<28} {:>10.5} {:>10.5} {:>8}",
            f.unknown.name,
            f.factor.value,
            f.factor.se,
            beams.join(",")
        )?;
    }
    writeln!(
        w,
        "frequency error RMS: {:.3}% typed, {:.3}% calibrated (chi^2 {:.4} / {} under the measurement error)",
        c.typed_rms_pct, c.calibrated_rms_pct, c.chi2, c.dof
    )?;
    writeln!(
        w,
        "{:>5} {:>12} {:>10} {:>12}",
        "mode", "measured Hz", "typed %", "calibrated %"
    )?;
    for m in &c.modes {
        writeln!(
            w,
            "{:>5} {:>12.4} {:>10.3} {:>12.3}",
            m.mode,
            m.measured_hz,
            100.0 * m.typed_error,
            100.0 * m.calibrated_error
        )?;
    }
    if let Some(t) = &c.trend {
        writeln!(
            w,
            "the calibrated frequencies still trend with frequency ({:+.2}% per decade, {:.1} standard errors): the factors absorb an effect the beam model lacks (shear and rotary inertia of a thick beam: a Timoshenko beam; a support), and are the model's, not the material's",
            100.0 * t.per_decade,
            t.sigmas
        )?;
    }
    let d = &c.discrepancy;
    if d.is_zero() {
        writeln!(
            w,
            "the calibrated specimen fits within the measurement error"
        )
    } else {
        writeln!(
            w,
            "model discrepancy left (in the standard errors): frequencies {:.3}%, shapes {:.3} of the peak",
            100.0 * d.frequency,
            d.shape
        )
    }
}
