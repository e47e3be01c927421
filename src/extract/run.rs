//! The extraction, step by step (see the module docs of [`super`]).

use std::f64::consts::PI;

use faer::c64;

use super::lscf::{self, Lscf};
use super::stabilization::{self, Chosen, Criteria, OrderPoles};
use super::uncertainty::{self, ModeStd, NoiseSource};
use super::{ExtractError, Extraction, FrfSet, Mode, Settings, frf, lsfd, refine, shapes};

fn frequency(s: c64) -> f64 {
    s.norm() / (2.0 * PI)
}

/// Whether refined poles can replace the chart's: each stays stable, in the band, below the
/// damping bound and within the frequency tolerance of its start (in |delta s| / |s|), and no
/// two merge.
fn acceptable(refined: &[c64], start: &[c64], band: (f64, f64), criteria: &Criteria) -> bool {
    let each = refined.iter().zip(start).all(|(r, s)| {
        let f = frequency(*r);
        r.re < 0.0
            && r.im > 0.0
            && f >= band.0
            && f <= band.1
            && -r.re / r.norm() < criteria.max_damping
            && (r - s).norm() < criteria.frequency_tolerance * s.norm()
    });
    let distinct = refined.iter().enumerate().all(|(i, a)| {
        refined[i + 1..]
            .iter()
            .all(|b| (a - b).norm() > 1e-9 * a.norm())
    });
    each && distinct
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

/// Whether `found` chains are enough: at least one, and the modes `settings` asks for.
fn enough_modes(
    found: usize,
    settings: &Settings,
    criteria: &Criteria,
    (lo, hi): (f64, f64),
) -> Result<(), ExtractError> {
    if found == 0 {
        return Err(ExtractError::NoModes {
            lo,
            hi,
            min_stable: criteria.min_stable,
            max_order: settings.max_order,
        });
    }
    if let Some(requested) = settings.n_modes
        && found < requested
    {
        return Err(ExtractError::TooFewModes {
            requested,
            found,
            min_stable: criteria.min_stable,
            lo,
            hi,
        });
    }
    Ok(())
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

/// The modes of the chosen chains with their final poles, residues and standard errors,
/// ascending in frequency.
fn modes_of(
    chosen: &[Chosen],
    poles: &[c64],
    residues: &[Vec<c64>],
    std: Vec<ModeStd>,
) -> Vec<Mode> {
    let mut modes: Vec<Mode> = chosen
        .iter()
        .zip(poles)
        .zip(residues)
        .zip(std)
        .map(|(((c, &pole), residues), std)| {
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
                stable_orders: c.orders,
                stable_count: c.stable_count,
                std,
            }
        })
        .collect();
    modes.sort_by(|a, b| a.frequency_hz.total_cmp(&b.frequency_hz));
    modes
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
/// called after each response of the reduction, each model order and at the end.
pub fn extract(
    frf: &FrfSet,
    settings: &Settings,
    progress: &dyn Fn(usize, usize),
) -> Result<Extraction, ExtractError> {
    let band = checked_band(frf, settings)?;
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
    let mut chart = stabilization::classify(&orders, &criteria);
    let residue_refs: Vec<&[c64]> = orders
        .iter()
        .flat_map(|o| o.residues.iter().map(|r| r.as_slice()))
        .collect();
    let chosen = stabilization::choose(&mut chart, &residue_refs, &criteria, settings.n_modes);
    enough_modes(chosen.len(), settings, &criteria, (lo, hi))?;

    let start: Vec<c64> = chosen.iter().map(|c| chart[c.pole].pole).collect();
    let (poles, refined) =
        final_poles(&omega, &band, start, basis, &responses, &criteria, settings);
    let ls = lsfd::least_squares(&omega, &band.weights, &poles, basis, &responses);
    let fit = lsfd::unpack(&ls.x, poles.len(), basis, ls.rank);
    let synthesized = lsfd::synthesize(&omega, &poles, basis, &fit);
    let fit_error = relative_errors(&responses, &synthesized);
    let (noise, variances) = line_variances(
        frf,
        settings,
        &band,
        &responses,
        &synthesized,
        basis,
        poles.len(),
    );
    let std = uncertainty::standard_errors(&omega, &band.weights, &poles, basis, &ls, &variances);
    let modes = modes_of(&chosen, &poles, &fit.residues, std);
    let mean_coherence = frf.coherence.as_ref().map(|c| {
        c.iter()
            .map(|r| band.lines.iter().map(|&k| r[k]).sum::<f64>() / band.lines.len() as f64)
            .collect()
    });
    progress(total, total);
    Ok(Extraction {
        modes,
        chart,
        criteria,
        max_order,
        band_hz: (lo, hi),
        frequencies_hz,
        lines: band.lines,
        synthesized,
        fit_error,
        lower_residual: fit.lower,
        upper_residual: fit.upper,
        mean_coherence,
        refined,
        noise,
    })
}

/// The poles the modes are given with: the chart's `start` refined when the settings ask for
/// it and the refined poles are [`acceptable`], else `start`; and whether they were refined.
fn final_poles(
    omega: &[f64],
    band: &frf::Band,
    start: Vec<c64>,
    basis: lsfd::Basis,
    responses: &[Vec<c64>],
    criteria: &Criteria,
    settings: &Settings,
) -> (Vec<c64>, bool) {
    if !settings.refine {
        return (start, false);
    }
    let r = refine::refine(omega, &band.weights, &start, basis, responses);
    if acceptable(&r.poles, &start, (band.lo, band.hi), criteria) {
        (r.poles, true)
    } else {
        (start, false)
    }
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
