//! The diagnosis report for the terminal. (The JSON form is the report's serde serialisation.)

use std::io::{self, Write};

use super::table::{plus_minus, sci, write_table};
use crate::diagnose::noise::LARGEST_FACTOR;
use crate::diagnose::report::Profile;
use crate::diagnose::report::{
    ErrorSummary, Flatness, Lacking, Misfit, ModeCorrection, Remaining, Source,
};
use crate::diagnose::{AMBIGUITY_MARGIN, Report, Verdict};
use crate::diagnose::{Estimate, LimitKind};

fn summary_line(label: &str, s: &ErrorSummary) -> Vec<String> {
    vec![
        label.to_string(),
        format!("{:.3}", s.frequency_rms_pct),
        format!("{:.4}", s.min_mac),
        format!("{:.4}", s.mean_mac),
        format!("{:.1}/{}", s.chi2, s.dof),
        format!("{:.2}", s.chi2_per_dof),
        format!("{:.2e}", s.p_value),
        format!(
            "{:.3}, {:.3}",
            100.0 * s.discrepancy.frequency,
            100.0 * s.discrepancy.shape
        ),
    ]
}

fn corrections(
    out: &mut dyn Write,
    title: &str,
    list: &[ModeCorrection],
    flat: &[Flatness],
) -> io::Result<()> {
    writeln!(out, "\n{title}")?;
    let rows: Vec<Vec<String>> = list
        .iter()
        .map(|c| {
            let empty = match c.source {
                Source::Held => "held",
                _ => "rank-deficient",
            };
            let from = match c.source {
                Source::Frequency => " f",
                _ => "",
            };
            vec![
                c.mode.to_string(),
                format!("{:.2}", c.frequency_hz),
                c.param.clone(),
                c.correction
                    .map(|v| format!("{}{from}", sci(v)))
                    .unwrap_or_else(|| empty.into()),
                c.std.map(sci).unwrap_or_default(),
                c.relative
                    .map(|z| {
                        let mark = if c.physical == Some(false) { " *" } else { "" };
                        format!("{:+.4}{mark}", z)
                    })
                    .unwrap_or_default(),
            ]
        })
        .collect();
    write_table(
        out,
        &[
            "mode",
            "f (Hz)",
            "param",
            "Delta p",
            "+- std",
            "Delta p / p",
        ],
        &rows,
    )?;
    if list.iter().any(|c| c.source == Source::Frequency) {
        writeln!(
            out,
            "  f: from the mode's frequency alone (its shape components cannot carry the paper's system): the parameter the mode is most sensitive to, the others held"
        )?;
    }
    if list.iter().any(|c| c.physical == Some(false)) {
        writeln!(
            out,
            "  * p + Delta p <= 0: beyond the reach of the per-mode linear step (the mode disagrees with the model in more than the joint)"
        )?;
    }
    for f in flat {
        writeln!(
            out,
            "  {}: weighted mean {}, slope {} per kHz, flatness chi^2 {:.1}/{} (p = {:.2e}): {}",
            f.param,
            sci(f.mean),
            plus_minus(f.slope_per_khz, f.slope_se_per_khz),
            f.chi2,
            f.dof,
            f.p_value,
            if f.p_value < 0.001 || f.slope_per_khz.abs() > 3.0 * f.slope_se_per_khz {
                "changes with the mode"
            } else {
                "constant within noise"
            }
        )?;
    }
    Ok(())
}

