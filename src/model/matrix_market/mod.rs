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

mod line;
mod write;

pub use line::MAX_SIZE;
pub use write::{write, write_entries};

use std::collections::HashMap;
use std::io;
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

/// Bytes read at a time: the lines are read where they lie in this buffer, never copied
/// (a line longer than it grows it, up to the line limit of the reader's bounds).
const BLOCK: usize = 1 << 20;

/// Reads Matrix Market text from `reader` (within [`crate::input::bounded::TABLE`]'s limits);
/// `file` names it in errors.
pub fn read(reader: impl io::Read, file: &Path) -> Result<LowerEntries, MatrixMarketError> {
    read_in_blocks(reader, file, BLOCK)
}

/// [`read`] with a first buffer of `block` bytes (the tests make lines cross its ends).
fn read_in_blocks(
    reader: impl io::Read,
    file: &Path,
    block: usize,
) -> Result<LowerEntries, MatrixMarketError> {
    let mut reader = crate::input::bounded::Bounded::new(reader, crate::input::bounded::TABLE);
    let mut reading = Reading::new(file);
    let mut buf = vec![0u8; block.max(1)];
    let mut filled = 0;
    loop {
        if filled == buf.len() {
            buf.resize(2 * buf.len(), 0);
        }
        let n = match io::Read::read(&mut reader, &mut buf[filled..]) {
            Ok(n) => n,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
            Err(cause) => return Err(reading.read_error(cause)),
        };
        let end = filled + n;
        if n == 0 {
            if end > 0 {
                reading.line(&buf[..end])?;
            }
            return reading.finish();
        }
        // The complete lines: up to the last newline of the buffer.
        let Some(last) = buf[filled..end].iter().rposition(|&b| b == b'\n') else {
            filled = end;
            continue;
        };
        let last = filled + last;
        let mut start = 0;
        while start <= last {
            let stop = start
                + buf[start..=last]
                    .iter()
                    .position(|&b| b == b'\n')
                    .expect("a newline at `last`");
            reading.line(&buf[start..stop])?;
            start = stop + 1;
        }
        buf.copy_within(last + 1..end, 0);
        filled = end - last - 1;
    }
}

/// Where the reading of a file stands.
enum Stage {
    /// Before the header line.
    Header,
    /// Before the size line (comments and blank lines skipped).
    Size,
    /// The entry lines.
    Entries,
}

/// A file being read, line by line.
struct Reading<'a> {
    file: &'a Path,
    /// Lines so far (the 1-based number of the last one).
    lines: usize,
    stage: Stage,
    general: bool,
    size: usize,
    declared: usize,
    entries: Vec<(usize, usize, f64)>,
    /// The line of each entry (`general` files: their symmetry error names it).
    at_line: Vec<usize>,
    /// Entry lines past the declared count.
    excess: usize,
}

impl<'a> Reading<'a> {
    fn new(file: &'a Path) -> Self {
        Reading {
            file,
            lines: 0,
            stage: Stage::Header,
            general: false,
            size: 0,
            declared: 0,
            entries: Vec::new(),
            at_line: Vec::new(),
            excess: 0,
        }
    }

    fn error(&self, line: usize, message: String) -> MatrixMarketError {
        MatrixMarketError::Line {
            file: self.file.to_path_buf(),
            line,
            message: crate::input::safe::clip_quotes(message),
        }
    }

    fn read_error(&self, cause: io::Error) -> MatrixMarketError {
        MatrixMarketError::Read {
            file: self.file.to_path_buf(),
            cause,
        }
    }

    /// The next line, `bytes` without its newline.
    fn line(&mut self, bytes: &[u8]) -> Result<(), MatrixMarketError> {
        self.lines += 1;
        if matches!(self.stage, Stage::Entries) && self.entries.len() < self.declared {
            if let Some(e) = line::fast_entry(bytes, self.size, self.general) {
                self.push(e);
                return Ok(());
            }
        }
        let text = std::str::from_utf8(bytes).map_err(|_| {
            self.read_error(io::Error::new(
                io::ErrorKind::InvalidData,
                "stream did not contain valid UTF-8",
            ))
        })?;
        let t = text.trim();
        match self.stage {
            Stage::Header => {
                self.general = line::is_general(text).map_err(|m| self.error(self.lines, m))?;
                self.stage = Stage::Size;
            }
            _ if t.is_empty() || t.starts_with('%') => {}
            Stage::Size => {
                (self.size, self.declared) =
                    line::size_line(t).map_err(|m| self.error(self.lines, m))?;
                self.entries = Vec::with_capacity(self.declared.min(1 << 24));
                self.stage = Stage::Entries;
            }
            Stage::Entries if self.entries.len() == self.declared => self.excess += 1,
            Stage::Entries => {
                let e = line::entry(t, self.size, self.general)
                    .map_err(|m| self.error(self.lines, m))?;
                self.push(e);
            }
        }
        Ok(())
    }

