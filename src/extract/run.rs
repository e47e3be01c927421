//! The extraction, step by step (see the module docs of [`super`]).

use std::f64::consts::PI;

use faer::c64;

use super::choice::{self, Decision, Rules};
use super::excitation::{self, BandSource, EdgeNote};
use super::final_fit::{Problem, fit_kept};
use super::lscf::{self, Lscf};
use super::stabilization::{self, ChartPole, Criteria, OrderPoles};
use super::uncertainty::{self, ModeStd, NoiseSource};
use super::{ExtractError, Extraction, FrfSet, Mode, Settings, frf, lsfd, shapes};

fn frequency(s: c64) -> f64 {
    s.norm() / (2.0 * PI)
}

/// The RMS of `h`; computed relative to its largest magnitude when the plain sum of squares
/// overflows or underflows (FRFs scaled by 1e150 or 1e-170 are not zero).
fn rms_of(h: &[c64]) -> f64 {
    let plain = (h.iter().map(|v| v.norm_sqr()).sum::<f64>() / h.len() as f64).sqrt();
    if plain > 0.0 && plain.is_finite() {
        return plain;
    }
    let peak = h.iter().map(|v| v.norm()).fold(0.0_f64, f64::max);
    if peak == 0.0 || !peak.is_finite() {
        return peak;
    }
    peak * (h.iter().map(|v| (v / peak).norm_sqr()).sum::<f64>() / h.len() as f64).sqrt()
}

/// The responses scaled to unit RMS over the band (`lo`, `hi` in Hz, for the error).
fn unit_rms(responses: &[Vec<c64>], (lo, hi): (f64, f64)) -> Result<Vec<Vec<c64>>, ExtractError> {
    let mut scaled = Vec::with_capacity(responses.len());
    for (response, h) in responses.iter().enumerate() {
        let rms = rms_of(h);
        if rms == 0.0 || !rms.is_finite() {
            return Err(ExtractError::ZeroResponse { response, lo, hi });
        }
        scaled.push(h.iter().map(|v| v / rms).collect::<Vec<c64>>());
    }
    Ok(scaled)
}

/// The poles of model order `order`: positive frequency, stable, in the band (`lo`, `hi` in
/// Hz), ascending in |s|.
fn band_poles(lscf: &Lscf, order: usize, (lo, hi): (f64, f64)) -> Vec<c64> {
    let alpha = lscf.denominator(order);
    let mut poles: Vec<c64> = lscf::poles(&alpha, lscf.dt)
        .into_iter()
        .filter(|s| {
            let fs = frequency(*s);
            s.im > 0.0 && s.re < 0.0 && fs >= lo && fs <= hi
        })
        .collect();
    poles.sort_by(|a, b| a.norm().total_cmp(&b.norm()));
    poles
}

/// ||H - H_model|| / ||H|| of every response over the band.
fn relative_errors(responses: &[Vec<c64>], synthesized: &[Vec<c64>]) -> Vec<f64> {
    responses
        .iter()
        .zip(synthesized)
        .map(|(h, m)| {
            let num: f64 = h.iter().zip(m).map(|(a, b)| (a - b).norm_sqr()).sum();
            let den: f64 = h.iter().map(|a| a.norm_sqr()).sum();
            (num / den).sqrt()
        })
        .collect()
}

/// The modes of the kept decisions (the first `poles.len()` of `kept`, in the order of the
/// poles) with their final poles, residues and standard errors.
fn modes_of(
    kept: &[Decision],
    poles: &[c64],
    residues: &[Vec<c64>],
    std: Vec<ModeStd>,
) -> Vec<Mode> {
    kept.iter()
        .zip(poles)
        .zip(residues)
        .zip(std)
        .map(|(((d, &pole), residues), std)| {
            let real = shapes::real_mode(residues);
            Mode {
                frequency_hz: frequency(pole),
                damping_ratio: -pole.re / pole.norm(),
                pole,
                residues: residues.clone(),
                complex_shape: shapes::complex_unit_peak(residues),
                real_shape: real.shape,
                mpc: real.mpc,
                mpd_deg: real.mpd_deg,
                stable_orders: d.stable_orders,
                stable_count: d.stable_count,
                std,
            }
        })
        .collect()
}

/// The settings and the FRFs checked, and the analysis band, which must hold enough lines for
/// the highest model order.
fn checked_band(frf: &FrfSet, settings: &Settings) -> Result<frf::Band, ExtractError> {
    settings.check().map_err(ExtractError::Setting)?;
    frf.validate()?;
    if let (Some(averages), None) = (settings.averages, &frf.coherence) {
        return Err(ExtractError::AveragesWithoutCoherence { averages });
    }
    let band = frf::band(frf, settings)?;
    let max_order = settings.max_order;
    let needed = 2 * (max_order + 1);
    if band.lines.len() < needed {
        return Err(ExtractError::TooFewLines {
            lines: band.lines.len(),
            needed,
            max_order,
        });
    }
    Ok(band)
}

/// The rules of the automatic choice.
fn rules_of(settings: &Settings) -> Rules {
    Rules {
        mpc_min: settings.mpc_min,
        low_order_share: settings.low_order_share,
        max_order: settings.max_order,
    }
}

