//! Matrix Market files of real symmetric matrices: reader and writer.
//!
//! The format is NIST's "The Matrix Market Exchange Formats: Initial Design" (Boisvert, Pozo,
//! Remington, 1996). Read here: the coordinate format of a square real (or integer) matrix,
//!
//! ```text
//! %%MatrixMarket matrix coordinate real symmetric
//! % comments
//! 2 2 3                      rows, columns, entries
//! 1 1 2.0e4                  row, column (1-based), value
//! 2 1 -1.0e4
//! 2 2 1.0e4
//! ```
//!
//! - `symmetric`: the file stores the lower triangle (row >= column), as the format defines;
//!   an entry above the diagonal is an error (it would otherwise be counted twice).
//! - `general`: both triangles; the matrix must be symmetric: |a_ij - a_ji| <= 1e-10 max |a|
//!   (round-off of an assembly in another order passes, a non-symmetric matrix does not); the
//!   lower triangle kept is (a_ij + a_ji) / 2, bitwise a_ij when the two are equal.
//! - Duplicate entries of a position are summed in file order, as a finite-element assembly
//!   (and scipy's `mmread(...).tocsr()`) does.
//! - Values must be finite; indices from 1 to the size; exactly the declared number of
//!   entries. `array`, `complex`, `pattern`, `skew-symmetric` and `hermitian` are refused.
//!
//! The writer ([`write()`]) stores the lower triangle of a symmetric matrix with every value
//! in Rust's shortest round-trip form (`{:e}`), so that reading back gives the same bits.

mod write;

pub use write::{write, write_entries};

use std::collections::HashMap;
use std::io::{self, BufRead};
use std::path::{Path, PathBuf};

/// Relative tolerance of the symmetry of a `general` file, against the largest |a_ij|.
pub const SYMMETRY_TOLERANCE: f64 = 1e-10;

/// A Matrix Market file that cannot be used, with where and why.
#[derive(Debug, thiserror::Error)]
pub enum MatrixMarketError {
    /// The file cannot be read.
    #[error("{file}: cannot read the file: {cause}")]
    Read {
        /// The file.
        file: PathBuf,
        /// The cause.
        cause: io::Error,
    },
    /// A line is invalid.
    #[error("{file}:{line}: {message}")]
    Line {
        /// The file.
        file: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What is wrong, with the value and what is allowed.
        message: String,
    },
    /// The file ends early or has more entries than declared.
    #[error("{file}: the size line declares {declared} entries, the file holds {found}")]
    Count {
        /// The file.
        file: PathBuf,
        /// Declared entries.
        declared: usize,
        /// Entry lines found.
        found: usize,
    },
    /// A `general` file whose matrix is not symmetric.
    #[error(
        "{file}:{line}: the matrix is not symmetric: a({row},{col}) = {value:e} but a({col},{row}) = {mirror:e} (a `general` file must hold a symmetric matrix, |a_ij - a_ji| <= {SYMMETRY_TOLERANCE:e} max |a|)"
    )]
    NotSymmetric {
        /// The file.
        file: PathBuf,
        /// Line of the (first) entry at (row, col).
        line: usize,
        /// 1-based row.
        row: usize,
        /// 1-based column.
        col: usize,
        /// a(row, col), duplicates summed.
        value: f64,
        /// a(col, row), duplicates summed (0 when absent).
        mirror: f64,
    },
}

/// A symmetric matrix read from a file: its size and its lower-triangle entries
/// `(row, col, value)`, 0-based, row >= col, in file order (duplicates kept, to be summed).
#[derive(Debug, Clone, PartialEq)]
pub struct LowerEntries {
    /// N (the matrix is N x N).
    pub size: usize,
    /// Entries on and below the diagonal.
    pub entries: Vec<(usize, usize, f64)>,
}

impl LowerEntries {
    /// Both triangles, in file order: a diagonal entry once, an off-diagonal entry (i, j) as
    /// its mirror (j, i) above the diagonal, then itself.
    pub fn both_triangles(&self) -> Vec<(usize, usize, f64)> {
        let mut out = Vec::with_capacity(2 * self.entries.len());
        for &(i, j, v) in &self.entries {
            if i != j {
                out.push((j, i, v));
            }
            out.push((i, j, v));
        }
        out
    }
}