    fn push(&mut self, e: (usize, usize, f64)) {
        self.entries.push(e);
        if self.general {
            self.at_line.push(self.lines);
        }
    }

    /// The matrix, once every line is read.
    fn finish(self) -> Result<LowerEntries, MatrixMarketError> {
        match self.stage {
            Stage::Header => {
                return Err(self.error(1, format!("the file is empty: {}", line::HEADER_ALLOWED)));
            }
            Stage::Size => {
                return Err(self.error(
                    2,
                    "the file ends before the size line `rows columns entries`".into(),
                ));
            }
            Stage::Entries => {}
        }
        let found = self.entries.len() + self.excess;
        if found != self.declared {
            return Err(MatrixMarketError::Count {
                file: self.file.to_path_buf(),
                declared: self.declared,
                found,
            });
        }
        let entries = if self.general {
            symmetric_part(&self.entries, &self.at_line, self.file)?
        } else {
            self.entries
        };
        Ok(LowerEntries {
            size: self.size,
            entries,
        })
    }
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

    /// Lines that cross the ends of the read buffer, CRLF line ends, a last line without its
    /// newline, comments between entries, exponents in every form: the same matrix whatever
    /// the buffer's size, and an error on the same line.
    #[test]
    fn lines_across_the_buffer_read_the_same_at_every_block_size() {
        let text = "%%MatrixMarket matrix coordinate real symmetric\r\n% K\r\n  \r\n3 3 6\r\n1 1 1.5E+04\r\n% between\r\n2 1 -2.5e-3\r\n2 2 7\r\n3 2 +1e0\r\n3   3\t.25\r\n3 3 1.0000000000000002";
        let whole = read_str(text).unwrap();
        assert_eq!(whole.size, 3);
        assert_eq!(
            whole.entries,
            vec![
                (0, 0, 1.5e4),
                (1, 0, -2.5e-3),
                (1, 1, 7.0),
                (2, 1, 1.0),
                (2, 2, 0.25),
                (2, 2, 1.0000000000000002)
            ]
        );
        let bad = text.replace("2 2 7", "2 2 7e");
        for block in [1, 2, 3, 5, 7, 16, 64, 1 << 20] {
            let m = read_in_blocks(text.as_bytes(), Path::new("K.mtx"), block).unwrap();
            assert_eq!(m, whole, "block {block}");
            let e = read_in_blocks(bad.as_bytes(), Path::new("K.mtx"), block).unwrap_err();
            assert_eq!(
                e.to_string(),
                "K.mtx:8: value = `7e` at (2, 2) is invalid: it must be a finite number",
                "block {block}"
            );
        }
    }

    #[test]
    fn integer_and_pattern_headers() {
        let m = read_str("%%MatrixMarket matrix coordinate integer symmetric\n1 1 1\n1 1 3\n");
        assert_eq!(m.unwrap().entries, vec![(0, 0, 3.0)]);
        let e = read_str("%%MatrixMarket matrix coordinate pattern symmetric\n1 1 1\n1 1\n");
        assert_eq!(
            e.unwrap_err().to_string(),
            "K.mtx:1: header `%%MatrixMarket matrix coordinate pattern symmetric` is invalid: a `pattern` file has no values (a stiffness or mass matrix needs them); the first line must be `%%MatrixMarket matrix coordinate real symmetric` (or `integer` for `real`, `general` for `symmetric`)"
        );
        let bytes = b"%%MatrixMarket matrix coordinate real symmetric\n2 2 1\n2 1 1\xff\n";
        let e = read(&bytes[..], Path::new("K.mtx"));
        assert_eq!(
            e.unwrap_err().to_string(),
            "K.mtx: cannot read the file: stream did not contain valid UTF-8"
        );
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
