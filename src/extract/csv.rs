//! The extracted modes as a measured-modes CSV (the `x,dof` form of [`crate::measured`]):
//! one row per mode and response, the real normal mode (largest component +1) as the value,
//! the damping ratio and the modal phase collinearity as the optional per-mode columns, then
//! the standard errors ([`super::uncertainty`]): `frequency_std` (Hz) and `damping_std` per
//! mode, `value_std` per row (0 at the mode's peak, which is 1 by definition). The
//! file reads back with [`crate::measured::MeasuredModes::from_path`] against a model of the
//! beam, so `jointid identify` and `jointid diagnose` take it as it is.

use std::io::Write;

use super::Mode;
use super::universal::Channel;

/// Writes `modes` (numbered 1.. in the order given) with the channel positions `x` (m).
pub fn write_modes<W: Write>(
    out: W,
    modes: &[Mode],
    channels: &[Channel],
    x: &[f64],
) -> Result<(), ::csv::Error> {
    let mut w = ::csv::Writer::from_writer(out);
    w.write_record([
        "mode",
        "frequency_hz",
        "x",
        "dof",
        "value",
        "damping_ratio",
        "mpc",
        "frequency_std",
        "damping_std",
        "value_std",
    ])?;
    for (r, m) in modes.iter().enumerate() {
        let rows = channels.iter().zip(x).zip(&m.real_shape).zip(&m.std.shape);
        for (((c, &xc), &v), &v_std) in rows {
            let dof = if c.is_rotation() { "theta" } else { "w" };
            w.write_record([
                (r + 1).to_string(),
                m.frequency_hz.to_string(),
                xc.to_string(),
                dof.to_string(),
                v.to_string(),
                m.damping_ratio.to_string(),
                m.mpc.to_string(),
                m.std.frequency_hz.to_string(),
                m.std.damping_ratio.to_string(),
                v_std.to_string(),
            ])?;
        }
    }
    w.flush()?;
    Ok(())
}
