//! The outputs of an amplitude fit ([`crate::amplitude`]): four CSV tables, the figure of a
//! mode (stiffness change in % and damping against amplitude, the data with their sigmas, every law's
//! curve and the chosen law's band) and a terminal summary. Formats only: every number comes
//! from the fit.
//!
//! The CSV columns are listed in docs/formats.md ("Amplitude outputs").

use std::io::{self, Write};

use crate::amplitude::{AmplitudeFit, ModeResult, Weights, estimates};
use crate::output::plot::{Band, LineAxes, PlotError, Series, lines_with_bands, svg};

/// Half-width of the bands, in standard errors (about 95%).
pub const BAND_SE: f64 = 2.0;

/// `amplitude_levels.csv`: the data, one row per mode and level.
pub fn write_levels(w: &mut dyn Write, fit: &AmplitudeFit) -> io::Result<()> {
    writeln!(
        w,
        "mode,excitation,acceleration_m_s2,amplitude_m,frequency_hz,frequency_std,\
         stiffness,stiffness_std,damping_ratio,damping_std"
    )?;
    for m in &fit.modes {
        let s = m.data.series();
        for (i, r) in m.data.rows.iter().enumerate() {
            writeln!(
                w,
                "{},{},{},{},{},{},{},{},{},{}",
                r.mode,
                r.excitation,
                r.acceleration,
                r.amplitude,
                r.frequency_hz,
                r.frequency_std,
                s.stiffness[i],
                s.stiffness_std[i],
                r.damping,
                r.damping_std
            )?;
        }
    }
    Ok(())
}

/// `amplitude_laws.csv`: one row per mode and law, fitted or not, with the criteria and the
/// choice.
pub fn write_laws(w: &mut dyn Write, fit: &AmplitudeFit) -> io::Result<()> {
    writeln!(
        w,
        "mode,law,regime,parameters,levels,chi2_stiffness,chi2_damping,tau_stiffness,\
         tau_damping,weights_from,aicc,bic,delta_aicc,akaike_weight,converged,selected,note"
    )?;
    for m in &fit.modes {
        let f = &m.fit;
        let levels = m.data.rows.len();
        for j in &f.laws {
            let l = &j.fitted;
            writeln!(
                w,
                "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},",
                m.data.mode,
                l.law.name(),
                if l.law == crate::amplitude::Law::Iwan {
                    format!("{:?}", l.regime).to_lowercase()
                } else {
                    String::new()
                },
                j.k,
                levels,
                l.chi2_stiffness,
                l.chi2_damping,
                f.tau_stiffness,
                f.tau_damping,
                f.weights_from.name(),
                j.aicc,
                j.bic,
                j.delta_aicc,
                j.weight,
                if l.converged { "yes" } else { "no" },
                if l.law == f.selected { "yes" } else { "no" },
            )?;
        }
        for (law, why) in &f.skipped {
            writeln!(
                w,
                "{},{},,,{levels},,,,,,,,,,,no,not fitted: {why}",
                m.data.mode,
                law.name()
            )?;
        }
    }
    Ok(())
}

/// `amplitude_parameters.csv`: every law's parameters with standard errors, and the derived
/// Iwan quantities ([`estimates`]).
pub fn write_parameters(w: &mut dyn Write, fit: &AmplitudeFit) -> io::Result<()> {
    writeln!(w, "mode,law,selected,parameter,value,std")?;
    for m in &fit.modes {
        let amplitudes = m.data.series().amplitude;
        for j in &m.fit.laws {
            let law = j.fitted.law;
            for e in estimates(j, &amplitudes) {
                writeln!(
                    w,
                    "{},{},{},{},{},{}",
                    m.data.mode,
                    law.name(),
                    if law == m.fit.selected { "yes" } else { "no" },
                    e.name,
                    e.value,
                    e.std
                )?;
            }
        }
    }
    Ok(())
}

/// `amplitude_bands.csv`: every law's stiffness and damping on a grid of amplitudes with
/// their standard errors.
pub fn write_bands(w: &mut dyn Write, fit: &AmplitudeFit) -> io::Result<()> {
    writeln!(
        w,
        "mode,law,selected,amplitude_m,stiffness,stiffness_se,damping_ratio,damping_se"
    )?;
    for m in &fit.modes {
        for (j, band) in m.fit.laws.iter().zip(&m.fit.bands) {
            let law = j.fitted.law;
            for p in band {
                writeln!(
                    w,
                    "{},{},{},{},{},{},{},{}",
                    m.data.mode,
                    law.name(),
                    if law == m.fit.selected { "yes" } else { "no" },
                    p.amplitude,
                    p.stiffness,
                    p.stiffness_se,
                    p.damping,
                    p.damping_se
                )?;
            }
        }
    }
    Ok(())
}