/// The thresholds of the chart and of the choice.
fn criteria_of(settings: &Settings) -> Criteria {
    Criteria {
        frequency_tolerance: settings.frequency_tolerance,
        damping_tolerance: settings.damping_tolerance,
        mac_min: settings.mac_min,
        min_stable: settings
            .min_stable
            .unwrap_or_else(|| stabilization::min_stable_default(settings.max_order)),
        max_damping: settings.max_damping,
    }
}

/// Extracts the modes of `frf` (see the module docs of [`super`]). `progress(done, total)` is
/// called after each response of the reduction, each model order and at the end (a band
/// extended for the modes' margins starts the count again).
pub fn extract(
    frf: &FrfSet,
    settings: &Settings,
    progress: &dyn Fn(usize, usize),
) -> Result<Extraction, ExtractError> {
    let band = checked_band(frf, settings)?;
    if band.source == BandSource::Given {
        return extract_in(frf, settings, band, progress)
            .map(|ex| with_edges(ex, settings, data_band(frf), None));
    }
    let first = extract_in(frf, settings, band.clone(), progress)?;
    let kept: Vec<(f64, f64)> = first
        .modes
        .iter()
        .map(|m| (m.frequency_hz, m.damping_ratio))
        .collect();
    let data = data_band(frf);
    let Some((lo, hi)) = excitation::extended(first.band_hz, &kept, settings.edge_margin, data)
    else {
        return Ok(with_edges(first, settings, data, None));
    };
    let wider = frf::band_of(frf, (lo, hi), band.source);
    let from = Some(first.band_hz);
    match extract_in(frf, settings, wider, progress) {
        Ok(ex) => Ok(with_edges(ex, settings, data, from)),
        Err(_) => Ok(with_edges(first, settings, data, None)),
    }
}

/// The first and last lines above 0 Hz of the data (Hz).
fn data_band(frf: &FrfSet) -> (f64, f64) {
    let f = &frf.frequencies_hz;
    let first = f.iter().copied().find(|&x| x > 0.0).unwrap_or(f[0]);
    (first, f[f.len() - 1])
}

/// The extraction with every decision's margins to the band's edges and, for a kept mode
/// short of `settings.edge_margin`, why the band does not give it more; `data`: the first and
/// last lines above 0 Hz; `extended_from`: the automatic band before its extension.
fn with_edges(
    mut ex: Extraction,
    settings: &Settings,
    data: (f64, f64),
    extended_from: Option<(f64, f64)>,
) -> Extraction {
    let (lo, hi) = ex.band_hz;
    for d in &mut ex.decisions {
        let bandwidth = 2.0 * d.damping_ratio * d.frequency_hz;
        d.margins = (
            (d.frequency_hz - lo) / bandwidth,
            (hi - d.frequency_hz) / bandwidth,
        );
        let short = d.margins.0.min(d.margins.1) < settings.edge_margin;
        let note = match (ex.band_source, extended_from) {
            (BandSource::Given, _) => EdgeNote::BandGiven,
            (_, Some(_)) => EdgeNote::ExtendedOnce,
            _ => EdgeNote::DataEnd {
                edge_hz: if d.margins.0 < d.margins.1 {
                    data.0
                } else {
                    data.1
                },
            },
        };
        d.edge = (short && d.mode.is_some()).then_some(note);
    }
    ex.extended_from = extended_from;
    ex
}

/// The stabilisation chart of `orders` and the choice made on it.
struct Charted {
    chart: Vec<ChartPole>,
    decisions: Vec<Decision>,
    weak_chains: usize,
}

/// Classifies the poles of `orders`, gathers their chains and chooses the modes among them.
fn charted(
    orders: &[OrderPoles],
    criteria: &Criteria,
    rules: &Rules,
    n_modes: Option<usize>,
) -> Charted {
    let mut chart = stabilization::classify(orders, criteria);
    let residues: Vec<&[c64]> = orders
        .iter()
        .flat_map(|o| o.residues.iter().map(|r| r.as_slice()))
        .collect();
    let chains = stabilization::chains(&chart);
    let weak_chains = chains
        .iter()
        .filter(|c| c.stable_count < criteria.min_stable)
        .count();
    let decisions = choice::choose(&mut chart, &chains, &residues, criteria, rules, n_modes);
    Charted {
        chart,
        decisions,
        weak_chains,
    }
}

