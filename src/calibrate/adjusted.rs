//! The calibrated model file: the user's model file with each calibrated beam's values
//! multiplied by what the calibration found since they were typed, and the record of it in
//! `[beam.calibrated]` (module `model::chain::calibration`), which identify, diagnose and
//! study read as any model file. Everything else is the user's, key for key (comments are not
//! kept: the file is written anew).

use crate::model::chain::{BeamCalibration, Factor};

/// Why the calibrated model cannot be written.
#[derive(Debug, thiserror::Error)]
#[error("the model file cannot be rewritten: {0}")]
pub struct AdjustError(String);

/// The model `text` (a chain model file, valid) with the beams of `records` at their
/// calibrated values; `earlier` are the records the file had, whose factors `records` include.
pub fn adjusted_model(
    text: &str,
    records: &[BeamCalibration],
    earlier: &[BeamCalibration],
    header: &str,
) -> Result<String, AdjustError> {
    let mut table: toml::Table = text.parse().map_err(|e| AdjustError(format!("{e}")))?;
    let beams = table
        .get_mut("beam")
        .and_then(toml::Value::as_array_mut)
        .ok_or_else(|| AdjustError("no [[beam]] array".into()))?;
    for record in records {
        let beam = beams
            .get_mut(record.beam)
            .and_then(toml::Value::as_table_mut)
            .ok_or_else(|| AdjustError(format!("no beam[{}]", record.beam)))?;
        let before = earlier.iter().find(|c| c.beam == record.beam);
        let change = |new: Option<Factor>, old: Option<Factor>| {
            new.map_or(1.0, |n| n.value) / old.map_or(1.0, |o| o.value)
        };
        let stiffness = change(record.stiffness, before.and_then(|c| c.stiffness));
        let density = change(record.density, before.and_then(|c| c.density));
        scale_keys(beam, &["youngs_modulus", "shear_modulus"], stiffness);
        scale_keys(beam, &["density"], density);
        if let Some(segments) = beam.get_mut("segment").and_then(toml::Value::as_array_mut) {
            for segment in segments.iter_mut().filter_map(toml::Value::as_table_mut) {
                scale_keys(segment, &["youngs_modulus"], stiffness);
                scale_keys(segment, &["density"], density);
            }
        }
        beam.insert(
            "calibrated".into(),
            toml::Value::Table(record_table(record)),
        );
    }
    let body = toml::to_string(&table).map_err(|e| AdjustError(format!("{e}")))?;
    let comment: String = header.lines().map(|l| format!("# {l}\n")).collect();
    Ok(format!("{comment}\n{body}"))
}

/// Multiplies the float values of `keys` in `table` by `factor`.
fn scale_keys(table: &mut toml::Table, keys: &[&str], factor: f64) {
    for key in keys {
        if let Some(v) = table.get_mut(*key) {
            let x = v.as_float().or_else(|| v.as_integer().map(|i| i as f64));
            if let Some(x) = x {
                *v = toml::Value::Float(x * factor);
            }
        }
    }
}

/// `[beam.calibrated]` of `record`.
fn record_table(record: &BeamCalibration) -> toml::Table {
    let mut t = toml::Table::new();
    for (name, factor) in [
        ("stiffness_factor", record.stiffness),
        ("density_factor", record.density),
    ] {
        if let Some(f) = factor {
            t.insert(name.into(), toml::Value::Float(f.value));
            t.insert(format!("{name}_se"), toml::Value::Float(f.se));
        }
    }
    if let Some(r) = &record.reference {
        t.insert("reference".into(), toml::Value::String(r.clone()));
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    const MODEL: &str = r#"
[[beam]]
length = 0.2
elements = 7
youngs_modulus = 2.1e11
density = 7850.0
area = 2.4e-3
second_moment = 3.2e-7
shear_factor = 0.85
shear_modulus = 8e10
[[beam.segment]]
from = 0.1
to = 0.2
youngs_modulus = 2e11
area = 4.8e-3

[[beam]]
length = 0.3
elements = 10
youngs_modulus = 210000000000
density = 7850
area = 2.4e-3
second_moment = 3.2e-7

[[joint]]
k1 = 1e7
k2 = 1e4
"#;

    #[test]
    fn the_calibrated_file_reads_back_with_the_calibrated_values_and_its_record() {
        let records = [BeamCalibration {
            beam: 0,
            stiffness: Some(Factor {
                value: 0.97,
                se: 0.004,
            }),
            density: None,
            reference: Some("mono.csv".into()),
        }];
        let text = adjusted_model(MODEL, &records, &[], "calibrated").unwrap();
        let file = std::path::Path::new("adjusted.toml");
        let chain = crate::model::chain_from_toml(&text, file).unwrap();
        let b = &chain.beams[0];
        assert_eq!(b.youngs_modulus, 2.1e11 * 0.97);
        assert_eq!(b.shear.unwrap().modulus, 8e10 * 0.97);
        assert_eq!(b.segments[0].section.youngs_modulus, 2e11 * 0.97);
        assert_eq!(b.density, 7850.0);
        assert_eq!(chain.beams[1].youngs_modulus, 2.1e11);
        assert_eq!(chain.calibration, records.to_vec());
        assert!(text.starts_with("# calibrated\n"));
        // A second calibration composes: the file holds the product, the values follow it.
        let again = [BeamCalibration {
            stiffness: Some(Factor {
                value: 0.97 * 1.01,
                se: 0.003,
            }),
            ..records[0].clone()
        }];
        let text = adjusted_model(&text, &again, &chain.calibration, "again").unwrap();
        let twice = crate::model::chain_from_toml(&text, file).unwrap();
        let e = twice.beams[0].youngs_modulus;
        assert!((e - 2.1e11 * 0.97 * 1.01).abs() <= 1e-15 * e);
        let typed = twice.typed();
        assert!((typed.beams[0].youngs_modulus - 2.1e11).abs() <= 1e-15 * 2.1e11);
    }
}