/// The figure of one mode: stiffness (top) and damping ratio (bottom) against amplitude.
pub fn figure(m: &ModeResult) -> Result<String, PlotError> {
    let data = m.data.series();
    let weights = Weights::new(&data, m.fit.tau_stiffness, m.fit.tau_damping);
    // The stiffness is shown as its change from the level of smallest amplitude (%), the
    // damping ratio in %.
    let first = (0..data.len())
        .min_by(|&a, &b| data.amplitude[a].total_cmp(&data.amplitude[b]))
        .map_or(1.0, |i| data.stiffness[i]);
    let change = |k: f64| 100.0 * (k / first - 1.0);
    let panel = |stiffness: bool| {
        // (value, its sigma or se) as drawn.
        let shown = |value: f64, se: f64| {
            if stiffness {
                (change(value), 100.0 * se / first)
            } else {
                (100.0 * value, 100.0 * se)
            }
        };
        let measured: Vec<(f64, f64)> = (0..data.len())
            .map(|i| {
                if stiffness {
                    shown(data.stiffness[i], weights.stiffness[i])
                } else {
                    shown(data.damping[i], weights.damping[i])
                }
            })
            .collect();
        let series = vec![Series {
            name: "measured (+- sigma with extra scatter)".to_string(),
            points: data
                .amplitude
                .iter()
                .zip(&measured)
                .map(|(&a, &(y, _))| (a, y))
                .collect(),
            errors: Some(measured.iter().map(|&(_, s)| s).collect()),
            line: false,
        }];
        let bands: Vec<Band> = m
            .fit
            .laws
            .iter()
            .zip(&m.fit.bands)
            .map(|(j, band)| {
                let chosen = j.fitted.law == m.fit.selected;
                let curve: Vec<(f64, f64)> = band
                    .iter()
                    .map(|p| {
                        if stiffness {
                            shown(p.stiffness, p.stiffness_se)
                        } else {
                            shown(p.damping, p.damping_se)
                        }
                    })
                    .collect();
                Band {
                    name: format!(
                        "{}{} (dAICc {:.1})",
                        j.fitted.law.name(),
                        if chosen { ", chosen, +-2 se" } else { "" },
                        j.delta_aicc
                    ),
                    points: band
                        .iter()
                        .zip(&curve)
                        .map(|(p, c)| (p.amplitude, c.0))
                        .collect(),
                    half_width: curve
                        .iter()
                        .map(|&(_, se)| {
                            if chosen && se.is_finite() {
                                BAND_SE * se
                            } else {
                                0.0
                            }
                        })
                        .collect(),
                }
            })
            .collect();
        (series, bands)
    };
    let axes = |y: &str| LineAxes {
        x_desc: "displacement amplitude at the reference sensor (m)".to_string(),
        y_desc: y.to_string(),
        log_x: false,
        log_y: false,
        reference: None,
        clip_errors: false,
    };
    let mode = m.data.mode;
    svg((900, 900), |root| {
        let (top, bottom) = root.split_vertically(450);
        let (s, b) = panel(true);
        lines_with_bands(
            &top,
            &format!("mode {mode}: modal stiffness against amplitude"),
            &axes("modal stiffness (2 pi f)^2: change from the smallest amplitude (%)"),
            &s,
            &b,
        )?;
        let (s, b) = panel(false);
        lines_with_bands(
            &bottom,
            &format!("mode {mode}: damping ratio against amplitude"),
            &axes("damping ratio (%)"),
            &s,
            &b,
        )
    })
}

/// A terminal summary: per mode, every law's AICc and the chosen law.
pub fn summary(fit: &AmplitudeFit) -> String {
    let mut out = String::new();
    for m in &fit.modes {
        let f = &m.fit;
        out += &format!(
            "mode {}: {} levels, extra sd stiffness {:.4e} (rad/s)^2, damping {:.3e}; chosen: {}\n",
            m.data.mode,
            m.data.rows.len(),
            f.tau_stiffness,
            f.tau_damping,
            f.selected.name()
        );
        for j in &f.laws {
            out += &format!(
                "  {:<10} k = {}  chi2 = {:>9.3}  AICc = {:>9.3}  dAICc = {:>7.3}\n",
                j.fitted.law.name(),
                j.k,
                j.fitted.chi2(),
                j.aicc,
                j.delta_aicc
            );
        }
        for (law, why) in &f.skipped {
            out += &format!("  {:<10} not fitted: {why}\n", law.name());
        }
    }
    out
}