/// The verdict of `r` in words: a sentence for the text report when `long`, else a title
/// (the name of the selected candidate, `partial (a)`, `ambiguous (a, b)`, `none`, ...).
pub fn verdict_text(r: &Report, long: bool) -> String {
    let selected = r.selected.as_deref().unwrap_or("");
    let contenders = r.contenders.join(", ");
    let removed = r
        .remaining
        .as_ref()
        .map_or(String::new(), |m| format!("{:.0}%", 100.0 * m.removed));
    match (r.verdict, long) {
        (Verdict::None, false) => "none".into(),
        (Verdict::None, true) => "none: the calibrated model explains the data within the measurement error (the yardstick below)".into(),
        (Verdict::Effect, false) => selected.into(),
        (Verdict::Effect, true) => format!("effect: {selected}"),
        (Verdict::Partial, false) => format!("partial ({selected})"),
        (Verdict::Partial, true) => format!(
            "partial: {selected} is clearly the best explanation and removes {removed} of the calibrated joint's misfit, but a misfit beyond the measurement error remains (below)"
        ),
        (Verdict::Ambiguous, false) => format!("ambiguous ({contenders})"),
        (Verdict::Ambiguous, true) => format!(
            "ambiguous: {contenders} explain the data about equally well (AIC within {AMBIGUITY_MARGIN} of the best); 'after' is the best, {selected}"
        ),
        (Verdict::FrequencyDependent, false) => "frequency-dependent".into(),
        (Verdict::FrequencyDependent, true) => format!(
            "frequency-dependent: {}; a joint whose stiffness scales as (f / f_ref)^alpha, each mode at its own frequency, explains the data and no static candidate comes close (the paper's frequency-dependent joint; candidate {selected})",
            alphas(r)
        ),
        (Verdict::Unexplained, false) => "unexplained".into(),
        (Verdict::Unexplained, true) if !r.contenders.is_empty() => format!(
            "unexplained: {contenders} each explain part of the misfit about equally well (AIC within {AMBIGUITY_MARGIN}), and none brings it down to the measurement error (an effect outside the library, or several)"
        ),
        (Verdict::Unexplained, true) => "unexplained: no candidate is clearly better than the calibrated joint, and the joint alone leaves a misfit beyond the measurement error (an effect outside the library)".into(),
    }
}

/// What the library offers or lacks for a local or distributed change.
fn extended(tried: bool) -> &'static str {
    if tried {
        " (of another kind than the library's local stiffness and joint region: a mass with its stiffness, a changed section, a layered lap)"
    } else {
        " (the extended library's local_stiffness and joint_region search such changes: --extended)"
    }
}

/// The selected candidate's alphas, `alpha = 0.45 +- 0.02` or one per parameter.
fn alphas(r: &Report) -> String {
    let list: Vec<String> = r
        .candidates
        .iter()
        .filter(|c| Some(&c.name) == r.selected.as_ref())
        .flat_map(|c| &c.parameters)
        .map(|e| {
            let name = e
                .name
                .rsplit_once(".alpha")
                .map_or("alpha", |(_, tail)| tail);
            let name = match name.strip_prefix('.') {
                Some(param) => format!("alpha({param})"),
                None => "alpha".to_string(),
            };
            format!("{name} = {}", plus_minus(e.value, e.se))
        })
        .collect();
    list.join(", ")
}

/// One line of a scan's chi^2 along its coordinate.
fn profile(out: &mut dyn Write, name: &str, p: &Profile) -> io::Result<()> {
    let points: Vec<String> = p
        .points
        .iter()
        .map(|(x, chi2)| match chi2 {
            Some(c) => format!("{x:.4} {c:.1}"),
            None => format!("{x:.4} -"),
        })
        .collect();
    writeln!(
        out,
        "  {name}: chi^2 along {} ({}): {}; best {:.4}, chi^2 within 1 of the least from {:.4} to {:.4} (- : failed or not physical)",
        p.coordinate,
        p.unit,
        points.join(", "),
        p.best,
        p.interval.0,
        p.interval.1
    )
}

