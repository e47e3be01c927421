//! Plain aligned text tables for the terminal.

use std::io::{self, Write};

/// Writes `header` and `rows` as right-aligned columns separated by two spaces.
pub fn write_table(out: &mut dyn Write, header: &[&str], rows: &[Vec<String>]) -> io::Result<()> {
    let mut widths: Vec<usize> = header.iter().map(|h| h.chars().count()).collect();
    for row in rows {
        for (w, cell) in widths.iter_mut().zip(row) {
            *w = (*w).max(cell.chars().count());
        }
    }
    let line = |cells: Vec<&str>| {
        cells
            .iter()
            .zip(&widths)
            .map(|(c, w)| format!("{c:>w$}"))
            .collect::<Vec<_>>()
            .join("  ")
    };
    writeln!(out, "{}", line(header.to_vec()))?;
    for row in rows {
        writeln!(out, "{}", line(row.iter().map(String::as_str).collect()))?;
    }
    Ok(())
}

/// A number in engineering-friendly scientific notation with 4 significant digits.
pub fn sci(x: f64) -> String {
    if x == 0.0 {
        "0".to_string()
    } else {
        format!("{x:.3e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_align_right() {
        let mut buf = Vec::new();
        write_table(&mut buf, &["a", "long"], &[vec!["123".into(), "x".into()]]).unwrap();
        assert_eq!(String::from_utf8(buf).unwrap(), "  a  long\n123     x\n");
        assert_eq!(sci(2.0e6), "2.000e6");
    }
}
