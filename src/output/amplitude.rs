//! The outputs of an amplitude fit ([`crate::amplitude`]): four CSV tables, the figure of a
//! mode (stiffness change in % and damping against amplitude, the data with their sigmas, every law's
//! curve and the chosen law's band) and a terminal summary; with a joint parameter named, the
//! same of the joint's stiffness and damping (`joint_*`) and the frequencies before and after.
//! Formats only: every number comes from the fit.
//!
//! The CSV columns are listed in docs/formats.md ("Amplitude outputs").

use std::io::{self, Write};

use crate::amplitude::{
    AmplitudeFit, BandPoint, ModeFit, ModeResult, Series as Data, Weights, estimates,
};
use crate::output::plot::{Band, LineAxes, PlotError, Series, lines_with_bands, svg};

/// Half-width of the bands, in standard errors (about 95%).
pub const BAND_SE: f64 = 2.0;

/// The amplitude axis of the modal laws (and of the joint's without a reference point).
const SENSOR_AMPLITUDE: &str = "displacement amplitude at the reference sensor (m)";

/// One mode's series and fit, modal or the joint's.
struct View<'a> {
    mode: usize,
    data: Data,
    fit: &'a ModeFit,
}

/// The modal series of every mode.
fn modal(fit: &AmplitudeFit) -> Vec<View<'_>> {
    fit.modes
        .iter()
        .map(|m| View {
            mode: m.data.mode,
            data: m.data.series(),
            fit: &m.fit,
        })
        .collect()
}

/// The joint's series of every mode that has one.
fn joint(fit: &AmplitudeFit) -> Vec<View<'_>> {
    fit.modes
        .iter()
        .filter_map(|m| {
            let j = m.joint.as_ref()?;
            Some(View {
                mode: m.data.mode,
                data: j.data.series(),
                fit: &j.fit,
            })
        })
        .collect()
}

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

/// `joint_levels.csv`: the joint's data, one row per mode and level.
pub fn write_joint_levels(w: &mut dyn Write, fit: &AmplitudeFit) -> io::Result<()> {
    writeln!(
        w,
        "mode,excitation,amplitude_m,joint_amplitude,frequency_hz,parameter,unit,value,std,\
         sensitivity,joint_damping,joint_damping_std"
    )?;
    for m in &fit.modes {
        let Some(j) = &m.joint else { continue };
        let d = &j.data;
        for (i, r) in m.data.rows.iter().enumerate() {
            writeln!(
                w,
                "{},{},{},{},{},{},{},{},{},{},{},{}",
                r.mode,
                r.excitation,
                r.amplitude,
                d.amplitude[i],
                r.frequency_hz,
                d.name,
                d.unit,
                d.value[i],
                d.std[i],
                d.sensitivity[i],
                d.damping[i],
                d.damping_std[i]
            )?;
        }
    }
    Ok(())
}

/// `joint_errors.csv`: per mode and level, the measured frequency and the model's with the
/// constant law's joint (before) and the chosen law's (after), with their errors in %.
pub fn write_joint_errors(w: &mut dyn Write, fit: &AmplitudeFit) -> io::Result<()> {
    writeln!(
        w,
        "mode,excitation,joint_amplitude,frequency_hz,constant_hz,constant_error_pct,selected_law,\
         selected_hz,selected_error_pct"
    )?;
    for m in &fit.modes {
        let Some(j) = &m.joint else { continue };
        for e in &j.errors {
            let pct = |f: f64| 100.0 * (f / e.measured_hz - 1.0);
            writeln!(
                w,
                "{},{},{},{},{},{},{},{},{}",
                m.data.mode,
                e.excitation,
                e.amplitude,
                e.measured_hz,
                e.constant_hz,
                pct(e.constant_hz),
                j.fit.selected.name(),
                e.selected_hz,
                pct(e.selected_hz)
            )?;
        }
    }
    Ok(())
}

/// `amplitude_laws.csv`: one row per mode and law, fitted or not, with the criteria and the
/// choice.
pub fn write_laws(w: &mut dyn Write, fit: &AmplitudeFit) -> io::Result<()> {
    laws(w, &modal(fit))
}