/// Writes the report as text.
pub fn write_text(out: &mut dyn Write, r: &Report) -> io::Result<()> {
    write_verdict(out, r)?;
    write_noise(out, r)?;
    write_errors(out, r)?;
    write_candidates(out, r)?;
    write_parameters(out, &r.after.parameters)?;
    if let Some(check) = &r.reduction {
        super::reduction::write_reduction(out, check)?;
    }
    if let Some(reference) = &r.reference {
        write_absorbed(out, reference)?;
    }
    corrections(
        out,
        &format!(
            "per-mode joint corrections, joint calibrated ({})",
            r.per_mode_settings
        ),
        &r.per_mode_before,
        &r.flatness_before,
    )?;
    corrections(
        out,
        "per-mode joint corrections, after",
        &r.per_mode_after,
        &r.flatness_after,
    )?;
    Ok(())
}

/// The joint with the beams as typed beside the joint with the beams calibrated.
fn write_absorbed(out: &mut dyn Write, a: &crate::diagnose::report::Absorbed) -> io::Result<()> {
    let factors: Vec<String> = a
        .beams
        .iter()
        .flat_map(|b| {
            [("E", b.stiffness), ("rho", b.density)]
                .into_iter()
                .filter_map(move |(name, f)| {
                    f.map(|f| {
                        format!(
                            "{name} x {:.4} +- {:.4} (beam {})",
                            f.value,
                            f.se,
                            b.beam + 1
                        )
                    })
                })
        })
        .collect();
    writeln!(
        out,
        "\nbeams calibrated on a reference test: {}; with the beams as typed the joint would be (frequency RMS {:.3}%):",
        factors.join(", "),
        a.typed_frequency_rms_pct
    )?;
    for p in &a.parameters {
        writeln!(
            out,
            "  {} = {} typed, {} +- {} calibrated: x {:.4}, {:+.1} standard errors",
            p.name,
            sci(p.typed),
            sci(p.calibrated),
            sci(p.se),
            p.ratio,
            p.sigmas
        )?;
    }
    Ok(())
}

/// The fitted parameters, each `name = value +- se unit`, `not identifiable`, or at a limit
/// with the bound the data set.
fn write_parameters(out: &mut dyn Write, parameters: &[Estimate]) -> io::Result<()> {
    writeln!(out, "\nfitted parameters after:")?;
    for e in parameters {
        match e.limit {
            Some(limit) => {
                let (words, side) = match limit.kind {
                    LimitKind::Rigid => ("rigid", ">="),
                    LimitKind::Free => ("free", "<="),
                };
                writeln!(
                    out,
                    "  {} = {words}: the data cannot tell it from its {words} limit ({} {side} {} {} at 95%; the fit stopped at {})",
                    e.name,
                    e.name,
                    sci(limit.bound),
                    e.unit,
                    sci(e.value)
                )?;
            }
            None => writeln!(
                out,
                "  {} = {} {}",
                e.name,
                plus_minus(e.value, e.se),
                e.unit
            )?,
        }
    }
    Ok(())
}

/// The verdict, with the trend and the misfit's pattern when there are, what remains with a
/// partial explanation, and the modes left out.
fn write_verdict(out: &mut dyn Write, r: &Report) -> io::Result<()> {
    let verdict = verdict_text(r, true);
    writeln!(out, "verdict: {verdict}")?;
    for u in &r.undetermined {
        writeln!(
            out,
            "  the {} discrepancy cannot be estimated: {} values leave {:.1} degrees of freedom after the model's unknowns; it is held at 0 (the measurement error alone)",
            u.kind, u.values, u.dof
        )?;
    }
    for l in &r.left_out {
        writeln!(
            out,
            "  mode {} ({:.4} Hz) left out: {}",
            l.mode, l.frequency_hz, l.reason
        )?;
    }
    if let Some(m) = &r.remaining {
        writeln!(
            out,
            "  remaining with {}: chi^2 {:.1}/{} under the measurement error (the joint calibrated: {:.1}/{}); its discrepancy: frequencies {:.3}%, shapes {:.3}% of the peak (standard deviations beyond the measurement error)",
            r.selected.as_deref().unwrap_or(""),
            m.chi2,
            m.dof,
            r.before.chi2,
            r.before.dof,
            100.0 * r.discrepancy.frequency,
            100.0 * r.discrepancy.shape
        )?;
        write_pattern(out, &m.pattern)?;
        if m.modes.is_empty() {
            writeln!(
                out,
                "  no single mode stays beyond the measurement error: the misfit is spread over the modes"
            )?;
        }
        for mode in &m.modes {
            writeln!(out, "    {}", remaining_text(mode))?;
        }
    }
    for f in &r.trend {
        writeln!(
            out,
            "  trend of {}: {} per kHz ({:.1} standard errors) about a weighted mean of {}",
            f.param,
            plus_minus(f.slope_per_khz, f.slope_se_per_khz),
            f.slope_per_khz / f.slope_se_per_khz,
            sci(f.mean)
        )?;
    }
    if let Some(p) = &r.pattern {
        write_pattern(out, p)?;
        write_remains(out, &r.remains)?;
    }
    Ok(())
}