/// The extraction in `band` (see [`extract`]), without the edges' margins.
fn extract_in(
    frf: &FrfSet,
    settings: &Settings,
    band: frf::Band,
    progress: &dyn Fn(usize, usize),
) -> Result<Extraction, ExtractError> {
    let max_order = settings.max_order;
    let f = &frf.frequencies_hz;
    let frequencies_hz: Vec<f64> = band.lines.iter().map(|&k| f[k]).collect();
    let omega: Vec<f64> = frequencies_hz.iter().map(|x| 2.0 * PI * x).collect();
    let (lo, hi) = (band.lo, band.hi);
    let responses: Vec<Vec<c64>> = frf
        .responses
        .iter()
        .map(|h| band.lines.iter().map(|&k| h[k]).collect())
        .collect();
    let scaled = unit_rms(&responses, (lo, hi))?;
    let basis = lsfd::Basis {
        power: frf.quantity.power(),
        terms: settings.residual_terms,
    };
    let total = responses.len() + max_order + 1;
    let mut done = 0;
    let lscf = Lscf::new(&omega, &band.weights, &scaled, hi, max_order, &mut || {
        done += 1;
        progress(done, total);
    });
    drop(scaled);

    let mut orders = Vec::with_capacity(max_order);
    for order in 1..=max_order {
        let poles = band_poles(&lscf, order, (lo, hi));
        let residues = if poles.is_empty() {
            Vec::new()
        } else {
            lsfd::fit(&omega, &band.weights, &poles, basis, &responses).residues
        };
        orders.push(OrderPoles {
            order,
            poles,
            residues,
        });
        done += 1;
        progress(done, total);
    }

    let criteria = criteria_of(settings);
    let rules = rules_of(settings);
    let Charted {
        mut chart,
        decisions,
        weak_chains,
    } = charted(&orders, &criteria, &rules, settings.n_modes);
    let problem = Problem {
        omega: &omega,
        band: &band,
        basis,
        responses: &responses,
        criteria: &criteria,
        settings,
    };
    let fitted = fit_kept(&problem, &mut chart, decisions)?;
    let mean_coherence = frf.coherence.as_ref().map(|c| {
        c.iter()
            .map(|r| band.lines.iter().map(|&k| r[k]).sum::<f64>() / band.lines.len() as f64)
            .collect()
    });
    let (noise, variances) = line_variances(
        frf,
        settings,
        &band,
        &responses,
        &fitted.synthesized,
        basis,
        fitted.poles.len(),
    );
    let std = uncertainty::standard_errors(
        &omega,
        &band.weights,
        &fitted.poles,
        basis,
        &fitted.ls,
        &variances,
    );
    let mut modes = modes_of(&fitted.decisions, &fitted.poles, &fitted.fit.residues, std);
    modes.sort_by(|a, b| a.frequency_hz.total_cmp(&b.frequency_hz));
    let decisions = choice::number_kept(&mut chart, fitted.decisions);
    progress(total, total);
    Ok(Extraction {
        modes,
        chart,
        criteria,
        rules,
        requested: settings.n_modes,
        edge_margin: settings.edge_margin,
        decisions,
        weak_chains,
        max_order,
        band_hz: (lo, hi),
        band_source: band.source,
        extended_from: None,
        frequencies_hz,
        lines: band.lines,
        fit_error: relative_errors(&responses, &fitted.synthesized),
        synthesized: fitted.synthesized,
        lower_residual: fitted.fit.lower,
        upper_residual: fitted.fit.upper,
        mean_coherence,
        refined: fitted.refined,
        noise,
    })
}

/// The noise of every line of the band (see [`uncertainty`]): from the coherence when the
/// number of averages is given, else, or when a response's coherence is 1 over the whole band,
/// from the residuals of the fit `synthesized`.
fn line_variances(
    frf: &FrfSet,
    settings: &Settings,
    band: &frf::Band,
    responses: &[Vec<c64>],
    synthesized: &[Vec<c64>],
    basis: lsfd::Basis,
    poles: usize,
) -> (NoiseSource, Vec<Vec<f64>>) {
    let residuals = |source| {
        let unknowns = basis.width(poles) as f64 + 2.0 * poles as f64 / responses.len() as f64;
        let v = uncertainty::from_residuals(&band.weights, responses, synthesized, unknowns);
        (source, v)
    };
    let (Some(averages), Some(coherence)) = (settings.averages, &frf.coherence) else {
        return residuals(NoiseSource::Residuals);
    };
    let in_band: Vec<Vec<f64>> = coherence
        .iter()
        .map(|c| band.lines.iter().map(|&k| c[k]).collect())
        .collect();
    if let Some(response) = in_band.iter().position(|g| g.iter().all(|&g| g >= 1.0)) {
        return residuals(NoiseSource::ResidualsCoherenceOne { response });
    }
    (
        NoiseSource::Coherence { averages },
        uncertainty::from_coherence(responses, &in_band, averages),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_response_scaled_far_from_one_is_not_zero() {
        let h: Vec<c64> = (0..50).map(|k| c64::new(1.0 + k as f64, -0.5)).collect();
        let unit = unit_rms(std::slice::from_ref(&h), (1.0, 2.0)).unwrap();
        for scale in [1e-170, 1e-300, 1e150, 1e300] {
            let far: Vec<c64> = h.iter().map(|v| v * scale).collect();
            let got = unit_rms(&[far], (1.0, 2.0)).unwrap();
            for (a, b) in got[0].iter().zip(&unit[0]) {
                assert!((a - b).norm() < 1e-12, "{scale}: {a} vs {b}");
            }
        }
        let zero = vec![c64::new(0.0, 0.0); 5];
        assert!(matches!(
            unit_rms(&[zero], (1.0, 2.0)),
            Err(ExtractError::ZeroResponse { response: 0, .. })
        ));
    }
}