/// `joint_laws.csv`: as [`write_laws`], of the joint's stiffness and damping.
pub fn write_joint_laws(w: &mut dyn Write, fit: &AmplitudeFit) -> io::Result<()> {
    laws(w, &joint(fit))
}

fn laws(w: &mut dyn Write, views: &[View]) -> io::Result<()> {
    writeln!(
        w,
        "mode,law,regime,parameters,levels,chi2_stiffness,chi2_damping,tau_stiffness,\
         tau_damping,weights_from,aicc,bic,delta_aicc,akaike_weight,converged,eligible,selected,note"
    )?;
    for m in views {
        let f = m.fit;
        let levels = m.data.len();
        for j in &f.laws {
            let l = &j.fitted;
            writeln!(
                w,
                "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
                m.mode,
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
                if j.ineligible.is_none() { "yes" } else { "no" },
                if l.law == f.selected { "yes" } else { "no" },
                j.ineligible
                    .as_deref()
                    .map_or(String::new(), |why| format!("not eligible: {why}")),
            )?;
        }
        for (law, why) in &f.skipped {
            writeln!(
                w,
                "{},{},,,{levels},,,,,,,,,,,no,no,not fitted: {why}",
                m.mode,
                law.name()
            )?;
        }
    }
    Ok(())
}

/// `amplitude_parameters.csv`: every law's parameters with standard errors, and the derived
/// Iwan quantities ([`estimates`]).
pub fn write_parameters(w: &mut dyn Write, fit: &AmplitudeFit) -> io::Result<()> {
    parameters(w, &modal(fit))
}

/// `joint_parameters.csv`: as [`write_parameters`], of the joint's laws.
pub fn write_joint_parameters(w: &mut dyn Write, fit: &AmplitudeFit) -> io::Result<()> {
    parameters(w, &joint(fit))
}