/// Where a misfit sits: its share in the frequencies, the modes that carry most, the stretches
/// of the beams with the largest shape residuals.
fn write_pattern(out: &mut dyn Write, p: &crate::diagnose::ResidualPattern) -> io::Result<()> {
    {
        let modes: Vec<String> = p
            .modes
            .iter()
            .take(3)
            .map(|m| {
                format!(
                    "mode {} (chi^2 {:.1}: frequency {:.1}, shape {:.1})",
                    m.mode,
                    m.frequency + m.shape,
                    m.frequency,
                    m.shape
                )
            })
            .collect();
        writeln!(
            out,
            "  remaining misfit: {} of chi^2 in the frequencies; most in {}",
            format_args!("{:.0}%", 100.0 * p.frequency_share),
            modes.join(", ")
        )?;
        let regions: Vec<String> = p
            .regions
            .iter()
            .map(|g| {
                format!(
                    "x = {:.4} to {:.4} m ({:.0}%)",
                    g.x_from,
                    g.x_to,
                    100.0 * g.share
                )
            })
            .collect();
        writeln!(
            out,
            "  largest shape residuals along the beams (share of the shape chi^2): {}",
            regions.join("; ")
        )?;
    }
    Ok(())
}

/// What remains of each mode with every model, one line each.
fn write_remains(out: &mut dyn Write, remains: &[Remaining]) -> io::Result<()> {
    if remains.is_empty() {
        return writeln!(
            out,
            "  no single mode stays beyond the noise with every model: the misfit is spread over the modes"
        );
    }
    writeln!(out, "  what remains with every model (the closest named):")?;
    for m in remains {
        writeln!(out, "    {}", remaining_text(m))?;
    }
    Ok(())
}

/// One mode's remaining misfit in words: `mode 2 shape: MAC <= 0.9500 with every model ...`.
pub fn remaining_text(m: &Remaining) -> String {
    let what = match &m.misfit {
        Misfit::Frequency { error_pct, sigmas } => format!(
            "mode {} frequency: {error_pct:+.2}% ({:.1} sigma) with the closest model ({}), at least that with every other",
            m.mode,
            sigmas.abs(),
            m.closest
        ),
        Misfit::Shape { mac, chi2, dof } => format!(
            "mode {} shape: MAC <= {mac:.4} with every model (shape chi^2 {chi2:.1}/{dof} with the closest, {})",
            m.mode, m.closest
        ),
    };
    let lacking = match &m.lacking {
        None => return what,
        Some(Lacking::LocalChange {
            x,
            share,
            extended_tried,
        }) => format!(
            "{:.0}% of it at the sensor at x = {x:.4} m: a local change of the structure there{}, or that sensor's own error (position, direction, calibration)",
            100.0 * share,
            extended(*extended_tried)
        ),
        Some(Lacking::Distributed { extended_tried }) => format!(
            "with its frequency, spread along the mode: a change of stiffness or mass along the structure that no candidate places{}",
            extended(*extended_tried)
        ),
        Some(Lacking::ShapeMixing { extended_tried }) => format!(
            "spread along the mode while its frequency fits: a change of stiffness or mass along the structure that the joint's calibration offsets in frequency{}; or motion the planar bending model lacks (torsion or the other bending plane mixing in, a close mode); or sensors placed or directed otherwise than the model says",
            extended(*extended_tried)
        ),
        Some(Lacking::FrequencyOnly) => "its shape fits: a change the sensors do not resolve, a joint that depends on the vibration amplitude (`jointid amplitude` fits one across excitation levels), or a frequency dependence other than a power law".to_string(),
    };
    format!("{what}; {lacking}")
}

