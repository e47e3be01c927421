//! The extracted modes as a measured-modes CSV (the `x,dof` form of [`crate::measured`]):
//! one row per mode and response, the real normal mode (largest component +1) as the value,
//! the damping ratio and the modal phase collinearity as the optional per-mode columns, then
//! the standard errors ([`super::uncertainty`]): `frequency_std` (Hz) and `damping_std` per
//! mode, `value_std` per row (0 at the mode's peak, which is 1 by definition). The
//! file reads back with [`crate::measured::MeasuredModes::from_path`] against a model of the
//! beam, so `jointid identify` and `jointid diagnose` take it as it is. A positive standard
//! error below the floor of [`RELATIVE_STD`] (1e-12 of the frequency, the damping ratio, the
//! peak) is written at that floor: it is below what the estimate's own rounding resolves
//! (noise-free FRFs give 1e-17 of the frequency), and the reader refuses less.

use std::io::Write;

use super::Mode;
use super::universal::Channel;
use crate::input::RELATIVE_STD;

/// Writes `modes` (numbered 1.. in the order given) with the channel positions `x` (m).
pub fn write_modes<W: Write>(
    out: W,
    modes: &[Mode],
    channels: &[Channel],
    x: &[f64],
) -> Result<(), ::csv::Error> {
    let point = |o: usize| {
        let dof = if channels[o].is_rotation() {
            "theta"
        } else {
            "w"
        };
        vec![x[o].to_string(), dof.to_string()]
    };
    write_rows(out, modes, channels.len(), &["x", "dof"], &point)
}

/// Writes `modes` with rows by coordinates in space (`x,y,z,dof`, the form of a measured
/// file for an external model): the channel nodes' coordinates `xyz` (as the geometry gives
/// them) and the response direction (x, y, z, rx, ry, rz).
pub fn write_modes_in_space<W: Write>(
    out: W,
    modes: &[Mode],
    channels: &[Channel],
    xyz: &[[f64; 3]],
) -> Result<(), ::csv::Error> {
    let point = |o: usize| {
        let names = ["x", "y", "z", "rx", "ry", "rz"];
        let dof = names[(channels[o].direction.unsigned_abs() as usize).clamp(1, 6) - 1];
        let mut row: Vec<String> = xyz[o].iter().map(f64::to_string).collect();
        row.push(dof.to_string());
        row
    };
    write_rows(out, modes, channels.len(), &["x", "y", "z", "dof"], &point)
}

/// The rows of `modes` over `responses` responses, located by `point(response)` under the
/// header fields `location`.
fn write_rows<W: Write>(
    out: W,
    modes: &[Mode],
    responses: usize,
    location: &[&str],
    point: &dyn Fn(usize) -> Vec<String>,
) -> Result<(), ::csv::Error> {
    let mut w = ::csv::Writer::from_writer(out);
    let mut head = vec!["mode", "frequency_hz"];
    head.extend(location);
    head.extend([
        "value",
        "damping_ratio",
        "mpc",
        "frequency_std",
        "damping_std",
        "value_std",
    ]);
    w.write_record(&head)?;
    // A positive error, at least the floor of the relative errors times `scale`.
    let floored = |std: f64, scale: f64| {
        if std > 0.0 {
            std.max(RELATIVE_STD.0 * scale)
        } else {
            std
        }
    };
    for (r, m) in modes.iter().enumerate() {
        let rows = m.real_shape.iter().zip(&m.std.shape).take(responses);
        let peak = m
            .real_shape
            .iter()
            .take(responses)
            .fold(0.0_f64, |a, v| a.max(v.abs()));
        for (o, (&v, &v_std)) in rows.enumerate() {
            let mut row = vec![(r + 1).to_string(), m.frequency_hz.to_string()];
            row.extend(point(o));
            row.extend([
                v.to_string(),
                m.damping_ratio.to_string(),
                m.mpc.to_string(),
                floored(m.std.frequency_hz, m.frequency_hz).to_string(),
                floored(m.std.damping_ratio, m.damping_ratio).to_string(),
                floored(v_std, peak).to_string(),
            ]);
            w.write_record(&row)?;
        }
    }
    w.flush()?;
    Ok(())
}