/// Reads a Matrix Market file (see the module docs).
pub fn from_path(path: &Path) -> Result<LowerEntries, MatrixMarketError> {
    let file = std::fs::File::open(path).map_err(|cause| MatrixMarketError::Read {
        file: path.to_path_buf(),
        cause,
    })?;
    read(file, path)
}

/// What the header line may be.
const HEADER_ALLOWED: &str = "the first line must be `%%MatrixMarket matrix coordinate real symmetric` (or `integer` for `real`, `general` for `symmetric`)";

/// Whether the header line declares a `general` matrix (else `symmetric`); the message when
/// it is not a header this reader takes.
fn is_general(header: &str) -> Result<bool, String> {
    let words: Vec<String> = header
        .split_whitespace()
        .map(str::to_ascii_lowercase)
        .collect();
    match words.iter().map(String::as_str).collect::<Vec<_>>()[..] {
        [
            "%%matrixmarket",
            "matrix",
            "coordinate",
            "real" | "integer",
            "symmetric",
        ] => Ok(false),
        [
            "%%matrixmarket",
            "matrix",
            "coordinate",
            "real" | "integer",
            "general",
        ] => Ok(true),
        _ => Err(format!(
            "header `{}` is invalid: {HEADER_ALLOWED}",
            header.trim()
        )),
    }
}

/// The largest matrix read, in rows (a model far beyond what the solvers handle).
pub const MAX_SIZE: usize = 10_000_000;

/// The size N and the declared number of entries of the size line `t` (trimmed, not a
/// comment); the message when it is not `N N entries`.
fn size_line(t: &str) -> Result<(usize, usize), String> {
    let fields: Vec<&str> = t.split_whitespace().collect();
    let parsed: Vec<Option<usize>> = fields.iter().map(|f| f.parse().ok()).collect();
    match parsed[..] {
        [Some(r), Some(c), Some(_)] if r == c && r > MAX_SIZE => Err(format!(
            "size `{t}` is invalid: the matrix is {r} x {c}; at most {MAX_SIZE} rows are read"
        )),
        [Some(r), Some(c), Some(nnz)] if r == c && r > 0 => Ok((r, nnz)),
        [Some(r), Some(c), Some(_)] if r != c => Err(format!(
            "size `{t}` is invalid: the matrix is {r} x {c}; it must be square"
        )),
        _ => Err(format!(
            "size line `{t}` is invalid: it must be `rows columns entries`, three integers, rows = columns > 0"
        )),
    }
}

/// The entry (row, column, value), 0-based, of the entry line `t` of a matrix of size
/// `size` (`general`: any triangle, else the lower one); the message when it is invalid.
fn entry(t: &str, size: usize, general: bool) -> Result<(usize, usize, f64), String> {
    let fields: Vec<&str> = t.split_whitespace().collect();
    let [ri, ci, vi] = fields[..] else {
        return Err(format!(
            "entry `{t}` is invalid: it must be `row column value`"
        ));
    };
    let index = |text: &str, name: &str| -> Result<usize, String> {
        match text.parse::<usize>() {
            Ok(k) if (1..=size).contains(&k) => Ok(k - 1),
            _ => Err(format!(
                "{name} = `{text}` is invalid: it must be an integer from 1 to {size}"
            )),
        }
    };
    let (i, j) = (index(ri, "row")?, index(ci, "column")?);
    let value = match vi.parse::<f64>() {
        Ok(v) if v.is_finite() => v,
        _ => {
            return Err(format!(
                "value = `{vi}` at ({ri}, {ci}) is invalid: it must be a finite number"
            ));
        }
    };
    if !general && i < j {
        return Err(format!(
            "entry ({ri}, {ci}) is above the diagonal: a `symmetric` file stores the lower triangle only (row >= column)"
        ));
    }
    Ok((i, j, value))
}