/// The stated noise and the estimate, and the pairing remarks.
fn write_noise(out: &mut dyn Write, r: &Report) -> io::Result<()> {
    let e = &r.noise_estimate;
    if !e.from_data {
        writeln!(
            out,
            "noise stated: frequency {} (relative std), shape {} (relative std, floor {} of the mode's peak)",
            r.noise.frequency, r.noise.shape, r.shape_floor
        )?;
    }
    if e.from_data {
        return writeln!(
            out,
            "noise used: the data's own standard errors (frequency_std, value_std; RMS relative: frequency {:.3e}, shape {:.3e}); the stated noise is not used. Check: the residuals of the largest model ({}) are {:.2}x them in the shapes and {:.2}x in the frequencies (1 when the errors are right and the model fits)",
            e.working.frequency, e.working.shape, e.from_model, e.shape_factor, e.frequency_factor
        )
        .and_then(|()| warnings(out, r));
    }
    if e.stated_kept {
        return writeln!(
            out,
            "noise used: the stated; no model's residuals pass the checks that do not stand on the noise level (whiteness along the structure, frequencies against the shapes' scale, within {}x the stated), so none gives the yardstick. Check: the largest model ({}) leaves shape {:.3e} ({:.2}x stated) and frequencies alone {:.3e} ({:.2}x stated)",
            LARGEST_FACTOR,
            e.from_model,
            e.shape,
            e.shape_factor,
            e.frequency_check,
            e.frequency_factor
        )
        .and_then(|()| warnings(out, r));
    }
    writeln!(
        out,
        "noise estimated from the shape residuals of the largest model that fits ({}): shape {:.3e} ({:.2}x stated), floor {:.3e} of the peak; frequencies alone {:.3e} ({:.2}x stated, a check); adequacy judged under frequency {:.3e}, shape {:.3e}, floor {:.3} of the peak",
        e.from_model,
        e.shape,
        e.shape_factor,
        e.shape_floor_abs,
        e.frequency_check,
        e.frequency_factor,
        e.working.frequency,
        e.working.shape,
        e.working_floor
    )?;
    warnings(out, r)
}

/// The pairing remarks.
fn warnings(out: &mut dyn Write, r: &Report) -> io::Result<()> {
    for w in &r.warnings {
        writeln!(out, "warning: {w}")?;
    }
    Ok(())
}

/// The columns of [`summary_rows`].
pub const SUMMARY_HEADERS: [&str; 8] = [
    "model",
    "f RMS (%)",
    "min MAC",
    "mean MAC",
    "chi^2/dof",
    "ratio",
    "P(fit)",
    "discr. f, s (%)",
];

/// The errors of the model as given, with the joint calibrated and after, one row each.
pub fn summary_rows(r: &Report) -> Vec<Vec<String>> {
    vec![
        summary_line("as given", &r.initial),
        summary_line("joint calibrated", &r.before),
        summary_line("after", &r.after),
    ]
}

/// The columns of [`candidate_rows`].
pub const CANDIDATE_HEADERS: [&str; 9] = [
    "candidate",
    "size",
    "chi^2/dof",
    "discr. f, s (%)",
    "LR stat",
    "p (adj.)",
    "P(fit)",
    "P(freq)",
    "P(white)",
];