fn parameters(w: &mut dyn Write, views: &[View]) -> io::Result<()> {
    writeln!(w, "mode,law,selected,parameter,value,std")?;
    for m in views {
        for j in &m.fit.laws {
            let law = j.fitted.law;
            for e in estimates(j) {
                writeln!(
                    w,
                    "{},{},{},{},{},{}",
                    m.mode,
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
    bands(w, &modal(fit))
}

/// `joint_bands.csv`: as [`write_bands`], of the joint's laws.
pub fn write_joint_bands(w: &mut dyn Write, fit: &AmplitudeFit) -> io::Result<()> {
    bands(w, &joint(fit))
}

fn bands(w: &mut dyn Write, views: &[View]) -> io::Result<()> {
    writeln!(
        w,
        "mode,law,selected,amplitude_m,stiffness,stiffness_se,damping_ratio,damping_se"
    )?;
    for m in views {
        for (j, band) in m.fit.laws.iter().zip(&m.fit.bands) {
            let law = j.fitted.law;
            for p in band {
                writeln!(
                    w,
                    "{},{},{},{},{},{},{},{}",
                    m.mode,
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

/// The figure of one mode: modal stiffness (top) and damping ratio (bottom) against amplitude.
pub fn figure(m: &ModeResult) -> Result<String, PlotError> {
    let view = View {
        mode: m.data.mode,
        data: m.data.series(),
        fit: &m.fit,
    };
    figure_of(
        &view,
        [
            "modal stiffness",
            "modal stiffness (2 pi f)^2",
            "damping ratio",
            SENSOR_AMPLITUDE,
        ],
    )
}

/// The figure of the joint's stiffness and damping on one mode, if it has them.
pub fn joint_figure(m: &ModeResult) -> Option<Result<String, PlotError>> {
    let j = m.joint.as_ref()?;
    let view = View {
        mode: m.data.mode,
        data: j.data.series(),
        fit: &j.fit,
    };
    let name = format!("joint {}", j.data.name);
    let x = if j.data.at_joint {
        format!(
            "the joint's deformation amplitude ({})",
            deformation_unit(j.data.unit)
        )
    } else {
        SENSOR_AMPLITUDE.to_string()
    };
    Some(figure_of(
        &view,
        [&name, &name, "joint damping ratio zeta / s", &x],
    ))
}

/// The unit of a joint's deformation from the unit of its stiffness.
fn deformation_unit(stiffness: &str) -> &'static str {
    match stiffness {
        "N m/rad" => "rad",
        "N/m" => "m",
        _ => "of the parameter's pattern",
    }
}

/// Every law's curve over the amplitudes, as `shown` draws a band point (value, se); the
/// chosen law's with its band of +- [`BAND_SE`] se.
fn law_bands(fit: &ModeFit, shown: impl Fn(&BandPoint) -> (f64, f64)) -> Vec<Band> {
    fit.laws
        .iter()
        .zip(&fit.bands)
        .map(|(j, band)| {
            let chosen = j.fitted.law == fit.selected;
            let curve: Vec<(f64, f64)> = band.iter().map(&shown).collect();
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
        .collect()
}

/// `titles`: the stiffness's title, its axis's name, the damping's title, the amplitude axis.
fn figure_of(m: &View, titles: [&str; 4]) -> Result<String, PlotError> {
    let data = &m.data;
    let weights = Weights::new(data, m.fit.tau_stiffness, m.fit.tau_damping);
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
        let bands = law_bands(m.fit, |p| {
            if stiffness {
                shown(p.stiffness, p.stiffness_se)
            } else {
                shown(p.damping, p.damping_se)
            }
        });
        (series, bands)
    };
    let axes = |y: &str| LineAxes {
        x_desc: titles[3].to_string(),
        y_desc: y.to_string(),
        log_x: false,
        log_y: false,
        reference: None,
        clip_errors: false,
    };
    let mode = m.mode;
    svg((900, 900), |root| {
        let (top, bottom) = root.split_vertically(450);
        let (s, b) = panel(true);
        lines_with_bands(
            &top,
            &format!("mode {mode}: {} against amplitude", titles[0]),
            &axes(&format!(
                "{}: change from the smallest amplitude (%)",
                titles[1]
            )),
            &s,
            &b,
        )?;
        let (s, b) = panel(false);
        lines_with_bands(
            &bottom,
            &format!("mode {mode}: {} against amplitude", titles[2]),
            &axes(&format!("{} (%)", titles[2])),
            &s,
            &b,
        )
    })
}

/// A terminal summary: per mode, every law's AICc and the chosen law; then the joint's, with
/// its frequency errors before and after.
pub fn summary(fit: &AmplitudeFit) -> String {
    let mut out = String::new();
    for m in modal(fit) {
        out += &laws_summary(&m, "(rad/s)^2");
    }
    for m in &fit.modes {
        let Some(j) = &m.joint else { continue };
        let v = View {
            mode: m.data.mode,
            data: j.data.series(),
            fit: &j.fit,
        };
        out += &format!("joint {} ({}), ", j.data.name, j.data.unit);
        out += &laws_summary(&v, j.data.unit);
        let rms = |f: &dyn Fn(&crate::amplitude::LevelError) -> f64| {
            let n = j.errors.len().max(1) as f64;
            (j.errors.iter().map(|e| f(e).powi(2)).sum::<f64>() / n).sqrt()
        };
        out += &format!(
            "  frequency error over the levels (RMS): {:.4}% with the constant joint, {:.4}% with the {} joint\n",
            rms(&|e| 100.0 * (e.constant_hz / e.measured_hz - 1.0)),
            rms(&|e| 100.0 * (e.selected_hz / e.measured_hz - 1.0)),
            j.fit.selected.name()
        );
    }
    out
}

fn laws_summary(m: &View, unit: &str) -> String {
    let f = m.fit;
    let mut out = format!(
        "mode {}: {} levels, extra sd stiffness {:.4e} {unit}, damping {:.3e}; chosen: {}\n",
        m.mode,
        m.data.len(),
        f.tau_stiffness,
        f.tau_damping,
        f.selected.name()
    );
    for j in &f.laws {
        out += &format!(
            "  {:<10} k = {}  chi2 = {:>9.3}  AICc = {:>9.3}  dAICc = {:>7.3}{}\n",
            j.fitted.law.name(),
            j.k,
            j.fitted.chi2(),
            j.aicc,
            j.delta_aicc,
            j.ineligible
                .as_deref()
                .map_or(String::new(), |why| format!("  not eligible: {why}"))
        );
    }
    for (law, why) in &f.skipped {
        out += &format!("  {:<10} not fitted: {why}\n", law.name());
    }
    out
}