/// Reads Matrix Market text from `reader` (within [`crate::input::bounded::TABLE`]'s limits);
/// `file` names it in errors.
pub fn read(reader: impl io::Read, file: &Path) -> Result<LowerEntries, MatrixMarketError> {
    let err = |line: usize, message: String| MatrixMarketError::Line {
        file: file.to_path_buf(),
        line,
        message: crate::input::safe::clip_quotes(message),
    };
    let reader = io::BufReader::new(crate::input::bounded::Bounded::new(
        reader,
        crate::input::bounded::TABLE,
    ));
    let mut lines = reader.lines().enumerate().map(|(i, l)| (i + 1, l));
    let mut next = || -> Result<Option<(usize, String)>, MatrixMarketError> {
        match lines.next() {
            None => Ok(None),
            Some((n, Ok(text))) => Ok(Some((n, text))),
            Some((_, Err(cause))) => Err(MatrixMarketError::Read {
                file: file.to_path_buf(),
                cause,
            }),
        }
    };
    let Some((_, header)) = next()? else {
        return Err(err(1, format!("the file is empty: {HEADER_ALLOWED}")));
    };
    let general = is_general(&header).map_err(|message| err(1, message))?;
    // Size line: the first line that is neither a comment nor blank.
    let (size, declared) = loop {
        let Some((n, text)) = next()? else {
            return Err(err(
                2,
                "the file ends before the size line `rows columns entries`".into(),
            ));
        };
        let t = text.trim();
        if t.is_empty() || t.starts_with('%') {
            continue;
        }
        break size_line(t).map_err(|message| err(n, message))?;
    };
    let mut entries = Vec::with_capacity(declared.min(1 << 24));
    let mut at_line = Vec::with_capacity(declared.min(1 << 24));
    let mut excess = 0;
    while let Some((n, text)) = next()? {
        let t = text.trim();
        if t.is_empty() || t.starts_with('%') {
            continue;
        }
        if entries.len() == declared {
            excess += 1;
            continue;
        }
        entries.push(entry(t, size, general).map_err(|message| err(n, message))?);
        at_line.push(n);
    }
    if entries.len() + excess != declared {
        return Err(MatrixMarketError::Count {
            file: file.to_path_buf(),
            declared,
            found: entries.len() + excess,
        });
    }
    if general {
        entries = symmetric_part(&entries, &at_line, file)?;
    }
    Ok(LowerEntries { size, entries })
}

/// A symmetric matrix given by its coordinates in memory, both triangles (as a `general`
/// file holds them: checked for symmetry, duplicates summed), 0-based `(row, col, value)`;
/// `name` names the matrix in errors, and an entry's "line" there is its 1-based position
/// in `entries`.
pub fn from_coordinates(
    size: usize,
    entries: &[(usize, usize, f64)],
    name: &Path,
) -> Result<LowerEntries, MatrixMarketError> {
    let err = |at: usize, message: String| MatrixMarketError::Line {
        file: name.to_path_buf(),
        line: at,
        message,
    };
    for (at, &(i, j, v)) in entries.iter().enumerate() {
        if i >= size || j >= size {
            return Err(err(
                at + 1,
                format!(
                    "entry ({}, {}) is invalid: indices must be from 1 to the size {size}",
                    i + 1,
                    j + 1
                ),
            ));
        }
        if !v.is_finite() {
            return Err(err(
                at + 1,
                format!(
                    "value = {v} at ({}, {}) is invalid: it must be a finite number",
                    i + 1,
                    j + 1
                ),
            ));
        }
    }
    let at: Vec<usize> = (1..=entries.len()).collect();
    Ok(LowerEntries {
        size,
        entries: symmetric_part(entries, &at, name)?,
    })
}