/// The errors of the model as given, calibrated and after; then mode by mode.
fn write_errors(out: &mut dyn Write, r: &Report) -> io::Result<()> {
    writeln!(out)?;
    write_table(out, &SUMMARY_HEADERS, &summary_rows(r))?;
    writeln!(
        out,
        "\nper mode (joint calibrated -> after): frequency error %, MAC"
    )?;
    let rows: Vec<Vec<String>> = r
        .before
        .modes
        .iter()
        .zip(&r.after.modes)
        .map(|(b, a)| {
            vec![
                b.mode.to_string(),
                b.model_mode.to_string(),
                format!("{:.3}", b.frequency_measured_hz),
                format!("{:+.3}", b.frequency_error_pct),
                format!("{:+.3}", a.frequency_error_pct),
                format!("{:.4}", b.mac),
                format!("{:.4}", a.mac),
            ]
        })
        .collect();
    write_table(
        out,
        &[
            "mode",
            "model mode",
            "f meas (Hz)",
            "err before",
            "err after",
            "MAC before",
            "MAC after",
        ],
        &rows,
    )?;
    Ok(())
}

/// Every candidate with its fit and tests (or why it failed or was excluded), and the scans'
/// profiles.
fn write_candidates(out: &mut dyn Write, r: &Report) -> io::Result<()> {
    writeln!(out, "\ncandidates ({})", r.criterion)?;
    write_table(out, &CANDIDATE_HEADERS, &candidate_rows(r))?;
    for c in &r.candidates {
        if let Some(p) = &c.profile {
            profile(out, &c.name, p)?;
        }
    }
    Ok(())
}

/// One row per candidate: its fit and tests, or why it failed or was excluded (a note after
/// the columns).
pub fn candidate_rows(r: &Report) -> Vec<Vec<String>> {
    // Name, size, chi^2/dof and LR statistic of a fitted candidate.
    let fitted_cells = |c: &crate::diagnose::CandidateReport| {
        vec![
            c.name.clone(),
            plus_minus(c.size.unwrap_or(0.0), c.size_se.unwrap_or(0.0)),
            format!("{:.1}/{}", c.chi2.unwrap_or(0.0), c.dof.unwrap_or(0)),
            c.discrepancy
                .as_ref()
                .map(|d| format!("{:.3}, {:.3}", 100.0 * d.frequency, 100.0 * d.shape))
                .unwrap_or_default(),
            format!("{:.1}", c.lrt.unwrap_or(0.0)),
        ]
    };
    r.candidates
        .iter()
        .map(|c| match &c.error {
            None if c.excluded.is_some() => [
                fitted_cells(c),
                vec![
                    "excluded".into(),
                    String::new(),
                    String::new(),
                    String::new(),
                    c.excluded.clone().unwrap_or_default(),
                ],
            ]
            .concat(),
            Some(e) => vec![
                c.name.clone(),
                "fit failed".into(),
                String::new(),
                String::new(),
                String::new(),
                String::new(),
                String::new(),
                String::new(),
                String::new(),
                e.clone(),
            ],
            None => [
                fitted_cells(c),
                vec![
                    format!("{:.2e}", c.criterion.unwrap_or(1.0)),
                    format!("{:.2e}", c.fit_p_value.unwrap_or(0.0)),
                    format!("{:.2e}", c.frequency_p_value.unwrap_or(0.0)),
                    format!("{:.2e}", c.whiteness_p_value.unwrap_or(0.0)),
                ],
            ]
            .concat(),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_parameter_without_a_finite_error_reads_not_identifiable() {
        let estimate = |value: f64, se: f64| Estimate {
            name: "joint1.k1".into(),
            unit: "N/m",
            value,
            se,
            limit: None,
        };
        let mut out = Vec::new();
        write_parameters(&mut out, &[estimate(1e7, 2e5), estimate(0.0, f64::NAN)]).unwrap();
        assert_eq!(
            String::from_utf8(out).unwrap(),
            "\nfitted parameters after:\n  joint1.k1 = 1.000e7 +- 2.000e5 N/m\n  joint1.k1 = not identifiable N/m\n"
        );
    }
}
