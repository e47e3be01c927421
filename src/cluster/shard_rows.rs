//! The result rows of a shard file, checked one by one before a merge: every field of the
//! study's result schema ([`crate::study::results`]) parsed, numbers finite, the cell's keys
//! the same on every row of a cell, each (mode, parameter) once; and the content hash of the
//! rows ([`rows_hash`]) that the shard's header carries, so that a row changed, dropped,
//! reordered or cut after the shard was written is found even when it still parses.
//!
//! Part of [`crate::cluster`]: imports [`crate::study`] (the schema and the hash function).

use std::collections::BTreeMap;

use crate::study::fingerprint::{FNV_OFFSET, fnv1a};
use crate::study::results::Column;

/// The content hash of a shard's rows: the 64-bit FNV-1a hash of the bytes after the `#`
/// header (the column line and every row), as 16 hexadecimal digits.
pub fn rows_hash(bytes: &[u8]) -> String {
    format!("{:016x}", fnv1a(FNV_OFFSET, bytes))
}

/// What a row is, once checked: its cell and its place in the cell (the positions of its
/// mode and parameter in the header's lists), by which a merge orders the rows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub struct RowKey {
    /// Cell index.
    pub cell: usize,
    /// Position of the row's mode in the header's `modes`.
    pub mode: usize,
    /// Position of the row's parameter in the header's `params`.
    pub param: usize,
}

/// The columns every row of one cell states alike: its conditions (`n` to `noise`), its
/// trials and its unidentified DOFs.
fn cell_keys() -> Vec<Column> {
    Column::ALL[Column::N.index()..=Column::Noise.index()]
        .iter()
        .copied()
        .chain([Column::Trials, Column::Unidentified])
        .collect()
}

/// The statistics that exist when a trial succeeded (`mean` to `bias_se` and `median_se`;
/// `relative_bias` may still be empty).
fn statistics() -> impl Iterator<Item = Column> {
    Column::ALL[Column::Mean.index()..=Column::BiasSe.index()]
        .iter()
        .copied()
        .filter(|&c| c != Column::RelativeBias)
        .chain([Column::MedianSe])
}

fn text(record: &csv::StringRecord, column: Column) -> &str {
    record.get(column.index()).unwrap_or("")
}

fn whole(record: &csv::StringRecord, column: Column) -> Result<usize, String> {
    let t = text(record, column);
    t.parse().map_err(|_| {
        format!(
            "{} = {} is not a whole number",
            column.name(),
            crate::input::safe::quoted(t)
        )
    })
}

fn finite(record: &csv::StringRecord, column: Column, required: bool) -> Result<(), String> {
    let t = text(record, column);
    if t.is_empty() && !required {
        return Ok(());
    }
    match t.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(()),
        _ => Err(format!(
            "{} = {} is not a finite number",
            column.name(),
            crate::input::safe::quoted(t)
        )),
    }
}

/// Checks one row against the shard's `cells`, `modes` and `params`; its key, or what is
/// wrong with it.
pub fn check_row(
    record: &csv::StringRecord,
    cells: usize,
    modes: &[usize],
    params: &[String],
) -> Result<RowKey, String> {
    let cell = whole(record, Column::Cell)?;
    if cell >= cells {
        return Err(format!(
            "cell = {cell} is invalid: it must be a cell index below {cells}"
        ));
    }
    let mode = whole(record, Column::Mode)?;
    let mode = modes.iter().position(|&m| m == mode).ok_or_else(|| {
        format!("mode = {mode} is not a mode of the study (the header lists {modes:?})")
    })?;
    let name = text(record, Column::Param);
    let param = params.iter().position(|p| p == name).ok_or_else(|| {
        format!(
            "param = {} is not a parameter of the study ({})",
            crate::input::safe::quoted(name),
            params.join(", ")
        )
    })?;
    for column in [Column::N, Column::M, Column::Nf] {
        whole(record, column)?;
    }
    for column in [Column::Weighting, Column::Noise] {
        if text(record, column).is_empty() {
            return Err(format!("{} is empty", column.name()));
        }
    }
    for column in [
        Column::ShapeNoise,
        Column::FrequencyNoise,
        Column::Introduced,
    ] {
        finite(record, column, true)?;
    }
    let trials = whole(record, Column::Trials)?;
    let failures = whole(record, Column::Failures)?;
    if failures > trials {
        return Err(format!(
            "failures = {failures} is more than trials = {trials}"
        ));
    }
    let succeeded = failures < trials;
    if succeeded == text(record, Column::Mean).is_empty() {
        return Err(format!(
            "mean is {} although {failures} of {trials} trials failed",
            if succeeded { "empty" } else { "given" }
        ));
    }
    for column in statistics() {
        finite(record, column, succeeded)?;
    }
    for column in [Column::RelativeBias, Column::PredictedStd] {
        finite(record, column, false)?;
    }
    Ok(RowKey { cell, mode, param })
}