/// The lower triangle of a `general` file's matrix, after the symmetry check.
fn symmetric_part(
    entries: &[(usize, usize, f64)],
    at_line: &[usize],
    file: &Path,
) -> Result<Vec<(usize, usize, f64)>, MatrixMarketError> {
    // Sums per position in file order, and the first line of each.
    let mut sums: HashMap<(usize, usize), (f64, usize)> = HashMap::new();
    let mut order: Vec<(usize, usize)> = Vec::new();
    for (&(i, j, v), &line) in entries.iter().zip(at_line) {
        sums.entry((i, j))
            .and_modify(|s| s.0 += v)
            .or_insert_with(|| {
                order.push((i, j));
                (0.0 + v, line)
            });
    }
    let largest = sums.values().map(|s| s.0.abs()).fold(0.0, f64::max);
    let mut out = Vec::new();
    for &(i, j) in &order {
        let (value, line) = sums[&(i, j)];
        let mirror = sums.get(&(j, i)).map_or(0.0, |s| s.0);
        if (value - mirror).abs() > SYMMETRY_TOLERANCE * largest {
            return Err(MatrixMarketError::NotSymmetric {
                file: file.to_path_buf(),
                line,
                row: i + 1,
                col: j + 1,
                value,
                mirror,
            });
        }
        if i >= j {
            let v = if i == j || value == mirror {
                value
            } else {
                0.5 * (value + mirror)
            };
            out.push((i, j, v));
        } else if !sums.contains_key(&(j, i)) {
            // Only reachable with a tiny value whose mirror is absent: keep it lower.
            out.push((j, i, 0.5 * value));
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    //! Fixtures are hand-written files with known matrices; the writer is checked by reading
    //! back its output bit for bit.
    use super::*;

    fn read_str(text: &str) -> Result<LowerEntries, MatrixMarketError> {
        read(text.as_bytes(), Path::new("K.mtx"))
    }

    #[test]
    fn symmetric_file_with_comments_duplicates_and_blank_lines() {
        let m = read_str(
            "%%MatrixMarket matrix coordinate real symmetric\n% a 2-DOF chain\n\n2 2 4\n1 1 1.0e4\n2 1 -1e4\n2 2 5e3\n2 2 5e3\n",
        )
        .unwrap();
        assert_eq!(m.size, 2);
        assert_eq!(
            m.entries,
            vec![(0, 0, 1e4), (1, 0, -1e4), (1, 1, 5e3), (1, 1, 5e3)]
        );
        assert_eq!(
            m.both_triangles()[..3],
            [(0, 0, 1e4), (0, 1, -1e4), (1, 0, -1e4)]
        );
    }

    #[test]
    fn general_symmetric_file_keeps_the_lower_triangle() {
        let m = read_str(
            "%%MatrixMarket matrix coordinate integer general\n2 2 4\n1 1 2\n1 2 -1\n2 1 -1\n2 2 1\n",
        )
        .unwrap();
        assert_eq!(m.entries, vec![(0, 0, 2.0), (1, 0, -1.0), (1, 1, 1.0)]);
        // Round-off asymmetry (assembly in another order) passes; the two are averaged.
        let m = read_str(
            "%%MatrixMarket matrix coordinate real general\n2 2 4\n1 1 2\n1 2 -1.0000000000002\n2 1 -1\n2 2 1\n",
        )
        .unwrap();
        assert_eq!(m.entries[1], (1, 0, 0.5 * (-1.0 + -1.0000000000002)));
    }

    #[test]
    fn every_bad_input_names_the_line_the_value_and_what_is_allowed() {
        let h = "%%MatrixMarket matrix coordinate real symmetric\n";
        let cases = [
            (
                "%%MatrixMarket matrix array real symmetric\n2 2\n".to_string(),
                "K.mtx:1: header `%%MatrixMarket matrix array real symmetric` is invalid: the first line must be `%%MatrixMarket matrix coordinate real symmetric` (or `integer` for `real`, `general` for `symmetric`)",
            ),
            (
                format!("{h}2 3 1\n1 1 1\n"),
                "K.mtx:2: size `2 3 1` is invalid: the matrix is 2 x 3; it must be square",
            ),
            (
                format!("{h}2 2 1\n3 1 1.0\n"),
                "K.mtx:3: row = `3` is invalid: it must be an integer from 1 to 2",
            ),
            (
                format!("{h}2 2 1\n1 0 1.0\n"),
                "K.mtx:3: column = `0` is invalid: it must be an integer from 1 to 2",
            ),
            (
                format!("{h}2 2 1\n1 1 NaN\n"),
                "K.mtx:3: value = `NaN` at (1, 1) is invalid: it must be a finite number",
            ),
            (
                format!("{h}2 2 1\n1 2 1.0\n"),
                "K.mtx:3: entry (1, 2) is above the diagonal: a `symmetric` file stores the lower triangle only (row >= column)",
            ),
            (
                format!("{h}2 2 2\n1 1 1.0\n"),
                "K.mtx: the size line declares 2 entries, the file holds 1",
            ),
            (
                format!("{h}2 2 1\n1 1 1.0\n2 2 1.0\n2 1 x\n"),
                "K.mtx: the size line declares 1 entries, the file holds 3",
            ),
            (
                "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 2 1.0\n2 1 1.5\n"
                    .to_string(),
                "K.mtx:3: the matrix is not symmetric: a(1,2) = 1e0 but a(2,1) = 1.5e0 (a `general` file must hold a symmetric matrix, |a_ij - a_ji| <= 1e-10 max |a|)",
            ),
        ];
        for (text, message) in cases {
            assert_eq!(read_str(&text).unwrap_err().to_string(), message);
        }
    }
}
