//! The Matrix Market writer: a symmetric matrix as a `coordinate real symmetric` file, values
//! in shortest round-trip form so that the reader gives back the same bits.

use std::io::{self, Write};

/// Writes a symmetric matrix of size `size` as a `coordinate real symmetric` file: every
/// `comments` line after `% `, then the entries `(row, col, value)` (0-based, row >= col) in
/// the given order, 1-based, values in shortest round-trip form.
pub fn write(
    out: &mut dyn Write,
    size: usize,
    lower: &[(usize, usize, f64)],
    comments: &[String],
) -> io::Result<()> {
    write_entries(out, size, lower.len(), lower.iter().copied(), comments)
}

/// [`write`](fn@write) from an iterator of `count` entries (a large matrix written as it is
/// read from its store, never copied).
pub fn write_entries(
    out: &mut dyn Write,
    size: usize,
    count: usize,
    lower: impl Iterator<Item = (usize, usize, f64)>,
    comments: &[String],
) -> io::Result<()> {
    writeln!(out, "%%MatrixMarket matrix coordinate real symmetric")?;
    for c in comments {
        writeln!(out, "% {c}")?;
    }
    writeln!(out, "{size} {size} {count}")?;
    let mut written = 0;
    for (i, j, v) in lower {
        debug_assert!(i >= j && i < size);
        writeln!(out, "{} {} {v:e}", i + 1, j + 1)?;
        written += 1;
    }
    debug_assert_eq!(written, count);
    Ok(())
}

#[cfg(test)]
mod tests {
    //! Checked by reading the output back with the module's reader, bit for bit.
    use super::*;
    use crate::model::matrix_market::read;
    use std::path::Path;

    #[test]
    fn written_files_read_back_bit_for_bit() {
        let lower = vec![
            (0, 0, 0.1 + 0.2),
            (2, 0, -1.234_567_890_123_456_7e-300),
            (2, 2, 6.02214076e23),
            (1, 1, f64::MIN_POSITIVE),
            (1, 0, 5e-324),
            (2, 1, -0.0),
        ];
        let mut bytes = Vec::new();
        write(&mut bytes, 3, &lower, &["K of a test".to_string()]).unwrap();
        let back = read(bytes.as_slice(), Path::new("K.mtx")).unwrap();
        assert_eq!(back.size, 3);
        assert_eq!(back.entries.len(), lower.len());
        for (a, b) in back.entries.iter().zip(&lower) {
            assert_eq!((a.0, a.1, a.2.to_bits()), (b.0, b.1, b.2.to_bits()));
        }
    }
}