/// The rows of every cell seen so far: the first row's line and cell keys, and the keys of
/// its rows, so that a cell whose rows disagree, or a row given twice, is found.
#[derive(Debug, Default)]
pub struct CellRows {
    seen: BTreeMap<usize, (u64, Vec<String>, Vec<RowKey>)>,
}

impl CellRows {
    /// Records the row at `line` with `key`; what is wrong when it disagrees with an earlier
    /// row of its cell or repeats one.
    pub fn add(
        &mut self,
        key: RowKey,
        record: &csv::StringRecord,
        line: u64,
    ) -> Result<(), String> {
        let columns = cell_keys();
        let keys: Vec<String> = columns
            .iter()
            .map(|&c| text(record, c).to_string())
            .collect();
        let (first, first_keys, rows) = self
            .seen
            .entry(key.cell)
            .or_insert_with(|| (line, keys.clone(), Vec::new()));
        if let Some(i) = (0..columns.len()).find(|&i| keys[i] != first_keys[i]) {
            return Err(format!(
                "{} = {} but line {first} of cell {} has {}: the rows of a cell must state the same conditions",
                columns[i].name(),
                crate::input::safe::quoted(&keys[i]),
                key.cell,
                crate::input::safe::quoted(&first_keys[i])
            ));
        }
        if rows.contains(&key) {
            return Err(format!(
                "cell {}, mode {}, parameter {} appears twice",
                key.cell,
                text(record, Column::Mode),
                text(record, Column::Param)
            ));
        }
        rows.push(key);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ROW: &str =
        "0,1,k1,7,5,0,equal,0.04,0,uniform,2000000,100,0,1.5,0.5,0.25,1,1,1,1,0,0,2,2,0.1,,0.2,";

    fn record(text: &str) -> csv::StringRecord {
        csv::StringRecord::from(text.split(',').collect::<Vec<_>>())
    }

    fn check(text: &str) -> Result<RowKey, String> {
        check_row(&record(text), 2, &[1, 2], &["k1".into(), "k2".into()])
    }

    #[test]
    fn a_valid_row_gives_its_key_and_every_fault_is_named() {
        assert_eq!(
            check(ROW),
            Ok(RowKey {
                cell: 0,
                mode: 0,
                param: 0
            })
        );
        for (from, to, says) in [
            ("0,1,k1", "2,1,k1", "cell = 2 is invalid"),
            ("0,1,k1", "0,3,k1", "mode = 3 is not a mode"),
            ("0,1,k1", "0,1,k9", "param = `k9` is not a parameter"),
            (",1.5,", ",NaN,", "mean = `NaN` is not a finite number"),
            (",0.2,", ",inf,", "median_se = `inf` is not a finite number"),
            (
                ",100,0,",
                ",100,101,",
                "failures = 101 is more than trials = 100",
            ),
            (
                ",1.5,",
                ",,",
                "mean is empty although 0 of 100 trials failed",
            ),
            ("equal", "", "weighting is empty"),
            (",7,5,", ",7.5,5,", "n = `7.5` is not a whole number"),
        ] {
            let bad = ROW.replacen(from, to, 1);
            let e = check(&bad).unwrap_err();
            assert!(e.starts_with(says), "{bad}: {e}");
        }
    }

    #[test]
    fn the_rows_of_a_cell_agree_and_none_repeats() {
        let mut cells = CellRows::default();
        let r = record(ROW);
        cells.add(check(ROW).unwrap(), &r, 10).unwrap();
        let e = cells.add(check(ROW).unwrap(), &r, 11).unwrap_err();
        assert_eq!(e, "cell 0, mode 1, parameter k1 appears twice");
        let other = ROW.replacen("0,1,k1,7", "0,1,k2,8", 1);
        let e = cells
            .add(check(&other).unwrap(), &record(&other), 12)
            .unwrap_err();
        assert_eq!(
            e,
            "n = `8` but line 10 of cell 0 has `7`: the rows of a cell must state the same conditions"
        );
    }
}
