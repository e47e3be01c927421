//! Merging shard files into the result CSV of the whole study.
//!
//! Every shard file was checked row by row when read ([`super::shard_file`]: its rows hash,
//! every field parsed, numbers finite, a cell's rows agreeing). Then, in order, before anything
//! is produced: every file carries the same fingerprint and the same N, assignment, modes and
//! parameters; no cell is in two files; every cell of the study is in some file, with `rows
//! per cell` rows, in the shard the assignment gives it. The output is the header and the rows
//! of every cell in cell order, within a cell in the study's order (mode, then parameter),
//! whatever the order in the file; each record is written back by the same CSV writer settings
//! as [`crate::study::results::write_results`]: a field read and written again is the same
//! bytes, so the merge is byte for byte the single-machine CSV.

use std::collections::BTreeMap;
use std::path::PathBuf;

use super::shard_file::ShardFile;
use crate::study::results::RESULT_HEADER;

/// Why shards do not merge.
#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    /// No file.
    #[error("no shard file given")]
    Empty,
    /// Different fingerprints.
    #[error(
        "{file}: fingerprint {found} differs from {first_file}'s {expected}: the shards come from different study files, models or jointid versions; rerun the odd ones"
    )]
    Fingerprint {
        /// The odd file.
        file: PathBuf,
        /// Its fingerprint, study name and tool.
        found: String,
        /// The first file.
        first_file: PathBuf,
        /// The first file's fingerprint, study name and tool.
        expected: String,
    },
    /// Different N, cells or rows per cell.
    #[error(
        "{file}: shard {found} of {cells} cell(s) does not match {first_file} (shard {expected}): every shard must come from the same `--shard K/N` split"
    )]
    Split {
        /// The odd file.
        file: PathBuf,
        /// Its K/N.
        found: String,
        /// Its cell count.
        cells: usize,
        /// The first file.
        first_file: PathBuf,
        /// The first file's K/N.
        expected: String,
    },
    /// A row in a shard that does not own its cell.
    #[error(
        "{file}:{line}: cell {cell} belongs to shard {owner}/{count}, not to this file's shard {shard}/{count}"
    )]
    Foreign {
        /// The file.
        file: PathBuf,
        /// Line.
        line: u64,
        /// The cell.
        cell: usize,
        /// Its shard.
        owner: usize,
        /// This file's shard.
        shard: usize,
        /// N.
        count: usize,
    },
    /// A cell in two files.
    #[error("cell {cell} is in both {first} and {second} (shard {shard}/{count} given twice?)")]
    Duplicate {
        /// The cell.
        cell: usize,
        /// The first file holding it.
        first: PathBuf,
        /// The second.
        second: PathBuf,
        /// Its shard.
        shard: usize,
        /// N.
        count: usize,
    },
    /// A cell with the wrong number of rows.
    #[error(
        "{file}: cell {cell} has {found} row(s), every cell has {expected}: the file is damaged; rerun its shard"
    )]
    Rows {
        /// The file.
        file: PathBuf,
        /// The cell.
        cell: usize,
        /// Rows found.
        found: usize,
        /// Rows expected.
        expected: usize,
    },
    /// Cells in no file.
    #[error("{count} cell(s) missing, in no file given:\n{list}", count = missing.len(), list = missing_by_shard(missing))]
    Missing {
        /// (cell, shard, N) of every missing cell.
        missing: Vec<(usize, usize, usize)>,
    },
    /// Writing into memory failed (not expected).
    #[error("cannot write the merged CSV: {0}")]
    Write(#[from] std::io::Error),
}

/// One line per shard with missing cells.
fn missing_by_shard(missing: &[(usize, usize, usize)]) -> String {
    let mut by: BTreeMap<(usize, usize), Vec<String>> = BTreeMap::new();
    for &(cell, k, n) in missing {
        by.entry((k, n)).or_default().push(cell.to_string());
    }
    by.iter()
        .map(|((k, n), cells)| {
            format!(
                "  shard {k}/{n}: cell(s) {} (run `jointid study S.toml --shard {k}/{n}`)",
                cells.join(", ")
            )
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// Merges `shards` into the bytes of the study's result CSV, or says why they do not merge.
pub fn merge(shards: &[ShardFile]) -> Result<Vec<u8>, MergeError> {
    let first = shards.first().ok_or(MergeError::Empty)?;
    let h0 = &first.header;
    for s in &shards[1..] {
        let h = &s.header;
        if h.fingerprint != h0.fingerprint {
            let describe = |h: &super::ShardHeader| {
                format!("{} (study {}, {})", h.fingerprint, h.study, h.tool)
            };
            return Err(MergeError::Fingerprint {
                file: s.file.clone(),
                found: describe(h),
                first_file: first.file.clone(),
                expected: describe(h0),
            });
        }
        if h.spec.count != h0.spec.count
            || h.assignment != h0.assignment
            || h.rows_per_cell != h0.rows_per_cell
            || h.modes != h0.modes
            || h.params != h0.params
        {
            return Err(MergeError::Split {
                file: s.file.clone(),
                found: h.spec.to_string(),
                cells: h.assignment.len(),
                first_file: first.file.clone(),
                expected: h0.spec.to_string(),
            });
        }
    }
    let count = h0.spec.count;
    // Rows of every cell, and the file that holds it.
    let mut cells: BTreeMap<usize, (usize, Vec<&super::shard_file::ShardRow>)> = BTreeMap::new();
    for (f, s) in shards.iter().enumerate() {
        for row in &s.rows {
            let owner = h0.assignment[row.cell];
            if owner != s.header.spec.index {
                return Err(MergeError::Foreign {
                    file: s.file.clone(),
                    line: row.line,
                    cell: row.cell,
                    owner,
                    shard: s.header.spec.index,
                    count,
                });
            }
            let entry = cells.entry(row.cell).or_insert((f, Vec::new()));
            if entry.0 != f {
                return Err(MergeError::Duplicate {
                    cell: row.cell,
                    first: shards[entry.0].file.clone(),
                    second: s.file.clone(),
                    shard: owner,
                    count,
                });
            }
            entry.1.push(row);
        }
    }
    let missing: Vec<(usize, usize, usize)> = (0..h0.assignment.len())
        .filter(|c| !cells.contains_key(c))
        .map(|c| (c, h0.assignment[c], count))
        .collect();
    if !missing.is_empty() {
        return Err(MergeError::Missing { missing });
    }
    let mut out = Vec::new();
    {
        let mut w = csv::Writer::from_writer(&mut out);
        w.write_record(RESULT_HEADER)
            .map_err(std::io::Error::from)?;
        for (&cell, (f, rows)) in &mut cells {
            if rows.len() != h0.rows_per_cell {
                return Err(MergeError::Rows {
                    file: shards[*f].file.clone(),
                    cell,
                    found: rows.len(),
                    expected: h0.rows_per_cell,
                });
            }
            rows.sort_by_key(|row| row.key);
            for row in rows.iter() {
                w.write_record(&row.record).map_err(std::io::Error::from)?;
            }
        }
        w.flush()?;
    }
    Ok(out)
}
